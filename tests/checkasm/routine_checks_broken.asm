; routine_checks_broken.asm: kernels with a correct result and a broken
; ABI, for tests/checkasm/test_routine_checks.cpp, which asserts that the check
; library (src/check/routine_checks.h) reports them as failures of the
; right routine and variant while the others still pass. Each changes one
; thing the ABI forbids, then jumps to the paper's C, which computes the
; right count (and saves and restores the clobbered register with the
; clobbered value in it, if it uses it at all).
;
;   sv_broken_count_facing_clobber   CountFacing with the first callee-
;                                    saved GPR (rbx / ebx) inverted
;   sv_broken_count_facing_dirty_ymm CountFacing that leaves ymm1's upper
;                                    half dirty (AVX; no vzeroupper)
; Register map: each touches only what its name says.
; Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.

%include "abi_check_prelude.inc"

section .text
%ifndef SV_X86_32
default rel
%endif

extern SYM(sv_count_facing_c_ref)

; The tail call: through the PLT on elf64 (position-independent
; executables), direct elsewhere.
%macro JMP_C_REF 0
  %ifidn __OUTPUT_FORMAT__, elf64
        jmp     SYM(sv_count_facing_c_ref) wrt ..plt
  %else
        jmp     SYM(sv_count_facing_c_ref)
  %endif
%endmacro

GLOBAL_FUNC sv_broken_count_facing_clobber
%ifdef SV_X86_32
        not     ebx
%else
        not     rbx
%endif
        JMP_C_REF

GLOBAL_FUNC sv_broken_count_facing_dirty_ymm
%ifdef SV_X86_32
        vbroadcastss ymm1, [esp]        ; AVX (not AVX2); nonzero upper half
%else
        vbroadcastss ymm1, [rsp]
%endif
        JMP_C_REF
