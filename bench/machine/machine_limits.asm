; machine_limits.asm: the throughput primitives behind `shadowvol bench
; --limits` (bench/machine/machine_limits.h): how many loads, gather lanes and
; bytes this core moves per TSC tick at best. They give each routine a
; floor: the ticks its unavoidable memory traffic needs (the loads of the
; elements it must look up, the bytes it must read and write), so that a
; kernel's distance from what the machine allows is a number, not a guess.
;
; Each routine runs a fixed, unrolled body ITERS times; the caller times the
; call and divides. The bodies are independent operations on addresses in
; one small buffer (L1-resident after the first pass), so nothing but the
; execution ports limits them:
;   svb_scalar_loads    32 movzx byte loads per iteration, each in its own
;                       cache line and at a different offset in it (64 j +
;                       4 (j mod 16): loads all at offset 0 of their lines
;                       measured ~10% slower here, a bank conflict)
;   svb_vector_loads    8 x 64-byte (zmm) or 32-byte (ymm) loads per
;                       iteration, walking a buffer of BYTES and wrapping
;                       (L1 or L2 bandwidth, by the buffer's size)
;   svb_vector_stores   8 x 64-byte or 32-byte stores per iteration, into
;                       the first 512 / 256 bytes of the buffer
;   svb_dependent_adds  32 adds per iteration, each on the one before
;                       (add rax, rdx with rdx = 1: a register operand, so
;                       no renamer folds the chain as it may fold
;                       immediates): one core cycle each, so the rate is
;                       the core's clock in cycles per TSC tick
;   svb_gather_lanes    8 independent vpgatherdd per iteration, 16 (zmm) or
;                       8 (ymm) lanes each, all in the buffer's first 1 KiB
;                       (each destination cleared first: a gather merges
;                       into it, which would chain the iterations)
; The zmm forms need AVX-512F, the ymm forms AVX2: the caller checks CPUID.
;
; void svb_scalar_loads(const uint8_t *buf, int64_t iters)              (2 KiB)
; void svb_dependent_adds(int64_t iters)
; void svb_vector_loads_zmm(const uint8_t *buf, int64_t iters, int64_t bytes)
; void svb_vector_loads_ymm(const uint8_t *buf, int64_t iters, int64_t bytes)
; void svb_vector_stores_zmm(uint8_t *buf, int64_t iters)               (512 B)
; void svb_vector_stores_ymm(uint8_t *buf, int64_t iters)               (256 B)
; void svb_gather_lanes_zmm(const uint8_t *buf, int64_t iters)          (1 KiB)
; void svb_gather_lanes_ymm(const uint8_t *buf, int64_t iters)          (1 KiB)
;   bytes: a multiple of 512, at least 512; buf 64-byte aligned.
;
; Register map: rdi the buffer, rsi iterations left, rcx the offset and rdx
;   the buffer's size (vector loads), eax the scalar loads' target (renamed:
;   no dependency), zmm/ymm0-7 load and gather targets, zmm/ymm0 the stored
;   zeros, zmm/ymm15 gather offsets, k1-k7 / ymm8 gather masks.
;
; Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.

%include "sv_abi.inc"

RODATA
align 64
svb_gather_offsets:                     ; lane i: byte 64 * i (dwords)
%assign i 0
%rep 16
        dd 64*i
%assign i i+1
%endrep

VEC_XMM
FUNC svb_scalar_loads, 2, 2, 0
        test    g1q, g1q
        jle     .done
.loop:
%assign j 0
%rep 32
        movzx   rvd, byte [g0q + 64*j + 4*(j % 16)]
%assign j j+1
%endrep
        dec     g1q
        jnz     .loop
.done:
        RET
ENDFUNC

FUNC svb_dependent_adds, 1, 3, 0
        test    g0q, g0q
        jle     .done
        xor     rvd, rvd
        mov     g2d, 1
.loop:
%rep 32
        add     rvq, g2q
%endrep
        dec     g0q
        jnz     .loop
.done:
        RET
ENDFUNC

; VECTOR_LOADS mov, reg, bytes: 8 loads of BYTES each per iteration with
; MOV (vmovdqu64 for zmm; vmovdqu for ymm, which needs no AVX-512VL),
; walking the buffer and wrapping at rdx bytes.
%macro VECTOR_LOADS 3
        test    g1q, g1q
        jle     %%done
        xor     g3d, g3d                ; offset in the buffer
%%loop:
%assign k 0
%rep 8
        %1      %2%[k], [g0q + g3q + k*%3]
%assign k k+1
%endrep
        add     g3q, 8*%3
        cmp     g3q, g2q
        jb      %%next
        xor     g3d, g3d                ; wrap (a predictable branch)
%%next:
        dec     g1q
        jnz     %%loop
%%done:
        RET
%endmacro

; VECTOR_STORES mov, reg, bytes: 8 stores of BYTES each per iteration, to
; the first 8 x BYTES of the buffer (zeros: the register is cleared with
; its xmm form).
%macro VECTOR_STORES 3
        test    g1q, g1q
        jle     %%done
        vpxor   xmm0, xmm0, xmm0
%%loop:
%assign k 0
%rep 8
        %1      [g0q + k*%3], %2 %+ 0
%assign k k+1
%endrep
        dec     g1q
        jnz     %%loop
%%done:
        RET
%endmacro

VEC_ZMM
FUNC svb_vector_loads_zmm, 3, 4, 8
        VECTOR_LOADS vmovdqu64, zmm, 64
ENDFUNC

VEC_YMM
FUNC svb_vector_loads_ymm, 3, 4, 8
        VECTOR_LOADS vmovdqu, ymm, 32
ENDFUNC

VEC_ZMM
FUNC svb_vector_stores_zmm, 2, 2, 1
        VECTOR_STORES vmovdqu64, zmm, 64
ENDFUNC

VEC_YMM
FUNC svb_vector_stores_ymm, 2, 2, 1
        VECTOR_STORES vmovdqu, ymm, 32
ENDFUNC

VEC_ZMM
FUNC svb_gather_lanes_zmm, 2, 2, 16
        test    g1q, g1q
        jle     .done
        vmovdqa64 zmm15, [svb_gather_offsets]
.loop:                                  ; the mask is consumed: set it each time
%assign k 0
%rep 8
%assign m (k % 7) + 1                   ; k1-k7: no chain through one mask
        kxnorw  k%[m], k0, k0           ; all ones
        vpxord  xmm%[k], xmm%[k], xmm%[k]  ; no merge with the last iteration
        vpgatherdd zmm%[k]{k%[m]}, [g0q + zmm15]
%assign k k+1
%endrep
        dec     g1q
        jnz     .loop
.done:
        RET
ENDFUNC

VEC_YMM
FUNC svb_gather_lanes_ymm, 2, 2, 16
        test    g1q, g1q
        jle     .done
        vmovdqa ymm15, [svb_gather_offsets]
.loop:                                  ; the mask register is cleared: refill it
%assign k 0
%rep 8
        vpcmpeqd ymm8, ymm8, ymm8
        vpxor   xmm%[k], xmm%[k], xmm%[k]   ; no merge with the last iteration
        vpgatherdd ymm%[k], [g0q + ymm15], ymm8
%assign k k+1
%endrep
        dec     g1q
        jnz     .loop
.done:
        RET
ENDFUNC
