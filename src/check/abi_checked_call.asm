; abi_checked_call.asm: calls a routine the way a hostile but legal caller
; would, and records every way the routine broke its platform's calling
; convention (the idea of dav1d's / FFmpeg's checkasm_checked_call; written
; for this project, nothing copied). One source for the test suite and for
; `shadowvol check`.
;
; uintptr_t sv_abi_checked_call(const void *fn, const uintptr_t args[8]);
;   Calls fn(args[0], ..., args[7]) with the platform's convention and
;   returns what fn returned in rax (eax on x86-32). Routines with fewer
;   parameters ignore the extra words. The C++ template checked_call()
;   (src/check/checked_call.h) builds args[] from fn's prototype: every
;   32-bit int parameter gets random garbage in bits 32-63.
;
; Before the call:
;   - every callee-saved GPR holds sv_abi_canary[i] (random per call);
;   - xmm0-15 (xmm0-7 on x86-32) hold sv_abi_xmm_garbage, loaded with
;     legacy-SSE movdqu, then vzeroupper (when the CPU has AVX) so that the
;     upper state is clean when the routine starts and anything dirty after
;     the call is the routine's doing;
;   - above the routine's stack arguments (above the shadow space and the
;     stack arguments on Windows; above the 8 argument words on x86-32) lie
;     SV_ABI_STACK_CANARIES words of sv_abi_stack_canary: the routine owns
;     its arguments but nothing above them.
; After the call, sv_abi_failed gets one bit per broken promise (the names
; per ABI are in src/check/abi_check.h, sv_abi_failure_names()):
;   bits 0-7   callee-saved GPRs, in this order:
;                SysV x86-64 (elf64, macho64): rbx rbp r12 r13 r14 r15
;                Windows x64 (win64):          rbx rbp rdi rsi r12 r13 r14 r15
;                x86-32 cdecl (elf32):         ebx esi edi ebp
;   bit 8      the stack pointer differs from before the call
;   bit 9      the direction flag was left set
;   bit 10     upper YMM state dirty: XGETBV(ecx=1) bit 2 (missing vzeroupper)
;   bit 11     upper ZMM state dirty: XGETBV(ecx=1) bit 6, ZMM_Hi256 (also
;              cleared by vzeroupper, so also a missing vzeroupper)
;   bit 12     a stack canary above the arguments was overwritten
;   bits 16-25 xmm6-xmm15 changed (win64 only: callee-saved there)
; sv_abi_xinuse_after receives the whole XINUSE word read after the call
; (0 when the CPU has no XGETBV ecx=1). Its bits 5 (opmask) and 7
; (Hi16_ZMM, zmm16-31) are not failures: vzeroupper clears neither, a
; routine that uses k registers legally leaves them non-zero, and glibc's
; EVEX string functions leave ymm16-31 in use on purpose (registers that
; legacy SSE cannot reach cost no transition).
; The checks of bits 10-11 run only when sv_abi_detect() found XGETBV ecx=1
; (CPUID.(EAX=0Dh,ECX=1):EAX bit 2, with OSXSAVE); vzeroupper runs only
; with AVX (CPUID.1:ECX bits 27 and 28 and XCR0 bits 1-2).
; The stack pointer is restored from a saved copy and DF is cleared, so a
; broken routine does not take the program down with it.
;
; Not reentrant: the saved stack pointer and the state are globals (the
; tests and `shadowvol check` call from one thread).
;
; uint32_t sv_abi_detect_cpu(void): fills sv_abi_flags (bit 0 AVX usable,
;   bit 1 XGETBV ecx=1 available, bit 2 SSE2) and returns it. Call once
;   before the first checked call (checked_call.h does).
;
; Does not include asm/sv_abi.inc: the checker must not depend on the layer
; it checks. Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.

%include "abi_check_prelude.inc"

%define STACK_CANARIES SV_ABI_STACK_CANARIES
%define F_AVX    1
%define F_XGETBV1 2
%define F_SSE2   4
%define BIT_SP      8
%define BIT_DF      9
%define BIT_YMM     10
%define BIT_ZMM     11
%define BIT_CANARY  12
%define BIT_XMM6    16

section .bss
alignb 16
GLOBAL_DATA sv_abi_xmm_garbage
        resb 16*16
