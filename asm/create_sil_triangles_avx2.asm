; create_sil_triangles_avx2.asm: CreateSilTriangles for x86-64-v3 (AVX2,
; POPCNT).
;
; Computes: for each SilEdge whose facing bytes f1 = facing[p1] and
;   f2 = facing[p2] differ, the two triangles of section 6's C, in its order:
;     f1 = 1:  v1, v2+1, v2,   v1,   v1+1, v2+1
;     f1 = 0:  v1, v2,   v2+1, v1+1, v1,   v2+1
;   Returns the number of indices written (6 per silhouette edge).
; Approach: not a port. Appendix E writes six indices for EVERY edge and
;   advances only on silhouette edges (about 10-20% of them); here the
;   edges are first sorted out, then only silhouette edges are written.
;   Chunks of up to 992 edges, two phases each:
;   1. Flags, 16 edges per iteration: per edge one qword load of (p1, p2),
;      movsxd / sar to split it, movzx f1, `xor r8b, [facing + p2]`, and
;      lea m = 2m + (f1 ^ f2) folds the flag into an 8-bit mask (bit 7 - k
;      for edge k of 8). The mask indexes a 256-entry table of packed edge
;      numbers (vpmovzxbd from memory), the group's first number is added,
;      32 bytes are stored to a list on the stack and popcnt moves the list
;      end: a branch-free left-pack of the silhouette edges.
;   2. Emit, two listed edges per iteration: vpermd, with the edge's
;      32-byte window as its memory operand (16 bytes loaded for a list's
;      last entry, the only one that can be the array's last edge), spreads
;      (v1, v2) to (v1, v2, v2, v1, v1, v2, -, -); on a silhouette edge
;      f1 = 1 - f2, so the +1s depend on f2 alone: vpxor with the 32 bytes
;      at xor_by_f2 + 8 * f2, two overlapping rows of one table,
;      (0,1,0,0,1,1) for f2 = 0 and (0,0,1,1,0,1) for f2 = 1 (v even: ^1 is
;      +1). The output advances 24 bytes per edge, so no store waits on a
;      pointer chain; each store is 32 bytes but the list's last, which is
;      16 + 8, so nothing lands past the count returned.
;   Why (measured on the Zen 5-class core this was written on, the
;   2016-edge character, moving light): one 32-byte store per edge with a
;   conditionally advanced pointer (the C's scheme in AVX2) was slower; a
;   vpgatherdd lane for the facing bytes costs several scalar byte loads;
;   phase 1 alone (about 7 instructions per edge) runs near the issue
;   width, so its two look-ups per edge are the floor of this routine.
;   The figures: docs/BENCHMARK.md, "Design measurements".
;
; int sv_create_sil_triangles_avx2(int *shadowIndices, const uint8_t *facing,
;                                  const SilEdge *silEdges, int numSilEdges)
;
; Register map (asm/sv_abi.inc names; rv = rax):
;   g10q output position     g11q shadowIndices     g12q silEdges
;   g13q the packed-positions table     g1q facing
;   g8q first edge of the chunk (pointer)   g0q end of the edges
;   g2q current edge (phase 1)   g6q end of the chunk (less a group)
;   g9q list entries; rvq, g3q masks / list index; g4q, g5q p1, p2, flags
;   g7q xor_by_f2
;   ymm6 2 * (current group's first edge number), broadcast; ymm7 16,
;   broadcast; ymm14 idx_lo; ymm0-ymm2 scratch
;   [rsp] the list: 2 * edge number (so that [g12q + entry*8] is the edge)
;
; Contracts: no alignment; output room for 6 * numSilEdges ints (nothing is
;   written past 6 * (silhouette edges)); facing bytes 0 or 1; v1, v2 even;
;   p1, p2 valid indices into facing (sign-extended: int). numSilEdges >= 0
;   (negative or zero: returns 0, touches nothing). Reads nothing outside
;   the numSilEdges edges but the facing bytes they name. Stack: < 4 KiB
;   (no probe needed).
;
; Cost: not kept here (figures go stale); `shadowvol bench` measures it
;   on the machine at hand and docs/BENCHMARK.md has the current table.
;
; Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.

%include "sv_abi.inc"
%include "avx2_left_pack.inc"

%define CHUNK        992                  ; edges per list: a multiple of 16
%define LIST_ENTRIES (CHUNK + 16)         ; + 8 for a group's 32-byte store
%define FRAME        (LIST_ENTRIES*4)     ; + 6 pushes + return + 8 of padding: 4096

RODATA
align 32
idx_lo:     dd 2, 3, 3, 2, 2, 3, 2, 3
; rows at +0 (f2 = 0) and +8 (f2 = 1), 8 dwords each
xor_by_f2:  dd 0, 1, 0, 0, 1, 1, 0, 1, 0, 0
step16:     dd 16
align 64
; positions[m]: for the mask m = sum of flag_k << (7 - k), the numbers 2k of
; the edges whose flag is set, in increasing k, one per byte, then zeros.
positions:
        SET_BIT_POSITIONS 2, 1

; FIRST off: starts a mask in eax with the flag of the edge at rdx + off.
%macro FIRST 1
        mov     g5q, [g2q + %1]                 ; p1 | p2 << 32
        movsxd  g4q, g5d
        sar     g5q, 32
        movzx   rvd, byte [g1q + g4q]
        xor     rvb, [g1q + g5q]                 ; f1 ^ f2
%endmacro
; NEXT off: appends the flag of the edge at rdx + off to the mask in rax.
%macro NEXT 1
        mov     g5q, [g2q + %1]
        movsxd  g4q, g5d
        sar     g5q, 32
        movzx   g4d, byte [g1q + g4q]
        xor     g4b, [g1q + g5q]
        lea     rvq, [g4q + rvq*2]
%endmacro
; MASK8 off: the mask of the 8 edges at rdx + off, in eax.
%macro MASK8 1
        FIRST   %1
        NEXT    %1 + 16
        NEXT    %1 + 32
        NEXT    %1 + 48
        NEXT    %1 + 64
        NEXT    %1 + 80
        NEXT    %1 + 96
        NEXT    %1 + 112
%endmacro
; PACK8 mask, ymm: appends the group's silhouette edges to the list.
%macro PACK8 2
        vpmovzxbd %2, [g13q + %1*8]
        popcnt  %1, %1
        vpaddd  %2, %2, ymm6
        vpaddd  ymm6, ymm6, ymm7
        vmovdqu [rsp + g9q*4], %2
        add     g9q, %1
%endmacro
; EMIT1 k, src, out: list entry eax + k (its edge: edx) into ymm out. src:
; the edge's 32-byte window (memory; never for the last edge of the
; array) or ymm0 after a 16-byte load.
%macro EMIT1 3
        mov     g2d, [rsp + rvq*4 + %1*4]      ; 2 * edge number
        movsxd  g5q, dword [g12q + g2q*8 + 4]
        movzx   g5d, byte [g1q + g5q]           ; f2
        vpermd  %3, ymm14, %2                  ; v1 v2 v2 v1 v1 v2 - -
        vpxor   %3, %3, [g7q + g5q*8]
%endmacro

VEC_YMM
FUNC sv_create_sil_triangles_avx2
        movsxd  g3q, g3d
        test    g3q, g3q
        jg      .start
        xor     rvd, rvd                ; negative or zero: 0, nothing touched
        RET_NOFRAME clean
.start:
        PROLOGUE 4, 14, 15, FRAME, shadowIndices, facing, silEdges, numSilEdges
        mov     g10q, g0q
        mov     g11q, g0q
        mov     g12q, g2q
        lea     g13q, [positions]
        lea     g7q, [xor_by_f2]
        vpbroadcastd ymm7, [step16]
        vmovdqa ymm14, [idx_lo]
        mov     g8q, g2q
        shl     g3q, 4
        lea     g0q, [g2q + g3q]        ; end of the edges

.chunk:
        ; ---- phase 1: list the silhouette edges of [rbx, chunk end)
        xor     g9d, g9d
        lea     g6q, [g8q + CHUNK*16]
        cmp     g6q, g0q
        cmova   g6q, g0q
        mov     g2q, g8q
        mov     rvq, g8q
        sub     rvq, g12q
        shr     rvq, 3                  ; 2 * first edge number (< 2^32)
        vmovd   xmm6, rvd
        vpbroadcastd ymm6, xmm6
        sub     g6q, 256
        cmp     g2q, g6q
        ja      .group8
.group16:
        MASK8   0
        mov     g3d, rvd
        MASK8   128
        PACK8   g3q, ymm1
        PACK8   rvq, ymm2
        add     g2q, 256
        cmp     g2q, g6q
        jbe     .group16
.group8:
        add     g6q, 128
        cmp     g2q, g6q
        ja      .rest
        MASK8   0
        PACK8   rvq, ymm1
        add     g2q, 128
.rest:                                  ; the last 0..7 edges (of the array)
        add     g6q, 128
        cmp     g2q, g6q
        jae     .emit
.rest1:
        movsxd  g4q, dword [g2q]
        movsxd  g5q, dword [g2q + 4]
        movzx   g4d, byte [g1q + g4q]
        xor     g4b, [g1q + g5q]
        mov     rvq, g2q
        sub     rvq, g12q
        shr     rvq, 3
        mov     [rsp + g9q*4], rvd
        add     g9q, g4q
        add     g2q, 16
        cmp     g2q, g6q
        jb      .rest1

        ; ---- phase 2: six indices per listed edge, in order
.emit:
        mov     g8q, g2q                ; the next chunk
        sub     g9d, 1                  ; index of the last entry
        jb      .next                   ; none
        xor     rvd, rvd
.emit2:                                 ; all but the last: 32-byte stores
        lea     g3d, [rvq + 2]
        cmp     g3d, g9d
        ja      .emit1
        EMIT1   0, [g12q + g2q*8], ymm1  ; (never the array's last edge)
        EMIT1   1, [g12q + g2q*8], ymm2
        vmovdqu [g10q], ymm1
        vmovdqu [g10q + 24], ymm2
        add     g10q, 48
        add     rvd, 2
        jmp     .emit2
.emit1:
        cmp     rvd, g9d
        jae     .emitlast
        EMIT1   0, [g12q + g2q*8], ymm1
        vmovdqu [g10q], ymm1
        add     g10q, 24
        inc     rvd
.emitlast:                              ; 16 bytes in; exactly six ints out
        mov     g2d, [rsp + rvq*4]
        vmovdqu xmm0, [g12q + g2q*8]     ; p1 p2 v1 v2
        EMIT1   0, ymm0, ymm1
        vmovdqu [g10q], xmm1
        vextracti128 xmm2, ymm1, 1
        vmovq   [g10q + 16], xmm2
        add     g10q, 24
.next:
        cmp     g8q, g0q
        jb      .chunk

        mov     rvq, g10q                ; return (end - shadowIndices) / 4
        sub     rvq, g11q
        shr     rvq, 2
        RET
ENDFUNC
