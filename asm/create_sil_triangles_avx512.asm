; create_sil_triangles_avx512.asm: CreateSilTriangles with AVX-512
; (x86-64-v4).
;
; Computes: for each SilEdge whose facing bytes f1 = facing[p1],
;   f2 = facing[p2] differ, in edge order, the six indices of section 6's C:
;     f1 = 1:  v1, v2+1, v2,   v1,   v1+1, v2+1
;     f1 = 0:  v1, v2,   v2+1, v1+1, v1,   v2+1
;   i.e. v1, v2^f1, v2^f2, v1^f2, v1^f1, v2^1 (v even, f1 ^ f2 = 1).
;   Returns the number of indices written (6 per silhouette edge).
; Approach: not a port. Appendix E writes six ints for every edge; here the
;   facing lookups are done sixteen edges at a time in vector registers,
;   and only the silhouette edges (12-20% of them on a character) are
;   written. Chunks of up to 448 edges, three passes each:
;   A. Triangle numbers: four loads take 16 edges; two vpermi2d and two
;      vshufi64x2 make P1 (their p1, one per lane) and P2, which go to the
;      stack; vpminud / vpmaxud keep the chunk's lowest and highest
;      triangle number lo, hi.
;   B. Lists: when hi - (lo rounded down to 64) < 2048, the facing bytes
;      lo64 .. hi are in a circular bitmap of 2048 bits in zmm28-zmm31
;      (byte p at bit p mod 2048: vptestmb per 64 bytes, the last load
;      masked so that nothing past facing[hi] is read). The window slides:
;      bytes already there from earlier chunks are kept, only new ones are
;      added (SilEdges come sorted by p1), so a mesh of under 2048
;      triangles reads each facing byte about once. A lookup of 16 triangle
;      numbers p is eight instructions: vpsrld p by 5 (the bitmap dword,
;      mod 64), two masked vpermi2d (dwords 0-31 and 32-63), vprorvd by p
;      (the bit to bit 0; the rotate takes the count mod 32), vptestmd.
;      On the reference machine (AMD Zen 5 class) this is the cheap way: a
;      vpgatherdd zmm costs more than its 16 lanes as scalar loads whatever
;      the mask, and blocks the load ports meanwhile. The lookups of P1 and P2 are
;      the masks F1, F2 (bit t: f1, f2 of edge t) and S = F1 ^ F2 is one
;      kxorw (splitting one interleaved mask with pext, as before, cost six
;      instructions and two mask-GPR trips more per 16 edges, and was
;      slower on the character); vpcompressd (to a register:
;      the memory form is several times slower on Zen) packs the byte
;      offsets of the silhouette edges and 64 * f1 into two lists on the
;      stack; popcnt advances them.
;      A chunk spanning more triangles (large meshes, whose SilEdges,
;      sorted by p1, meet far-away p2) is handed whole to
;      sv_create_sil_triangles_avx2 (scalar lookups), an ordinary call:
;      scalar lookups folded sixteen at a time into masks here were
;      slower than the AVX2 kernel's on koala.glb (99994 triangles), and
;      on the 980k-triangle character this variant then lost to c_ref's
;      volume.
;   Whole calls of more than 3072 SilEdges (SIL_AVX2_ABOVE: a closed mesh
;   of more than 2048 triangles) go to the AVX2 kernel at entry, a tail
;   call: there its scalar lookups beat the window, which slides and
;   refills, on every such mesh measured (`shadowvol bench --scaling`),
;   while on the smaller meshes this path wins or ties. The figures per
;   model: docs/BENCHMARK.md, "Design measurements".
;   C. Output: per listed pair of edges, vpbroadcastq of each (v1, v2),
;      one vpermt2d into (v1 v2 v2 v1 v1 v2) twice, a vpxord of the ^1
;      patterns of their f1 (a 4-entry table), one masked store of twelve
;      ints. Writes exactly 6 ints per silhouette edge, nothing past them.
;   The only data-dependent branches: pass C's loop exit (once per chunk),
;   and per chunk the choice of lookup (by its triangle numbers, not by
;   the facing data).
;
; int sv_create_sil_triangles_avx512(int *shadowIndices, const uint8_t *facing,
;                                    const SilEdge *silEdges, int numSilEdges)
;
; Register map (asm/sv_abi.inc names; rv = rax) (across the AVX2 call: rvq, g2q, g0q, g4q saved in the frame,
; zmm25, zmm27-zmm31 reloaded):
;   g0q  facing; g2q the chunk's edges; rvq edges after this chunk
;   g4q   output pointer; g10q edges in the chunk; g11q list length
;   g13q  the ^1 pattern table; g12q, g3q, g1q, g6q scratch
;   g8q  block counter; g7q offset of the block's P1, P2
;   g9q  the frame: rsp 64-byte aligned below it; shadowIndices and the
;        bitmap's window [lo64, end) in its first slots
;   zmm0-zmm3 16 edges; zmm4, zmm5 their p1 / p2 halves (pass A), then
;   P1, P2 (pass B); zmm6, zmm7 P1, P2 (pass A), zmm6-zmm9 lookup scratch
;   (pass B); zmm10, zmm11 list entries; zmm12-zmm15 min / max; zmm25 pass
;   C's permute; zmm26 byte offsets of the block's edges; zmm27 the p1 / p2
;   dword picks; zmm28-zmm31 the bitmap
;   k1 F1, k2 F2, k3 S, k4-k6 scratch; k6 twelve ints and k7 six ints in
;   pass C
;
; Contracts: facing bytes 0 or 1 (only bit 0 is looked up); v1, v2 even
;   (v ^ 1 = v + 1, as in appendix E); 0 <= p1, p2 <= numTriangles
;   (facing has numTriangles + 1 bytes; the routine reads facing bytes
;   between the smallest and the largest triangle number of a chunk only,
;   give or take the 64-byte rounding down of the smallest). Output room
;   for 6 * numSilEdges ints; exactly the returned count is written. No
;   alignment anywhere. numSilEdges >= 0 (negative returns 0, touches
;   nothing). Stack: the 7616-byte frame (SIL_FRAME), its 64-byte
;   alignment and the saved registers, under 7.6 KiB; plus the AVX2
;   kernel's (< 4 KiB) while a wide chunk is handed to it.
;
; Cost: not kept here (figures go stale); `shadowvol bench` measures it
;   on the machine at hand and docs/BENCHMARK.md has the current table.
;
; Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.