GLOBAL_DATA sv_abi_canary
%ifdef SV_X86_32
        resd 8
%else
        resq 8
%endif
GLOBAL_DATA sv_abi_stack_canary
%ifdef SV_X86_32
        resd STACK_CANARIES
%else
        resq STACK_CANARIES
%endif
GLOBAL_DATA sv_abi_failed
        resd 1
GLOBAL_DATA sv_abi_flags
        resd 1
GLOBAL_DATA sv_abi_xinuse_after
        resd 1
        resd 1
saved_sp:   resq 1
saved_ret:  resq 1
alignb 16
saved_xmm:  resb 10*16               ; win64: the caller's xmm6-15

section .text

%ifndef SV_X86_32
; ======================================================================
; x86-64 (SysV and Windows)
; ======================================================================
default rel

; uint32_t sv_abi_detect_cpu(void): rbx is callee-saved everywhere, cpuid
; writes it.
GLOBAL_FUNC sv_abi_detect_cpu
        push    rbx
        xor     r8d, r8d                ; flags
        mov     eax, 1
        cpuid
        test    edx, 1 << 26
        jz      .no_sse2
        or      r8d, F_SSE2
.no_sse2:
        mov     r9d, ecx
        and     r9d, (1 << 27) | (1 << 28) ; OSXSAVE, AVX
        cmp     r9d, (1 << 27) | (1 << 28)
        jne     .done_avx               ; no XGETBV at all without OSXSAVE
        xor     ecx, ecx
        xgetbv                          ; XCR0
        and     eax, 6
        cmp     eax, 6                  ; the OS saves XMM and YMM state
        jne     .xgetbv1
        or      r8d, F_AVX
.xgetbv1:
        xor     eax, eax
        cpuid                           ; max basic leaf
        cmp     eax, 0xD
        jb      .done_avx
        mov     eax, 0xD
        mov     ecx, 1
        cpuid
        test    eax, 1 << 2             ; XGETBV with ecx = 1
        jz      .done_avx
        or      r8d, F_XGETBV1
.done_avx:
        mov     [SYM(sv_abi_flags)], r8d
        mov     eax, r8d
        pop     rbx
        ret

; Sets bit %3 of r10d unless %1 equals the qword at %2.
%macro CHECK_REG 3
        cmp     %1, [%2]
        je      %%same
        or      r10d, 1 << %3
%%same:
%endmacro

%ifdef SV_SYSV
  %define FRAME       (16 + 8*STACK_CANARIES + 8)  ; args 7-8, canaries, pad
  %define STACK_ARGS  0
  %define CANARY_AT   16
%else
  %define FRAME       (32 + 32 + 8*STACK_CANARIES + 8) ; shadow, args 5-8, canaries, pad
  %define STACK_ARGS  32
  %define CANARY_AT   64
%endif

GLOBAL_FUNC sv_abi_checked_call
        ; Our own caller's callee-saved registers.
        push    rbp
        push    rbx
        push    r12
        push    r13
        push    r14
        push    r15
%ifdef SV_WIN64
        push    rdi
        push    rsi
        mov     r11, rcx                ; fn
        mov     rax, rdx                ; args
        lea     r10, [saved_xmm]
  %assign i 6
  %rep 10
        movdqa  [r10 + (i-6)*16], xmm %+ i
    %assign i i+1
  %endrep
%else
        mov     r11, rdi                ; fn
        mov     rax, rsi                ; args
%endif
        ; 6 (SysV) or 8 (win64) pushes after the return address leave rsp
        ; 8 mod 16; FRAME is 8 mod 16, so rsp is 16-aligned at the call.
        sub     rsp, FRAME

        ; Stack arguments, then the canaries above them.
%ifdef SV_SYSV
        mov     r10, [rax + 48]
        mov     [rsp + STACK_ARGS], r10
        mov     r10, [rax + 56]
        mov     [rsp + STACK_ARGS + 8], r10
%else
  %assign i 0
  %rep 4
        mov     r10, [rax + 32 + i*8]
        mov     [rsp + STACK_ARGS + i*8], r10
    %assign i i+1
  %endrep
