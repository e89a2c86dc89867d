; abi_checked_call.asm: calls a routine the way a hostile but legal caller
; would, and records every way the routine broke the System V ABI
; (after dav1d's / FFmpeg's checkasm_checked_call; written for this project).
;
; uint64_t sv_abi_checked_call(void *fn, uint64_t a1, uint64_t a2,
;                              uint64_t a3, uint64_t a4, uint64_t a5)
;   Calls fn(a1, a2, a3, a4, a5). Callers pass 32-bit int arguments with
;   garbage in the upper half (the ABI leaves it undefined), so a routine
;   that reads rsi where it should read esi computes garbage.
;   Before the call: rbx, rbp, r12-r15 hold the values of sv_abi_canary[6];
;   xmm0-xmm15 hold sv_abi_xmm_garbage (legal: they are caller-saved and
;   undefined on entry), so a routine that reads a register it never set
;   (appendix D's xmm5 at count 0) returns garbage instead of a lucky zero;
;   rax, r10, r11 hold garbage too.
;   After: sv_abi_failed gets one bit per broken promise:
;     bit 0..5  rbx, rbp, r12, r13, r14, r15 changed
;     bit 6     rsp differs from before the call
;     bit 7     the direction flag was left set
;   and rsp is restored from the saved copy, so a broken routine does not
;   take the test program down with it.
;
; Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.

%include "sv_abi.inc"

section .bss
align 16
global sv_abi_canary
global sv_abi_xmm_garbage
global sv_abi_failed
sv_abi_xmm_garbage: resb 16*16
sv_abi_canary:      resq 6
sv_abi_failed:      resd 1
                    resd 1
saved_rsp:          resq 1

FUNCTION sv_abi_checked_call
        push    rbp
        push    rbx
        push    r12
        push    r13
        push    r14
        push    r15
        sub     rsp, 8                  ; 6 pushes + return address: re-align to 16

        mov     r11, arg1q              ; the routine
        mov     rdi, rsi                ; shift the arguments down by one
        mov     rsi, rdx
        mov     rdx, rcx
        mov     rcx, r8
        mov     r8, r9

        lea     rax, [sv_abi_xmm_garbage]
%assign i 0
%rep 16
        movdqu  xmm %+ i, [rax + i*16]
%assign i i+1
%endrep
        mov     r9, [sv_abi_canary + 8]  ; garbage for the unused 6th argument
        mov     r10, [sv_abi_canary + 16]
        mov     rbx, [sv_abi_canary + 0]
        mov     rbp, [sv_abi_canary + 8]
        mov     r12, [sv_abi_canary + 16]
        mov     r13, [sv_abi_canary + 24]
        mov     r14, [sv_abi_canary + 32]
        mov     r15, [sv_abi_canary + 40]
        mov     [saved_rsp], rsp
        mov     rax, r15                ; garbage in rax (vector-arg count for varargs)

        call    r11

        xor     r10d, r10d
%macro CHECK_REG 3 ; register, canary slot, failure bit
        cmp     %1, [sv_abi_canary + %2*8]
        je      %%same
        or      r10d, 1 << %3
%%same:
%endmacro
        CHECK_REG rbx, 0, 0
        CHECK_REG rbp, 1, 1
        CHECK_REG r12, 2, 2
        CHECK_REG r13, 3, 3
        CHECK_REG r14, 4, 4
        CHECK_REG r15, 5, 5
        cmp     rsp, [saved_rsp]
        je      .rsp_same
        or      r10d, 1 << 6
        mov     rsp, [saved_rsp]
.rsp_same:
        pushfq
        pop     r11
        test    r11d, 1 << 10           ; DF
        jz      .df_clear
        or      r10d, 1 << 7
        cld
.df_clear:
        mov     [sv_abi_failed], r10d

        add     rsp, 8
        pop     r15
        pop     r14
        pop     r13
        pop     r12
        pop     rbx
        pop     rbp
        ret
ENDFUNCTION

; Deliberately broken routines, to prove the checker catches what it claims.
FUNCTION sv_abi_selftest_clobber_rbx_r13
        xor     ebx, ebx
        not     r13
        mov     eax, 7
        ret
ENDFUNCTION

FUNCTION sv_abi_selftest_leave_df_set
        std
        xor     eax, eax
        ret
ENDFUNCTION

; Returns its first int argument sign-extended with movsxd: correct.
FUNCTION sv_abi_selftest_return_arg1
        movsxd  rax, arg1d
        ret
ENDFUNCTION

; Returns its first argument read as 64 bits: wrong for an int argument;
; the garbage upper half shows up in the 64-bit result.
FUNCTION sv_abi_selftest_return_arg1_as_64bit
        mov     rax, arg1q
        ret
ENDFUNCTION
