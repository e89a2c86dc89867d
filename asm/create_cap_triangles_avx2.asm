; create_cap_triangles_avx2.asm: CreateCapTriangles for x86-64-v3 (AVX2,
; BMI2, POPCNT).
;
; Computes: for each triangle j with facing[j] == 0 and vertex numbers
;   i0, i1, i2 (doubled: a0 = 2*i0, ...): the near cap (a2, a1, a0) and the
;   far cap (a0+1, a1+1, a2+1), exactly section 7's C. Returns the number
;   of indices written (6 per non-facing triangle).
; Approach: not a port. Appendix F writes six indices for EVERY triangle
;   and advances only for the non-facing ones (about half); here they are
;   sorted out first, then only they are written. Chunks of up to 992
;   triangles, two phases each:
;   1. List: 32 facing bytes at a time, vpcmpeqb against zero + vpmovmskb
;      give a 32-bit mask of the casting triangles; per mask byte, a
;      256-entry table of packed 3 * bit positions (vpmovzxbd straight from
;      memory) plus 3 * the block's first triangle are stored to a list on
;      the stack and popcnt moves its end: a branch-free left-pack of the
;      casting triangles' first index positions.
;   2. Emit, per listed triangle (two per iteration): one vpermd with its
;      32-byte window of indices as the memory operand lays out
;      (i2, i1, i0, i0, i1, i2, -, -), vpaddd doubles, vpxor with
;      (0,0,0,1,1,1,0,0) adds the far cap's +1 (the doubled numbers are
;      even), one 32-byte store; the output advances 24 bytes per triangle,
;      so the stores wait on no pointer chain.
;   The 32-byte window of a triangle in the last two reads up to 20 bytes
;   past the indices: the (at most two) listed triangles among the last two
;   are loaded as 8 + 4 bytes and stored as 16 + 8 bytes, so nothing is read
;   past the indices nor written past the count returned.
;   Why a list: appendix F's scheme with one vpermd and one 32-byte store
;   per triangle, its offsets from a prefix-sum multiply, was measured
;   first (the 1344-triangle character, moving light, the Zen 5-class core
;   this was written on) and was slower than this one (docs/BENCHMARK.md, "Design measurements").
;
; int sv_create_cap_triangles_avx2(int *shadowIndices, const uint8_t *facing,
;                                  const int *indices, int numIndices)
;
; Register map (asm/sv_abi.inc names; rv = rax):
;   g10q output position     g11q shadowIndices    g12q indices   g13q facing
;   g6q triangles (n)       g5q  3 * (n - 3): the last first-index position
;                               whose 32-byte window stays inside indices
;   g8q first triangle of the chunk    g0q end of the chunk
;   g1q triangle of the current 32-block    g9q list entries
;   g7q the packed-positions table; rvq, g3q, g2q, g4q scratch
;   ymm5 zero; ymm6 3 * (current 8-block's first triangle), broadcast;
;   ymm7 24, broadcast; ymm8 the vpermd pattern; ymm9 (0,0,0,1,1,1,0,0);
;   ymm0-ymm2 scratch
;   [rsp] the list: 3 * triangle number (the position of its i0)
;
; Contracts: no alignment; numIndices a multiple of 3, >= 0 (negative or
;   zero: returns 0, touches nothing; of a count that is not, the partial
;   last triangle is ignored, where C's i < numIndices walk reads past
;   it); vertex numbers in [0, 2^30) (doubled in 32 bits); facing bytes 0
;   or 1; output room for 2 * numIndices ints (nothing is written past
;   6 * (casting triangles)). Reads nothing outside facing[0 .. n-1] and
;   indices[0 .. numIndices-1]. Stack: < 4 KiB (no probe needed).
;
; Cost: not kept here (figures go stale); `shadowvol bench` measures it
;   on the machine at hand and docs/BENCHMARK.md has the current table.
;
; Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.

%include "sv_abi.inc"
%include "avx2_left_pack.inc"

%define CHUNK        992                  ; triangles per list: a multiple of 32
%define LIST_ENTRIES (CHUNK + 16)         ; + 8 for an 8-block's 32-byte store
%define FRAME        (LIST_ENTRIES*4)     ; + 6 pushes + return + 8 of padding: 4096

RODATA
align 32
perm_cap:   dd 2, 1, 0, 0, 1, 2, 0, 0
far_plus1:  dd 0, 0, 0, 1, 1, 1, 0, 0
step24:     dd 24
align 64
; positions3[m]: 3 * the indices of the set bits of m, in increasing order,
; one per byte, then zero bytes.
positions3:
        SET_BIT_POSITIONS 3, 0

; EMIT8 / EMIT32 and pass 1 (LIST_NONFACING): asm/avx2_left_pack.inc (r11 = the
; table above).
; CAP1 k, ymm: the six indices of list entry eax + k, from its 32-byte
; window of indices.
%macro CAP1 2
        mov     g3d, [rsp + rvq*4 + %1*4]
        vpermd  %2, ymm8, [g12q + g3q*4]
        vpaddd  %2, %2, %2
        vpxor   %2, %2, ymm9
%endmacro

VEC_YMM
FUNC sv_create_cap_triangles_avx2
        mov     rvd, g3d
        test    rvd, rvd
        jg      .start
        xor     rvd, rvd                ; negative or zero: 0, nothing touched
        RET_NOFRAME clean
.start:
        PROLOGUE 4, 14, 10, FRAME, shadowIndices, facing, indices, numIndices
        mov     g10q, g0q
        mov     g11q, g0q
        mov     g12q, g2q
        mov     g13q, g1q
        mov     g4d, 0xAAAAAAAB         ; numIndices / 3 (exact for 32-bit unsigned)
        imul    rvq, g4q
        shr     rvq, 33
        jz      .done                   ; 1 or 2 indices: no whole triangle
        mov     g6q, rvq
        lea     g5q, [rvq + rvq*2 - 9]   ; signed: negative when n < 3
        lea     g7q, [positions3]
        vpxor   xmm5, xmm5, xmm5
        vpbroadcastd ymm7, [step24]
        vmovdqa ymm8, [perm_cap]
        vmovdqa ymm9, [far_plus1]
        xor     g8d, g8d

.chunk:
        ; ---- phase 1: list the casting triangles of [rbx, rdi)
        xor     g9d, g9d
        mov     g1q, g8q
        lea     rvq, [g8q + g8q*2]      ; < 2^31
        vmovd   xmm6, rvd
        vpbroadcastd ymm6, xmm6
        lea     g0q, [g8q + CHUNK]
        cmp     g0q, g6q
        cmova   g0q, g6q
        LIST_NONFACING g13q, g6q, g0q, rvq, .emit

        ; ---- phase 2: six indices per listed triangle, in order
.emit:
        mov     g8q, g0q                ; the next chunk
        ; the listed triangles whose window stays inside indices (3t <= r9)
        ; are a prefix of the list; the rest (0..2) are among the last two
        mov     g2d, g9d
        test    g2d, g2d
        jz      .next
        mov     rvd, [rsp + g2q*4 - 4]
        cmp     rvq, g5q
        jle     .split
        dec     g2d
        jz      .split
        mov     rvd, [rsp + g2q*4 - 4]
        cmp     rvq, g5q
        jle     .split
        dec     g2d
.split:
        xor     rvd, rvd
.fast2:
        lea     g3d, [rvq + 2]
        cmp     g3d, g2d
        ja      .fast1
        CAP1    0, ymm1
        CAP1    1, ymm2
        vmovdqu [g10q], ymm1
        vmovdqu [g10q + 24], ymm2
        add     g10q, 48
        add     rvd, 2
        jmp     .fast2
.fast1:
        cmp     rvd, g2d
        jae     .slow
        CAP1    0, ymm1
        vmovdqu [g10q], ymm1
        add     g10q, 24
        inc     rvd
.slow:                                  ; 12 bytes in, 24 bytes out
        cmp     rvd, g9d
        jae     .next
        mov     g3d, [rsp + rvq*4]
        vmovq   xmm0, [g12q + g3q*4]
        vpinsrd xmm0, xmm0, [g12q + g3q*4 + 8], 2
        vpermd  ymm1, ymm8, ymm0
        vpaddd  ymm1, ymm1, ymm1
        vpxor   ymm1, ymm1, ymm9
        vmovdqu [g10q], xmm1
        vextracti128 xmm2, ymm1, 1
        vmovq   [g10q + 16], xmm2
        add     g10q, 24
        inc     rvd
        jmp     .slow
.next:
        cmp     g8q, g6q
        jb      .chunk

.done:
        mov     rvq, g10q                ; return (end - shadowIndices) / 4
        sub     rvq, g11q
        shr     rvq, 2
        RET
ENDFUNC