%endif
%assign i 0
%rep STACK_CANARIES
        mov     r10, [SYM(sv_abi_stack_canary) + i*8]
        mov     [rsp + CANARY_AT + i*8], r10
  %assign i i+1
%endrep

        ; Garbage in every xmm, with legacy-SSE loads; then a clean upper
        ; state, so the XINUSE read after the call sees only the routine.
        lea     r10, [SYM(sv_abi_xmm_garbage)]
%assign i 0
%rep 16
        movdqu  xmm %+ i, [r10 + i*16]
  %assign i i+1
%endrep
        test    dword [SYM(sv_abi_flags)], F_AVX
        jz      .clean
        vzeroupper
.clean:

        ; Register arguments, then the canaries in the callee-saved GPRs.
%ifdef SV_SYSV
        mov     rdi, [rax]
        mov     rsi, [rax + 8]
        mov     rdx, [rax + 16]
        mov     rcx, [rax + 24]
        mov     r8,  [rax + 32]
        mov     r9,  [rax + 40]
        mov     rbx, [SYM(sv_abi_canary) + 0]
        mov     rbp, [SYM(sv_abi_canary) + 8]
        mov     r12, [SYM(sv_abi_canary) + 16]
        mov     r13, [SYM(sv_abi_canary) + 24]
        mov     r14, [SYM(sv_abi_canary) + 32]
        mov     r15, [SYM(sv_abi_canary) + 40]
%else
        mov     rcx, [rax]
        mov     rdx, [rax + 8]
        mov     r8,  [rax + 16]
        mov     r9,  [rax + 24]
        mov     rbx, [SYM(sv_abi_canary) + 0]
        mov     rbp, [SYM(sv_abi_canary) + 8]
        mov     rdi, [SYM(sv_abi_canary) + 16]
        mov     rsi, [SYM(sv_abi_canary) + 24]
        mov     r12, [SYM(sv_abi_canary) + 32]
        mov     r13, [SYM(sv_abi_canary) + 40]
        mov     r14, [SYM(sv_abi_canary) + 48]
        mov     r15, [SYM(sv_abi_canary) + 56]
%endif
        mov     [saved_sp], rsp
        mov     r10, [SYM(sv_abi_canary) + 8]  ; garbage in the scratch GPRs
        mov     rax, [SYM(sv_abi_canary) + 40]

        call    r11

        mov     [saved_ret], rax
        xor     r10d, r10d
%ifdef SV_SYSV
        CHECK_REG rbx, SYM(sv_abi_canary) + 0, 0
        CHECK_REG rbp, SYM(sv_abi_canary) + 8, 1
        CHECK_REG r12, SYM(sv_abi_canary) + 16, 2
        CHECK_REG r13, SYM(sv_abi_canary) + 24, 3
        CHECK_REG r14, SYM(sv_abi_canary) + 32, 4
        CHECK_REG r15, SYM(sv_abi_canary) + 40, 5
%else
        CHECK_REG rbx, SYM(sv_abi_canary) + 0, 0
        CHECK_REG rbp, SYM(sv_abi_canary) + 8, 1
        CHECK_REG rdi, SYM(sv_abi_canary) + 16, 2
        CHECK_REG rsi, SYM(sv_abi_canary) + 24, 3
        CHECK_REG r12, SYM(sv_abi_canary) + 32, 4
        CHECK_REG r13, SYM(sv_abi_canary) + 40, 5
        CHECK_REG r14, SYM(sv_abi_canary) + 48, 6
        CHECK_REG r15, SYM(sv_abi_canary) + 56, 7
%endif
        cmp     rsp, [saved_sp]
        je      .sp_same
        or      r10d, 1 << BIT_SP
        mov     rsp, [saved_sp]
.sp_same:
        pushfq
        pop     r11
        test    r11d, 1 << 10           ; DF
        jz      .df_clear
        or      r10d, 1 << BIT_DF
        cld
.df_clear:
%assign i 0
%rep STACK_CANARIES
        mov     r11, [SYM(sv_abi_stack_canary) + i*8]
        cmp     r11, [rsp + CANARY_AT + i*8]
        je      .canary_ok %+ i
        or      r10d, 1 << BIT_CANARY
.canary_ok %+ i:
  %assign i i+1