%include "sv_abi.inc"

SV_EXTERN sv_create_sil_triangles_avx2

RODATA
align 64
sil_pick_p:                             ; over 2 zmm of 8 edges: their p1, then p2
%assign j 0
%rep 8
        dd 4*j
%assign j j+1
%endrep
%assign j 0
%rep 8
        dd 4*j + 1
%assign j j+1
%endrep
sil_off:                                ; byte offsets of edges 0-15
%assign i 0
%rep 16
        dd 16*i
%assign i i+1
%endrep
; Two edges' outputs from (v1, v2) of a (first table) and of b (second).
sil_pair: dd 0, 1, 1, 0, 0, 1, 16, 17, 17, 16, 16, 17, 0, 0, 0, 0
; The ^1 patterns of two edges' twelve ints, at 128 * f1a + 64 * f1b:
; f1 = 0: 0, 0, 1, 1, 0, 1;  f1 = 1: 0, 1, 0, 0, 1, 1 (then 4 zeros).
sil_pat2:
%assign fa 0
%rep 2
%assign fb 0
%rep 2
%if fa == 0
        dd 0, 0, 1, 1, 0, 1
%else
        dd 0, 1, 0, 0, 1, 1
%endif
%if fb == 0
        dd 0, 0, 1, 1, 0, 1
%else
        dd 0, 1, 0, 0, 1, 1
%endif
        dd 0, 0, 0, 0
%assign fb fb+1
%endrep
%assign fa fa+1
%endrep
sil_c32:  dd 32
sil_c1:   dd 1
sil_c64:  dd 64
sil_c256: dd 256

