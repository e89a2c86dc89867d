; abi_selfcheck.asm: deliberately broken routines, one per promise the ABI
; checker (src/check/abi_checked_call.asm) claims to check, and correct
; twins where a check could fire falsely. tests/checkasm/test_abi.cpp (and the
; standalone harness tests/checkasm/abi_selfcheck_main.c on win64 / elf32) assert
; that the checker reports exactly the right bit for each.
;
;   sv_abi_selftest_clobbers[i]   changes callee-saved GPR number i of the
;                                 ABI (order of sv_abi_failed bits 0-7);
;                                 sv_abi_selftest_clobber_count of them
;   sv_abi_selftest_clobber_xmm[i] (win64) changes xmm(6+i), i = 0..9
;   sv_abi_selftest_leave_df_set  returns with DF = 1
;   sv_abi_selftest_shift_sp      returns with the stack pointer 8 bytes off
;   sv_abi_selftest_dirty_ymm     writes ymm1's upper half, no vzeroupper
;   sv_abi_selftest_clean_ymm     the same, then vzeroupper (must pass)
;   sv_abi_selftest_write_canary  writes the first word above its stack
;                                 arguments (above the shadow space and 4
;                                 stack arguments on win64)
;   sv_abi_selftest_write_own_args writes all its stack arguments (and the
;                                 shadow space on win64): legal, must pass
;   sv_abi_selftest_return_arg1   int f(int): movsxd of the 32-bit argument
;   sv_abi_selftest_return_arg1_as_64bit  the same argument read as 64 bits
;   sv_abi_selftest_return_arg2_as_64bit  f(const void *, int): the int in
;                                 second place read as 64 bits
; Register map: each routine touches only what its name says, and eax/rax.
; Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.

%include "abi_check_prelude.inc"

section .text
%ifndef SV_X86_32
default rel
%endif

%macro CLOBBER 2 ; index, register
GLOBAL_FUNC sv_abi_selftest_clobber_%1
        not     %2
        xor     eax, eax
        ret
%endmacro

%ifdef SV_SYSV
  CLOBBER 0, rbx
  CLOBBER 1, rbp
  CLOBBER 2, r12
  CLOBBER 3, r13
  CLOBBER 4, r14
  CLOBBER 5, r15
  %define NCLOBBER 6
  %define STACK_ARG_BYTES 16            ; the checker passes 8 words: 2 on the stack
%elifdef SV_WIN64
  CLOBBER 0, rbx
  CLOBBER 1, rbp
  CLOBBER 2, rdi
  CLOBBER 3, rsi
  CLOBBER 4, r12
  CLOBBER 5, r13
  CLOBBER 6, r14
  CLOBBER 7, r15
  %define NCLOBBER 8
  %define STACK_ARG_BYTES 64            ; shadow space + 4 stack arguments
%else
  CLOBBER 0, ebx
  CLOBBER 1, esi
  CLOBBER 2, edi
  CLOBBER 3, ebp
  %define NCLOBBER 4
  %define STACK_ARG_BYTES 32            ; 8 argument words
%endif

%ifdef SV_X86_32
  %define SP esp
  %define WORD_BYTES 4
%else
  %define SP rsp
  %define WORD_BYTES 8
%endif

%ifdef SV_WIN64
%assign i 6
%rep 10
GLOBAL_FUNC sv_abi_selftest_clobber_xmm %+ i
        pcmpeqd xmm %+ i, xmm %+ i      ; all ones: never the random garbage
        xor     eax, eax
        ret
  %assign i i+1
%endrep
%endif

GLOBAL_FUNC sv_abi_selftest_leave_df_set
        std
        xor     eax, eax
        ret

; Pops its return address and one word more (it lies in the caller's
; stack arguments), and jumps back: the stack pointer ends one word higher
; than a ret would leave it.
GLOBAL_FUNC sv_abi_selftest_shift_sp
%ifdef SV_X86_32
        pop     ecx
        add     esp, 4
        jmp     ecx
%else
        pop     r11
        add     rsp, 8
        jmp     r11
%endif

GLOBAL_FUNC sv_abi_selftest_dirty_ymm
        vbroadcastss ymm1, [SP]         ; AVX (not AVX2); nonzero upper half
        xor     eax, eax
        ret

GLOBAL_FUNC sv_abi_selftest_clean_ymm
        vbroadcastss ymm1, [SP]
        vzeroupper
        xor     eax, eax
        ret

GLOBAL_FUNC sv_abi_selftest_write_canary
        mov     dword [SP + WORD_BYTES + STACK_ARG_BYTES], 0x5EC0DE
        xor     eax, eax
        ret

GLOBAL_FUNC sv_abi_selftest_write_own_args
%assign i 0
%rep STACK_ARG_BYTES / 4
        mov     dword [SP + WORD_BYTES + i*4], 0x0A0A0A0A + i
  %assign i i+1
%endrep
        xor     eax, eax
        ret

%ifdef SV_X86_32
GLOBAL_FUNC sv_abi_selftest_return_arg1
        mov     eax, [esp + 4]
        cdq
        ret
GLOBAL_FUNC sv_abi_selftest_return_arg1_as_64bit
        mov     eax, [esp + 4]
        cdq
        ret
GLOBAL_FUNC sv_abi_selftest_return_arg2_as_64bit
        mov     eax, [esp + 8]
        cdq
        ret
%else
  %ifdef SV_WIN64
    %define A1 rcx
    %define A1D ecx
    %define A2 rdx
  %else
    %define A1 rdi
    %define A1D edi
    %define A2 rsi
  %endif
GLOBAL_FUNC sv_abi_selftest_return_arg1
        movsxd  rax, A1D
        ret
GLOBAL_FUNC sv_abi_selftest_return_arg1_as_64bit
        mov     rax, A1
        ret
GLOBAL_FUNC sv_abi_selftest_return_arg2_as_64bit
        mov     rax, A2
        ret
%endif

; Tables for the tests: the clobbering routines by register number.
%ifdef SV_X86_32
section .data.rel.ro
  %define PTR dd
%else
section .data
  %define PTR dq
%endif
align 16
GLOBAL_DATA sv_abi_selftest_clobber_count
        dd      NCLOBBER
        dd      0
%ifndef SV_X86_32
        dd      0, 0
%endif
GLOBAL_DATA sv_abi_selftest_clobbers
%assign i 0
%rep NCLOBBER
        PTR     SYM(sv_abi_selftest_clobber_ %+ i)
  %assign i i+1
%endrep