%endrep
%ifdef SV_WIN64
        ; xmm6-15 are callee-saved here: compare with what went in.
        lea     r11, [SYM(sv_abi_xmm_garbage)]
  %assign i 6
  %rep 10
        pcmpeqb xmm %+ i, [r11 + i*16]
        pmovmskb eax, xmm %+ i
        cmp     eax, 0xFFFF
        je      .xmm_ok %+ i
        or      r10d, 1 << (BIT_XMM6 + i - 6)
.xmm_ok %+ i:
    %assign i i+1
  %endrep
%endif
        mov     dword [SYM(sv_abi_xinuse_after)], 0
        test    dword [SYM(sv_abi_flags)], F_XGETBV1
        jz      .xinuse_done
        mov     ecx, 1
        xgetbv                          ; edx:eax = XINUSE
        mov     [SYM(sv_abi_xinuse_after)], eax
        test    eax, 1 << 2
        jz      .ymm_clean
        or      r10d, 1 << BIT_YMM
.ymm_clean:
        test    eax, 1 << 6
        jz      .xinuse_done
        or      r10d, 1 << BIT_ZMM
.xinuse_done:
        test    dword [SYM(sv_abi_flags)], F_AVX
        jz      .no_vzu
        vzeroupper                      ; do not hand a dirty state on
.no_vzu:
        mov     [SYM(sv_abi_failed)], r10d
%ifdef SV_WIN64
        lea     r10, [saved_xmm]
  %assign i 6
  %rep 10
        movdqa  xmm %+ i, [r10 + (i-6)*16]
    %assign i i+1
  %endrep
%endif
        mov     rax, [saved_ret]
        add     rsp, FRAME
%ifdef SV_WIN64
        pop     rsi
        pop     rdi
%endif
        pop     r15
        pop     r14
        pop     r13
        pop     r12
        pop     rbx
        pop     rbp
        ret

%else
; ======================================================================
; x86-32 cdecl (elf32): every argument on the stack; eax, ecx, edx scratch;
; ebx, esi, edi, ebp callee-saved. Position-independent: the globals are
; reached through the GOT base in a register (no text relocations in PIE).
; ======================================================================
%macro GOT_BASE 1
        call    %%here
%%here: pop     %1
        add     %1, _GLOBAL_OFFSET_TABLE_ + $$ - %%here wrt ..gotpc
%endmacro
extern _GLOBAL_OFFSET_TABLE_
%define G(base, x) base + (x) wrt ..gotoff

GLOBAL_FUNC sv_abi_detect_cpu
        push    ebx
        push    esi
        push    edi
        GOT_BASE edi
        xor     esi, esi                ; flags
        ; CPUID itself exists on every CPU this project runs on (Pentium+).
        mov     eax, 1
        cpuid
        test    edx, 1 << 26
        jz      .no_sse2
        or      esi, F_SSE2
.no_sse2:
        and     ecx, (1 << 27) | (1 << 28)
        cmp     ecx, (1 << 27) | (1 << 28)
        jne     .done
        xor     ecx, ecx
        xgetbv
        and     eax, 6
        cmp     eax, 6
        jne     .xgetbv1
        or      esi, F_AVX
.xgetbv1:
        xor     eax, eax
        cpuid
        cmp     eax, 0xD
        jb      .done
        mov     eax, 0xD
        mov     ecx, 1
        cpuid
        test    eax, 1 << 2
        jz      .done
        or      esi, F_XGETBV1
.done:
        mov     [G(edi, sv_abi_flags)], esi
        mov     eax, esi
        pop     edi
        pop     esi
        pop     ebx
        ret

%define FRAME32 (32 + 4*STACK_CANARIES + 12) ; 8 argument words, canaries, pad

GLOBAL_FUNC sv_abi_checked_call
        push    ebx
        push    esi
        push    edi
        push    ebp
        ; entry esp is 12 mod 16 (i386 SysV keeps 16 at the call); 4 pushes
        ; keep it 12 mod 16, FRAME32 is 12 mod 16: 16-aligned at the call.
        sub     esp, FRAME32
        GOT_BASE ebx
        mov     ecx, [esp + FRAME32 + 16 + 4]  ; fn
        mov     eax, [esp + FRAME32 + 16 + 8]  ; args