; Frame (below rbp, rsp 64-byte aligned): a few slots, the bitmap, the
; (p1, p2) pairs of one chunk and its two lists: 7616 bytes, so its two pages
; are touched in order (a stack probe, as compilers do for frames over a
; page: a thread's guard page is not skipped).
%define SIL_CHUNK   448                         ; edges per chunk (x 16)
; Above this many SilEdges (a closed mesh of more than ~2048 triangles,
; whose facing bytes no longer fit the window at once) the AVX2 kernel is
; faster on every mesh measured, and the call goes there (header).
%define SIL_AVX2_ABOVE 3072
%define SIL_BASE    0                           ; shadowIndices
%define SIL_WLO     8                           ; bitmap window: first byte (x 64)
%define SIL_WEND    16                          ;   and one past its last
%define SIL_SAVE_AFTER  24                      ; across the AVX2 call (.chunk_via_avx2):
%define SIL_SAVE_EDGES  32                      ;   edges after the chunk, the
%define SIL_SAVE_FACING 40                      ;   chunk, facing, the output
%define SIL_SAVE_OUT    48                      ;   pointer
%define SIL_BM      64                          ; 256 bytes: 2048 facing bits
%define SIL_P1P2    (SIL_BM + 256)              ; SIL_CHUNK qwords: P1, P2 per block
%define SIL_LIST_OFS (SIL_P1P2 + SIL_CHUNK * 8)  ; (SIL_CHUNK + 16) dwords: byte
                                                ;   offsets of the silhouette edges
%define SIL_LIST_F1 (SIL_LIST_OFS + (SIL_CHUNK + 16) * 4) ; their 64 * f1
%define SIL_FRAME   (SIL_LIST_F1 + (SIL_CHUNK + 16) * 4)

; Pass A over one block of 16 edges at rbx (%1 = 1: the last 1-15 edges,
; rcx = their number): P1 (p1 of edges 0-15) to [rsp+SIL_P1P2+r11] and P2
; (their p2) to the next 64 bytes; their minima into zmm14, zmm15 and
; maxima into zmm12, zmm13.
%macro SIL_PAIRS 1
%if %1 == 0
        vmovdqu32 zmm0, [g8q+0*64]
        vmovdqu32 zmm1, [g8q+1*64]
        vmovdqu32 zmm2, [g8q+2*64]
        vmovdqu32 zmm3, [g8q+3*64]
%else
        lea     g6d, [g3q*4]                   ; dwords left (<= 60)
        mov     g12q, -1
        bzhi    g12q, g12q, g6q
        kmovq   k1, g12q
        kshiftrq k2, k1, 16
        kshiftrq k3, k1, 32
        kshiftrq k4, k1, 48
        vmovdqu32 zmm0{k1}{z}, [g8q+0*64]       ; missing edges: all zero, p1 = p2
        vmovdqu32 zmm1{k2}{z}, [g8q+1*64]
        vmovdqu32 zmm2{k3}{z}, [g8q+2*64]
        vmovdqu32 zmm3{k4}{z}, [g8q+3*64]
        mov     g6d, -1
        bzhi    g6d, g6d, g3d
        kmovw   k1, g6d                        ; the edges that exist
%endif
        vmovdqa64 zmm4, zmm27
        vmovdqa64 zmm5, zmm27
        vpermi2d zmm4, zmm0, zmm1               ; p1 of edges 0-7, then their p2
        vpermi2d zmm5, zmm2, zmm3               ; of edges 8-15
        vshufi64x2 zmm6, zmm4, zmm5, 0x44       ; P1
        vshufi64x2 zmm7, zmm4, zmm5, 0xEE       ; P2
        vpmaxud zmm12, zmm12, zmm6
        vpmaxud zmm13, zmm13, zmm7
%if %1 == 0
        vpminud zmm14, zmm14, zmm6
        vpminud zmm15, zmm15, zmm7
%else
        vpminud zmm14{k1}, zmm14, zmm6          ; the edges that exist
        vpminud zmm15{k1}, zmm15, zmm7
%endif
        vmovdqa64 [rsp+SIL_P1P2+g7q+0], zmm6
        vmovdqa64 [rsp+SIL_P1P2+g7q+64], zmm7
%endmacro

; The largest (%1 = vpmaxud) or smallest (vpminud) lane of zmm %2 | %3
; into %4 (32-bit register); %2, %3 are destroyed.
%macro SIL_REDUCE 4
        %1      zmm%2, zmm%2, zmm%3
        vextracti64x4 ymm%3, zmm%2, 1
        %1      ymm%2, ymm%2, ymm%3
        vextracti128 xmm%3, ymm%2, 1
        %1      xmm%2, xmm%2, xmm%3
        vpshufd xmm%3, xmm%2, SHUFFLE_D(2, 3, 0, 1)
        %1      xmm%2, xmm%2, xmm%3
        vpshufd xmm%3, xmm%2, SHUFFLE_D(1, 0, 3, 2)
        %1      xmm%2, xmm%2, xmm%3
        vmovd   %4, xmm%2
%endmacro

; Facing bits of the 16 triangle numbers in %1 (each in the window) into
; mask %2, from the circular bitmap in zmm28-zmm31: bit p mod 2048, i.e.
; dword (p >> 5) mod 64 (dwords 0-15, 16-31, 32-47, 48-63), bit p mod 32.
; %3, %4: scratch vectors; k5, k6 scratch.
%macro SIL_BITS 4
        vpsrld  %3, %1, 5                       ; dword of the bit (mod 64 below)
        vptestmd k5, %3, [sil_c32]{1to16}       ; dwords 32-63
        knotw   k6, k5
        vmovdqa64 %4, %3
        vpermi2d %4{k6}, zmm28, zmm29           ; lanes of dwords 0-31 (mod 32)
        vpermi2d %4{k5}, zmm30, zmm31           ; the others (index kept)
        vprorvd %4, %4, %1                      ; bit p % 32 to bit 0
        vptestmd %2, %4, [sil_c1]{1to16}
%endmacro

; The two lists from F1 (k1) and F2 (k2) of the block: byte offsets of the
; silhouette edges (zmm26: this block's) and 64 * f1, at r13.
%macro SIL_EMIT 0
        kxorw   k3, k1, k2                      ; S (a missing edge has p1 = p2)
        vpcompressd zmm10{k3}{z}, zmm26         ; offsets of the silhouette edges
        vpbroadcastd zmm11{k1}{z}, [sil_c64]    ; 64 * f1
        vpcompressd zmm11{k3}{z}, zmm11
        kmovw   g6d, k3
        vmovdqu32 [rsp+SIL_LIST_OFS+g11q*4], zmm10
        vmovdqu32 [rsp+SIL_LIST_F1+g11q*4], zmm11
        popcnt  g6d, g6d
        add     g11q, g6q
        vpaddd  zmm26, zmm26, [sil_c256]{1to16}
%endmacro

VEC_ZMM
FUNC sv_create_sil_triangles_avx512
        mov     g4q, g0q                       ; output pointer
        mov     rvd, g3d                      ; numSilEdges
        test    rvd, rvd
        jle     .zero                           ; negative or zero: touch nothing
        cmp     rvd, SIL_AVX2_ABOVE
        jg      .avx2                           ; a large mesh: the AVX2 kernel

        PROLOGUE 4, 14, 32, shadowIndices, facing, silEdges, numSilEdges
        mov     g9q, rsp
        sub     rsp, 4096
        or      qword [rsp], 0                  ; probe the first page
        sub     rsp, SIL_FRAME - 4096
        and     rsp, -64
        mov     [rsp+SIL_BASE], g4q              ; (the second page)
        mov     g0q, g1q                        ; facing
        xor     g3d, g3d
        mov     [rsp+SIL_WLO], g3q              ; no window yet
        mov     [rsp+SIL_WEND], g3q
        vmovdqa64 zmm27, [sil_pick_p]
        vmovdqa64 zmm25, [sil_pair]
        lea     g13q, [sil_pat2]

.chunk:                                         ; rdx: the chunk's edges
        mov     g10q, rvq
        mov     g3d, SIL_CHUNK
        cmp     g10q, g3q
        cmova   g10q, g3q                        ; edges in this chunk
        sub     rvq, g10q                        ; edges after it

        ; Pass A: pairs, their minimum and maximum.
        vpxord  xmm12, xmm12, xmm12
        vpxord  xmm13, xmm13, xmm13
        vpternlogd zmm14, zmm14, zmm14, 0xFF
        vpternlogd zmm15, zmm15, zmm15, 0xFF
        mov     g8q, g2q
        xor     g7d, g7d                      ; pairs offset
        mov     g3q, g10q
        sub     g3q, 16
        jb      .a_tail
.a_loop:
        SIL_PAIRS 0
        add     g8q, 256
        add     g7q, 128
        sub     g3q, 16
        jae     .a_loop
.a_tail:
        add     g3q, 16                         ; 0-15 (only in the last chunk)
        jz      .a_done
        SIL_PAIRS 1
.a_done:
        SIL_REDUCE vpmaxud, 12, 13, g6d        ; hi
        SIL_REDUCE vpminud, 14, 15, g1d         ; lo
        and     g1d, -64                        ; lo64
        mov     g3d, g6d
        sub     g3d, g1d
        cmp     g3d, 2048
        jae     .chunk_via_avx2                         ; too wide for the bitmap
        lea     g7d, [g6q+1]                   ; the bytes needed end here
        mov     g3q, [rsp+SIL_WEND]
        cmp     g1q, [rsp+SIL_WLO]
        jb      .window                         ; below the window: a new one
        cmp     g1q, g3q
        jae     .window                         ; above it: a new one
        mov     [rsp+SIL_WLO], g1q              ; lo64 .. old end: still there
        cmp     g7q, g3q
        jbe     .b                              ; the window covers lo .. hi
        mov     g1q, g3q                        ; extend it: from the 64 bytes
        and     g1d, -64                        ; that hold its last byte
        jmp     .fill
.window:
        mov     [rsp+SIL_WLO], g1q              ; a new window at lo64
.fill:  ; the bits of facing[rsi .. r11) (rsi a multiple of 64) into the
        ; circular bitmap: byte p at bit p mod 2048, 64 bytes per vptestmb;
        ; the last load masked: nothing past facing[hi] is read. What it
        ; overwrites lies below lo64 (hi + 1 - lo64 <= 2048).
        mov     [rsp+SIL_WEND], g7q
        sub     g7d, g1d                       ; bytes, 1 .. 2048
        mov     g3d, g1d
        shr     g3d, 3                          ; its bitmap qword, times 8
        add     g1q, g0q
.fill64:
        mov     g8d, 64
        cmp     g7d, g8d
        cmovb   g8d, g7d                       ; min(bytes left, 64)
        mov     g6q, -1
        bzhi    g6q, g6q, g8q                   ; (bzhi reads 8 bits of the count)
        kmovq   k1, g6q
        vmovdqu8 zmm0{k1}{z}, [g1q]
        vptestmb k1, zmm0, zmm0
        and     g3d, 255
        kmovq   [rsp+SIL_BM+g3q], k1
        add     g3d, 8
        add     g1q, 64
        sub     g7d, 64
        jg      .fill64
        vmovdqa64 zmm28, [rsp+SIL_BM+0*64]      ; (bits outside lo64 .. hi: never
        vmovdqa64 zmm29, [rsp+SIL_BM+1*64]      ;  looked up)
        vmovdqa64 zmm30, [rsp+SIL_BM+2*64]
        vmovdqa64 zmm31, [rsp+SIL_BM+3*64]

.b:     ; Pass B with the bitmap.
        xor     g11d, g11d                      ; list length
        vmovdqa64 zmm26, [sil_off]              ; 16 * t
        xor     g7d, g7d
        lea     g8q, [g10q+15]
        shr     g8q, 4                          ; blocks (the last may be partial)
.b_loop:
        vmovdqa64 zmm4, [rsp+SIL_P1P2+g7q+0]      ; P1
        vmovdqa64 zmm5, [rsp+SIL_P1P2+g7q+64]     ; P2
        SIL_BITS zmm4, k1, zmm6, zmm7           ; F1: bit t = f1 of edge t
        SIL_BITS zmm5, k2, zmm8, zmm9           ; F2
        SIL_EMIT
        add     g7q, 128
        sub     g8q, 1
        jnz     .b_loop
        jmp     .c

.chunk_via_avx2:        ; A chunk too wide for the bitmap: the AVX2 kernel does it
        ; (its scalar lookups measured faster on such chunks than sixteen
        ; lookups folded into masks here: docs/BENCHMARK.md).
        ; An ordinary System V call: what must survive goes to the frame,
        ; and the vector registers kept across chunks are reloaded after.
        mov     [rsp+SIL_SAVE_AFTER], rvq
        mov     [rsp+SIL_SAVE_EDGES], g2q
        mov     [rsp+SIL_SAVE_FACING], g0q
        mov     [rsp+SIL_SAVE_OUT], g4q
        mov     g1q, g0q                        ; facing
        mov     g0q, g4q                         ; output
        mov     g3d, g10d                       ; edges in the chunk (<= 448)
        CALL_SV    sv_create_sil_triangles_avx2
        mov     g4q, [rsp+SIL_SAVE_OUT]
        mov     rvd, rvd                        ; an int: its upper half is undefined
        lea     g4q, [g4q+rvq*4]                  ; past the ints it wrote (>= 0)
        mov     rvq, [rsp+SIL_SAVE_AFTER]
        mov     g2q, [rsp+SIL_SAVE_EDGES]
        mov     g0q, [rsp+SIL_SAVE_FACING]
        vmovdqa64 zmm27, [sil_pick_p]
        vmovdqa64 zmm25, [sil_pair]
        vmovdqa64 zmm28, [rsp+SIL_BM+0*64]      ; the window, as it was
        vmovdqa64 zmm29, [rsp+SIL_BM+1*64]
        vmovdqa64 zmm30, [rsp+SIL_BM+2*64]
        vmovdqa64 zmm31, [rsp+SIL_BM+3*64]
        jmp     .c_done

.c:     ; Pass C: the six ints of each listed edge, two edges at a time
        mov     g3d, 0xFFF
        kmovw   k6, g3d                         ; twelve ints
        mov     g3d, 0x3F
        kmovw   k7, g3d                         ; six ints
        xor     g3d, g3d
        sub     g11q, 2
        jb      .c_one
.c_loop:
        mov     g6d, [rsp+SIL_LIST_OFS+g3q*4]        ; byte offsets of edges a, b
        mov     g7d, [rsp+SIL_LIST_OFS+g3q*4+4]
        vpbroadcastq zmm0, [g2q+g6q+8]          ; (v1, v2) of a, eight times
        vpbroadcastq zmm1, [g2q+g7q+8]          ; of b
        mov     g6d, [rsp+SIL_LIST_F1+g3q*4]        ; 64 * f1 of a, b
        mov     g7d, [rsp+SIL_LIST_F1+g3q*4+4]
        lea     g6q, [g7q+g6q*2]                ; their pattern pair
        vpermt2d zmm0, zmm25, zmm1              ; a: v1 v2 v2 v1 v1 v2, then b's
        vpxord  zmm0, zmm0, [g13q+g6q]           ; the ^1 patterns of f1a, f1b
        vmovdqu32 [g4q]{k6}, zmm0                ; twelve ints
        add     g4q, 48
        add     g3q, 2
        cmp     g3q, g11q
        jbe     .c_loop
.c_one:
        add     g11q, 2
        cmp     g3q, g11q
        jae     .c_done
        mov     g6d, [rsp+SIL_LIST_OFS+g3q*4]        ; an odd one left
        mov     g7d, [rsp+SIL_LIST_F1+g3q*4]
        vpbroadcastq zmm0, [g2q+g6q+8]
        vpermt2d zmm0, zmm25, zmm0
        vpxord  zmm0, zmm0, [g13q+g7q*2]         ; (f1, 0): lanes 0-5 are f1's
        vmovdqu32 [g4q]{k7}, zmm0                ; six ints
        add     g4q, 24
.c_done:
        shl     g10q, 4
        add     g2q, g10q                        ; next chunk
        test    rvq, rvq
        jnz     .chunk

        mov     rvq, g4q
        sub     rvq, [rsp+SIL_BASE]
        shr     rvq, 2                          ; ints written
        mov     rsp, g9q
        RET

.zero:
        xor     rvd, rvd
        RET_NOFRAME clean
.avx2:  ; same arguments, same registers: a tail call
        TAIL_SV sv_create_sil_triangles_avx2, clean
ENDFUNC
