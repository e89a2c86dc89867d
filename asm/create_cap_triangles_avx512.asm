; create_cap_triangles_avx512.asm: CreateCapTriangles with AVX-512
; (x86-64-v4).
;
; Computes: for each triangle j with facing[j] == 0 and doubled vertex
;   numbers i0, i1, i2: the near cap (i2, i1, i0) and the far cap
;   (i0+1, i1+1, i2+1), in triangle order, exactly section 7's C. Returns
;   the number of indices (6 per back-facing triangle).
; Approach: sixteen triangles per iteration, and instead of appendix F's
;   store-everything-and-advance, compress first:
;   1. three loads take the 48 indices; vpaddd doubles them; a vpermi2d
;      and a masked vpermt2d each transpose them into I0, I1, I2 (lane t:
;      triangle t's i0, i1, i2).
;   2. vptestnmb of the 16 facing bytes is the mask k1 of back-facing
;      triangles; vpcompressd (to a register: the memory form is several
;      times slower on AMD Zen) packs the m back-facing triangles of I0, I1,
;      I2 into lanes 0 .. m-1.
;   3. the 6m outputs are six vectors of 16 ints. Output int q belongs to
;      packed triangle j = q / 6 and takes I2, I1, I0, I0, I1, I2 for
;      r = q % 6 = 0..5; the three vectors of triangles 0-7 draw from
;      [I0 0-7 | I1 0-7] and I2, those of triangles 8-15 from
;      [I0 8-15 | I1 8-15] and I2: one vpermi2d each (constant indices),
;      then a vpxord adds the far cap's +1 (the numbers are even).
;   4. six plain 64-byte stores at the output pointer, which then advances
;      by 6m ints (popcnt). The stores write 96 ints from a position at
;      most 6 * (triangles before this block) into the output: never past
;      6 * numTriangles, the contract's room. The last 1-15 triangles run
;      the same code with masks: zero-masked loads read exactly the
;      indices and facing bytes left, masked stores write exactly 6m ints.
;   No branch depends on the facing data.
;
; int sv_create_cap_triangles_avx512(int *shadowIndices, const uint8_t *facing,
;                                    const int *indices, int numIndices)
;
; Register map (asm/sv_abi.inc names; rv = rax):
;   g5q   shadowIndices (for the return value); g4q output pointer
;   g1q  facing, g2q indices: both advanced per block
;   rvq  triangles left (numIndices / 3)
;   zmm0-zmm2 the 48 indices (doubled); zmm3-zmm5 I0, I1, I2 (then packed);
;   zmm6, zmm7 the two 32-entry tables' first halves; zmm8 facing bytes;
;   zmm9-zmm14 the six output vectors; xmm15 sixteen bytes of 0xFF;
;   zmm16-zmm18 transpose indices; zmm19-zmm21 the +1 patterns;
;   zmm22-zmm27 output indices
;   k1 back-facing triangles; k2, k3 the transpose's second-source lanes;
;   k4-k7 tail masks; g3q, g6q, g7q scratch
;
; Contracts: facing bytes 0 or 1 (only 0 is back-facing, as the C's
;   `if (facing[j]) continue`); numIndices a multiple of 3 (the routine
;   takes numIndices / 3 whole triangles and reads nothing past them);
;   vertex numbers in [0, 2^30) (doubled in 32 bits); output room for
;   2 * numIndices ints, written past the returned count with garbage
;   but never past 2 * numIndices. No alignment anywhere.
;   numIndices >= 0 (negative returns 0, touches nothing).
;
; Cost: not kept here (figures go stale); `shadowvol bench` measures it
;   on the machine at hand and docs/BENCHMARK.md has the current table.
;
; Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.

%include "sv_abi.inc"

RODATA
; Transpose: lane t of I<c> is index 3t + c of the 48. The first vpermi2d
; takes lanes 3t + c < 32 from zmm0|zmm1; the masked vpermt2d (k2, k3) then
; takes the others from zmm2 (indices 16 + (3t + c - 32) select the second
; table). One constant serves both steps (vpermi2d ignores the lanes it
; gets wrong; the masked step overwrites them).
align 64
cap_tr:
%assign c 0
%rep 3
%assign t 0
%rep 16
%assign q 3*t + c
%if q < 32
        dd q
%else
        dd 16 + q - 32
%endif
%assign t t+1
%endrep
%assign c c+1
%endrep
; Output vector k, lane l: q = 16k + l, packed triangle j = q / 6,
; r = q % 6 takes I2, I1, I0, I0, I1, I2. Tables: [I0 | I1] halves for
; j mod 8 (entries 0-7 and 8-15), I2 as the second table (16 + j).
cap_out:
%assign k 0
%rep 6
%assign l 0
%rep 16
%assign q 16*k + l
%assign j q / 6
%assign r q % 6
%if r == 2 || r == 3
        dd (j % 8)
%elif r == 1 || r == 4
        dd 8 + (j % 8)
%else
        dd 16 + j
%endif
%assign l l+1
%endrep
%assign k k+1
%endrep
; +1 (xor 1: the doubled numbers are even) for r = 3, 4, 5. Vector k
; starts at r = 16k % 6 = 0, 4, 2, 0, 4, 2: three patterns.
cap_plus1:
%assign s 0
%rep 3
%assign l 0
%rep 16
%assign r (16*s + l) % 6
%if r >= 3
        dd 1
%else
        dd 0
%endif
%assign l l+1
%endrep
%assign s s+1
%endrep

; One block of 16 triangles. %1 = 0: full block (plain loads and stores);
; %1 = 1: the last 1-15 triangles (k4-k7 and r10 set up by the caller).
%macro CAP_BLOCK 1
%if %1 == 0
        vmovdqu32 zmm0, [g2q+0*64]
        vmovdqu32 zmm1, [g2q+1*64]
        vmovdqu32 zmm2, [g2q+2*64]
        vptestnmb k1, xmm15, [g1q]              ; facing == 0 (xmm15: all ones)
%else
        ; (no load whose mask is empty: a masked load over a page that is
        ; unmapped or not yet touched is very slow on Zen 5
        ; even when it reads nothing; ecx = 3 * triangles left)
        vmovdqu32 zmm0{k4}{z}, [g2q+0*64]
        vpxord  xmm1, xmm1, xmm1
        vpxord  xmm2, xmm2, xmm2
        cmp     g3d, 16
        jbe     %%loaded
        vmovdqu32 zmm1{k5}{z}, [g2q+1*64]
        cmp     g3d, 32
        jbe     %%loaded
        vmovdqu32 zmm2{k6}{z}, [g2q+2*64]
%%loaded:
        vmovdqu8 xmm8{k7}{z}, [g1q]
        vptestnmb k1{k7}, xmm8, xmm8            ; facing == 0, lanes that exist
%endif
        vpaddd  zmm0, zmm0, zmm0                ; doubled vertex numbers
        vpaddd  zmm1, zmm1, zmm1
        vpaddd  zmm2, zmm2, zmm2
        vmovdqa64 zmm3, zmm16
        vmovdqa64 zmm4, zmm17
        vmovdqa64 zmm5, zmm18
        vpermi2d zmm3, zmm0, zmm1               ; I0 lanes 0-10
        vpermi2d zmm4, zmm0, zmm1               ; I1 lanes 0-10
        vpermi2d zmm5, zmm0, zmm1               ; I2 lanes 0-9
        vpermt2d zmm3{k2}, zmm16, zmm2          ; I0 lanes 11-15
        vpermt2d zmm4{k2}, zmm17, zmm2          ; I1 lanes 11-15
        vpermt2d zmm5{k3}, zmm18, zmm2          ; I2 lanes 10-15
        kmovw   g3d, k1
        vpcompressd zmm3{k1}{z}, zmm3           ; back-facing triangles first
        vpcompressd zmm4{k1}{z}, zmm4
        vpcompressd zmm5{k1}{z}, zmm5
        popcnt  g3d, g3d                        ; m
        vinserti64x4 zmm6, zmm3, ymm4, 1        ; [I0 0-7 | I1 0-7]
        vshufi64x2 zmm7, zmm3, zmm4, 0xEE       ; [I0 8-15 | I1 8-15]
        vmovdqa64 zmm9,  zmm22
        vmovdqa64 zmm10, zmm23
        vmovdqa64 zmm11, zmm24
        vmovdqa64 zmm12, zmm25
        vmovdqa64 zmm13, zmm26
        vmovdqa64 zmm14, zmm27
        vpermi2d zmm9,  zmm6, zmm5
        vpermi2d zmm10, zmm6, zmm5
        vpermi2d zmm11, zmm6, zmm5
        vpermi2d zmm12, zmm7, zmm5
        vpermi2d zmm13, zmm7, zmm5
        vpermi2d zmm14, zmm7, zmm5
        vpxord  zmm9,  zmm9,  zmm19
        vpxord  zmm10, zmm10, zmm20
        vpxord  zmm11, zmm11, zmm21
        vpxord  zmm12, zmm12, zmm19
        vpxord  zmm13, zmm13, zmm20
        vpxord  zmm14, zmm14, zmm21
        lea     g3d, [g3q+g3q*2]                ; 3m
%if %1 == 0
        vmovdqu32 [g4q+0*64], zmm9
        vmovdqu32 [g4q+1*64], zmm10
        vmovdqu32 [g4q+2*64], zmm11
        vmovdqu32 [g4q+3*64], zmm12
        vmovdqu32 [g4q+4*64], zmm13
        vmovdqu32 [g4q+5*64], zmm14
%else
        ; exactly 6m ints: masks from the 96-bit run of 6m ones
        lea     g6d, [g3q+g3q]                 ; 6m (<= 90)
        mov     g7q, -1
        bzhi    g7q, g7q, g6q                   ; ints 0-63 (all if 6m >= 64)
        kmovq   k4, g7q
        sub     g6d, 64
        mov     g7d, 0
        cmovs   g6d, g7d                      ; max(6m - 64, 0)
        mov     g7q, -1
        bzhi    g7q, g7q, g6q                   ; ints 64-95
        kmovq   k5, g7q
        vmovdqu32 [g4q+0*64]{k4}, zmm9
        kshiftrq k6, k4, 16
        vmovdqu32 [g4q+1*64]{k6}, zmm10
        kshiftrq k6, k4, 32
        vmovdqu32 [g4q+2*64]{k6}, zmm11
        kshiftrq k6, k4, 48
        vmovdqu32 [g4q+3*64]{k6}, zmm12
        vmovdqu32 [g4q+4*64]{k5}, zmm13
        kshiftrq k6, k5, 16
        vmovdqu32 [g4q+5*64]{k6}, zmm14
%endif
        lea     g4q, [g4q+g3q*8]                  ; + 6m ints (24m bytes)
%endmacro

VEC_ZMM
FUNC sv_create_cap_triangles_avx512, 4, 8, 28, shadowIndices, facing, indices, numIndices
        mov     g5q, g0q                       ; shadowIndices
        mov     g4q, g0q
        mov     rvd, g3d                      ; numIndices
        test    rvd, rvd
        jle     .zero                           ; negative or zero: touch nothing
        ; triangles = numIndices / 3 (unsigned: numIndices > 0 here)
        mov     g3d, 0xAAAAAAAB
        imul    rvq, g3q
        shr     rvq, 33

        vmovdqa64 zmm16, [cap_tr+0*64]
        vmovdqa64 zmm17, [cap_tr+1*64]
        vmovdqa64 zmm18, [cap_tr+2*64]
        vmovdqa64 zmm19, [cap_plus1+0*64]
        vmovdqa64 zmm20, [cap_plus1+1*64]
        vmovdqa64 zmm21, [cap_plus1+2*64]
        vmovdqa64 zmm22, [cap_out+0*64]
        vmovdqa64 zmm23, [cap_out+1*64]
        vmovdqa64 zmm24, [cap_out+2*64]
        vmovdqa64 zmm25, [cap_out+3*64]
        vmovdqa64 zmm26, [cap_out+4*64]
        vmovdqa64 zmm27, [cap_out+5*64]
        mov     g3d, 0xF800
        kmovw   k2, g3d                         ; I0, I1 lanes 11-15 from zmm2
        mov     g3d, 0xFC00
        kmovw   k3, g3d                         ; I2 lanes 10-15 from zmm2
        vpternlogd xmm15, xmm15, xmm15, 0xFF    ; all ones

        sub     rvq, 16
        jb      .tail
.loop16:
        CAP_BLOCK 0
        add     g2q, 16*3*4
        add     g1q, 16
        sub     rvq, 16
        jae     .loop16

.tail:
        add     rvq, 16                         ; 0-15 triangles left
        jz      .done
        lea     g3d, [rvq+rvq*2]                ; 3 * left indices (<= 45)
        mov     g6q, -1
        bzhi    g6q, g6q, g3q
        kmovq   k4, g6q
        kshiftrq k5, k4, 16
        kshiftrq k6, k4, 32
        mov     g6q, -1
        bzhi    g6q, g6q, rvq
        kmovw   k7, g6d
        CAP_BLOCK 1

.done:
        mov     rvq, g4q
        sub     rvq, g5q
        shr     rvq, 2                          ; ints written
        RET

.zero:
        xor     rvd, rvd
        RET clean
ENDFUNC