%assign i 0
%rep 8
        mov     edx, [eax + i*4]
        mov     [esp + i*4], edx
  %assign i i+1
%endrep
%assign i 0
%rep STACK_CANARIES
        mov     edx, [G(ebx, sv_abi_stack_canary + i*4)]
        mov     [esp + 32 + i*4], edx
  %assign i i+1
%endrep
        test    dword [G(ebx, sv_abi_flags)], F_SSE2
        jz      .no_xmm
        lea     edx, [G(ebx, sv_abi_xmm_garbage)]
%assign i 0
%rep 8
        movdqu  xmm %+ i, [edx + i*16]
  %assign i i+1
%endrep
.no_xmm:
        test    dword [G(ebx, sv_abi_flags)], F_AVX
        jz      .clean
        vzeroupper
.clean:
        mov     [G(ebx, saved_sp)], esp
        mov     edx, [G(ebx, sv_abi_canary + 4)]   ; scratch garbage
        mov     eax, [G(ebx, sv_abi_canary + 8)]
        mov     esi, [G(ebx, sv_abi_canary + 4)]
        mov     edi, [G(ebx, sv_abi_canary + 8)]
        mov     ebp, [G(ebx, sv_abi_canary + 12)]
        mov     ebx, [G(ebx, sv_abi_canary + 0)]   ; the base register last

        call    ecx

        ; Only eax, ecx, edx are ours now; the mask goes to memory. The
        ; callee-saved registers are compared before anything touches them.
        push    eax                     ; the return value, briefly (ecx
        GOT_BASE ecx                    ;  is the base from here on)
        pop     dword [G(ecx, saved_ret)]
        mov     [G(ecx, saved_ret + 4)], edx
        xor     eax, eax
        cmp     ebx, [G(ecx, sv_abi_canary + 0)]
        je      .ebx_ok
        or      eax, 1 << 0
.ebx_ok:
        cmp     esi, [G(ecx, sv_abi_canary + 4)]
        je      .esi_ok
        or      eax, 1 << 1
.esi_ok:
        cmp     edi, [G(ecx, sv_abi_canary + 8)]
        je      .edi_ok
        or      eax, 1 << 2
.edi_ok:
        cmp     ebp, [G(ecx, sv_abi_canary + 12)]
        je      .ebp_ok
        or      eax, 1 << 3
.ebp_ok:
        ; The push/pop above is balanced, so esp compares as it came back.
        cmp     esp, [G(ecx, saved_sp)]
        je      .sp_same
        or      eax, 1 << BIT_SP
        mov     esp, [G(ecx, saved_sp)]
.sp_same:
        pushfd
        pop     edx
        test    edx, 1 << 10
        jz      .df_clear
        or      eax, 1 << BIT_DF
        cld
.df_clear:
%assign i 0
%rep STACK_CANARIES
        mov     edx, [G(ecx, sv_abi_stack_canary + i*4)]
        cmp     edx, [esp + 32 + i*4]
        je      .canary_ok %+ i
        or      eax, 1 << BIT_CANARY
.canary_ok %+ i:
  %assign i i+1
%endrep
        mov     [G(ecx, sv_abi_failed)], eax
        mov     dword [G(ecx, sv_abi_xinuse_after)], 0
        test    dword [G(ecx, sv_abi_flags)], F_XGETBV1
        jz      .xinuse_done
        push    ecx                     ; xgetbv takes ecx and writes edx:eax
        mov     ecx, 1
        xgetbv
        pop     ecx
        mov     [G(ecx, sv_abi_xinuse_after)], eax
        test    eax, 1 << 2
        jz      .ymm_clean
        or      dword [G(ecx, sv_abi_failed)], 1 << BIT_YMM
.ymm_clean:
        test    eax, 1 << 6
        jz      .xinuse_done
        or      dword [G(ecx, sv_abi_failed)], 1 << BIT_ZMM
.xinuse_done:
        test    dword [G(ecx, sv_abi_flags)], F_AVX
        jz      .no_vzu
        vzeroupper
.no_vzu:
        mov     eax, [G(ecx, saved_ret)]
        mov     edx, [G(ecx, saved_ret + 4)]
        add     esp, FRAME32
        pop     ebp
        pop     edi
        pop     esi
        pop     ebx
        ret
%endif
