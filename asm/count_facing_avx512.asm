; count_facing_avx512.asm: CountFacing with AVX-512 (x86-64-v4).
;
; Computes: the number of facing bytes set, n = sum(facing[0 .. n-1]),
;   exactly what section 4's C and appendix C compute for facing bytes of
;   0 or 1.
; Approach: appendix C's idea (add bytes in byte lanes, widen rarely) at
;   64 bytes per instruction. The main loop adds 256 bytes per iteration
;   with four vpaddb (load + add, one uop each) into four byte accumulators;
;   a lane gets at most one 1 per iteration, so after at most 62
;   iterations the four are summed (<= 248 per lane) and vpsadbw against
;   zero widens the 64 lanes into 8 qword sums. Then 0-3 whole vectors
;   (bits 7 and 6 of the count) and the last 0-63 bytes, with a zero-masked
;   vmovdqu8 whose mask (bzhi of all ones) covers exactly the bytes left:
;   masked-off bytes are neither read nor able to fault, so the routine
;   reads exactly facing[0 .. n-1] and needs no alignment and no scalar
;   tail. One vpsadbw and a horizontal add at the end.
;
; int sv_count_facing_avx512(const uint8_t *facing, int numTriangles)
;
; Register map (asm/sv_abi.inc names; rv = rax):
;   g0q  facing, advanced as bytes are added; rvd numTriangles (its low
;        8 bits: the last vectors and bytes)
;   g2d  256-byte blocks not yet added; g3d blocks left in this chunk
;   zmm0 zero (vpsadbw), then the total; zmm1-zmm4 byte accumulators;
;   zmm5 the masked last bytes; zmm6 qword sums of the full chunks;
;   k1 the last bytes' mask
;
; Contracts: facing bytes 0 or 1 (the routine sums byte values; a lane of
;   the byte accumulators holds at most 62 + 1 ones). No alignment.
;   numTriangles >= 0; a negative count returns 0 and reads nothing (the
;   test is on the 32-bit value: erratum C-7 does not arise).
;
; Cost: not kept here (figures go stale); `shadowvol bench` measures it
;   on the machine at hand and docs/BENCHMARK.md has the current table.
;
; Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.

%include "sv_abi.inc"

VEC_ZMM
FUNC sv_count_facing_avx512, 2, 4, 7, facing, numTriangles
        mov     rvd, g1d                      ; numTriangles (upper half ignored)
        vpxord  xmm0, xmm0, xmm0                ; zero, for vpsadbw
        test    rvd, rvd
        jle     .zero                           ; negative or zero: read nothing
        vpxord  xmm1, xmm1, xmm1
        vpxord  xmm2, xmm2, xmm2
        vpxord  xmm3, xmm3, xmm3
        vpxord  xmm4, xmm4, xmm4
        vpxord  xmm6, xmm6, xmm6                ; qword totals of full chunks
        mov     g2d, rvd
        shr     g2d, 8                          ; whole 256-byte blocks
        jz      .vectors

.chunk:                                         ; at most 62 blocks per chunk
        mov     g3d, 62
        cmp     g2d, g3d
        cmovb   g3d, g2d
        sub     g2d, g3d
.loop256:
        vpaddb  zmm1, zmm1, [g0q+0*64]
        vpaddb  zmm2, zmm2, [g0q+1*64]
        vpaddb  zmm3, zmm3, [g0q+2*64]
        vpaddb  zmm4, zmm4, [g0q+3*64]
        add     g0q, 256
        dec     g3d
        jnz     .loop256
        test    g2d, g2d
        jz      .vectors
        ; 62 blocks: widen (4 x 62 = 248 per lane fits a byte), go on
        vpaddb  zmm1, zmm1, zmm2
        vpaddb  zmm3, zmm3, zmm4
        vpaddb  zmm1, zmm1, zmm3
        vpsadbw zmm1, zmm1, zmm0
        vpaddq  zmm6, zmm6, zmm1
        vpxord  xmm1, xmm1, xmm1
        vpxord  xmm2, xmm2, xmm2
        vpxord  xmm3, xmm3, xmm3
        vpxord  xmm4, xmm4, xmm4
        jmp     .chunk

.vectors:                                       ; 0-3 whole vectors, then 0-63 bytes
        test    rvb, 128
        jz      .v1
        vpaddb  zmm2, zmm2, [g0q+0*64]
        vpaddb  zmm3, zmm3, [g0q+1*64]
        add     g0q, 128
.v1:
        test    rvb, 64
        jz      .v0
        vpaddb  zmm4, zmm4, [g0q]
        add     g0q, 64
.v0:
        and     rvd, 63
        jz      .sum                            ; no bytes left: no load (a
        mov     g2q, -1                         ; masked load that reaches a
        bzhi    g2q, g2q, rvq                   ; page not mapped or not yet
        kmovq   k1, g2q                         ; touched is very slow on
        vmovdqu8 zmm5{k1}{z}, [g0q]             ; Zen 5, even fully
        vpaddb  zmm1, zmm1, zmm5                ; masked); lanes now <= 63
.sum:
        vpaddb  zmm1, zmm1, zmm2
        vpaddb  zmm3, zmm3, zmm4
        vpaddb  zmm1, zmm1, zmm3                ; <= 252
        vpsadbw zmm1, zmm1, zmm0                ; 8 qword sums
        vpaddq  zmm0, zmm1, zmm6                ; + the earlier chunks
        ; horizontal sum of the 8 qwords (the total is below 2^31)
        vextracti64x4 ymm1, zmm0, 1
        vpaddq  ymm0, ymm0, ymm1
        vextracti128 xmm1, ymm0, 1
        vpaddq  xmm0, xmm0, xmm1
        vpshufd xmm1, xmm0, SHUFFLE_D(2, 3, 0, 1)
        vpaddq  xmm0, xmm0, xmm1
        vmovd   rvd, xmm0
        RET

.zero:
        xor     rvd, rvd
        RET
ENDFUNC
