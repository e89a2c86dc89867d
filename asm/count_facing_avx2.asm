; count_facing_avx2.asm: CountFacing for x86-64-v3 (AVX2, BMI2, POPCNT).
;
; Computes: the number of facing bytes set, n = sum(facing[0 .. n-1]), as
;   section 4's C (bytes are 0 or 1, so the sum is the count).
; Approach: not a port; appendix C's idea (add bytes, widen rarely) at 32
;   bytes per instruction. vpaddb adds two 32-byte loads into one register
;   (at most 2 per byte lane, no overflow), vpsadbw against zero sums those
;   32 bytes into four qwords, vpaddq accumulates: 128 bytes per iteration,
;   two independent accumulators. The tail never reads past facing + n:
;     - whole 32-byte blocks, then the last 1-31 bytes with ONE 32-byte
;       load that ends exactly at facing + n (it overlaps bytes already
;       counted) ANDed with a sliding mask that keeps only its last r bytes
;       (possible whenever n >= 32);
;     - n < 32: whole qwords summed by popcnt (a qword of 0/1 bytes has as
;       many bits set as it has bytes set), the last 1-7 bytes by one qword
;       load ending at facing + n shifted right past the overlap (n >= 8),
;       or byte by byte (n < 8).
;
; int sv_count_facing_avx2(const uint8_t *facing, int numTriangles)
;
; Register map (asm/sv_abi.inc names; rv = rax):
;   g0q  facing (walks forward)      g1q  facing + n (end)
;   g3d  bytes still to count        rvd  scalar sum (popcnt tails)
;   ymm0, ymm1 qword accumulators    ymm5 zero
;   ymm2-ymm4 loads / byte sums
;
; Contracts: no alignment; facing bytes 0 or 1 (a byte of 2..255 adds its
;   value, and four such in one lane could wrap: the C counts it as 1);
;   numTriangles >= 0 (negative returns 0 and reads nothing). Reads exactly
;   facing[0 .. n-1]: never a byte before or after.
;
; Cost: not kept here (figures go stale); `shadowvol bench` measures it
;   on the machine at hand and docs/BENCHMARK.md has the current table.
;
; Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.

%include "sv_abi.inc"

RODATA
align 32
; 32 zero bytes then 32 0xFF bytes: a 32-byte load at tail_mask + r
; keeps the last r bytes of a vector (byte p is kept when p >= 32 - r).
tail_mask:  times 32 db 0
            times 32 db 0xFF

VEC_YMM
FUNC sv_count_facing_avx2, 2, 4, 6, facing, numTriangles
        mov     g3d, g1d              ; numTriangles (upper half ignored)
        xor     rvd, rvd
        test    g3d, g3d
        jle     .ret                    ; negative or zero: 0, nothing read
        lea     g1q, [g0q + g3q]        ; end (ecx > 0: zero-extended is right)
        cmp     g3d, 32
        jb      .small

        vpxor   xmm0, xmm0, xmm0
        vpxor   xmm1, xmm1, xmm1
        vpxor   xmm5, xmm5, xmm5
        sub     g3d, 128                ; signed from here: n <= 2^31 - 1
        jl      .run32

.loop128:
        vmovdqu ymm2, [g0q]
        vpaddb  ymm2, ymm2, [g0q + 32]
        vmovdqu ymm3, [g0q + 64]
        vpaddb  ymm3, ymm3, [g0q + 96]
        vpsadbw ymm2, ymm2, ymm5
        vpsadbw ymm3, ymm3, ymm5
        vpaddq  ymm0, ymm0, ymm2
        vpaddq  ymm1, ymm1, ymm3
        add     g0q, 128
        sub     g3d, 128
        jge     .loop128

.run32:
        add     g3d, 128 - 32           ; bytes left - 32
        jl      .last
.loop32:
        vpsadbw ymm2, ymm5, [g0q]
        vpaddq  ymm0, ymm0, ymm2
        add     g0q, 32
        sub     g3d, 32
        jge     .loop32

.last:
        add     g3d, 32                 ; 0..31 bytes left
        jz      .reduce
        lea     g2q, [tail_mask]
        vmovdqu ymm2, [g2q + g3q]       ; keeps the last ecx bytes
        vpand   ymm2, ymm2, [g1q - 32]  ; n >= 32: never before facing
        vpsadbw ymm2, ymm2, ymm5
        vpaddq  ymm0, ymm0, ymm2

.reduce:
        vpaddq  ymm0, ymm0, ymm1
        vextracti128 xmm1, ymm0, 1
        vpaddq  xmm0, xmm0, xmm1
        vpshufd xmm1, xmm0, SHUFFLE_D(2, 3, 0, 1)
        vpaddq  xmm0, xmm0, xmm1
        vmovq   rvq, xmm0
        RET
.ret:
        RET clean

        ; 1 <= n < 32: no vector register touched, so no vzeroupper needed
.small:
        sub     g3d, 8
        jb      .bytes
.qwords:                                ; n >= 8
        popcnt  g2q, [g0q]
        add     rvd, g2d
        add     g0q, 8
        sub     g3d, 8
        jae     .qwords
        add     g3d, 8                  ; 0..7 bytes left
        jz      .ret
        ; the qword ending at the end holds 8 - ecx bytes already counted:
        ; shift them out (low bytes are the lower addresses)
        mov     g2q, [g1q - 8]
        neg     g3d
        lea     g3d, [g3q*8 + 64]       ; 8 * (8 - left)
        shrx    g2q, g2q, g3q
        popcnt  g2q, g2q
        add     rvd, g2d
        RET clean
.bytes:                                 ; 1 <= n < 8
        movzx   g2d, byte [g0q]
        add     rvd, g2d
        inc     g0q
        cmp     g0q, g1q
        jb      .bytes
        RET clean
ENDFUNC
