; count_facing_cull_avx512.asm: CountFacingCull with AVX-512 (x86-64-v4).
;
; Computes: for each triangle i with facing[i] == 0, c = cullBits[i0] &
;   cullBits[i1] & cullBits[i2]; if c != 0 (any bit, bit 7 included),
;   facing[i] = 1. Returns the number of facing bytes set afterwards:
;   exactly section 5's C for facing bytes of 0 or 1.
; Approach: not a port. Section 5's C skips the lookups of facing triangles
;   with a branch per triangle (a misprediction wherever the predictor
;   has not learnt the facing pattern); appendix D looks up the three cull
;   bytes of EVERY triangle. This looks up only the non-facing ones,
;   without a branch per triangle: two passes over chunks of up to 960
;   triangles.
;   1. List: per 16 triangles, vptestnmb of the facing bytes is the mask of
;      the non-facing ones; vpcompressd (to a register) packs their
;      triangle numbers, one 64-byte store appends them to a list on the
;      stack, and popcnt advances its end.
;   2. Cull: per listed triangle t, its three vertex numbers (one qword
;      load for i0, i1 and one for i2: the loads are what limits this
;      loop), the AND of their cull bytes (movzx, then `and` with memory
;      operands, which sets ZF), and facing[t] = (c != 0) with setnz; four
;      per iteration, the list padded with copies of its last entry (which
;      store the same byte again). Unlike appendix D's signed pcmpgtb
;      (limit D-5), c = 0x80 culls.
;   3. The count: the facing bytes afterwards, summed by a tail call of
;      sv_count_facing_avx512.
;   The lookups stay scalar: on the reference machine (AMD Zen 5 class) a
;   vpgatherdd zmm costs more than its 16 lanes as scalar loads, whatever
;   the mask, and blocks the load ports meanwhile (docs/BENCHMARK.md, "Design measurements"). The only data-dependent branch is
;   the exit of pass 2's loop, once per chunk.
;
; int sv_count_facing_cull_avx512(uint8_t *facing, int numTriangles,
;                                 const int *indices, const uint8_t *cullBits)
;
; Register map (asm/sv_abi.inc names; rv = rax):
;   g10q  facing, g11q numTriangles (both kept for the count's tail call)
;   g0q  the chunk's facing, g2q its indices; g3q cullBits
;   g1q  triangles after this chunk; g8q triangles in the chunk
;   g9q  the frame (rsp is 64-byte aligned below it); g13q list length
;   g12q  pass 1's block counter, pass 2's list position
;   rvq, g4q-g7q scratch
;   zmm0 triangle numbers of the block (lane t: 16b + t); xmm1 sixteen
;   bytes of 0xFF; zmm2 the packed list entries; k1 non-facing; k2 tail
;   [rsp] the list: CFC_CHUNK + 16 dwords (3.8 KiB; with the pushes and
;   the 64-byte alignment still under a page: no
;   stack probe needed)
;
; Contracts: facing bytes 0 or 1 (only 0 is looked up; the count sums
;   bytes); vertex numbers valid indices into cullBits (read with movsxd,
;   as C indexes with an int; read only for the non-facing triangles, as
;   the C does); all 8 cull bits count. No alignment. numTriangles >= 0
;   (negative or zero: returns 0, touches nothing). Reads exactly
;   facing[0 .. n-1]; writes only facing bytes that were 0.
;
; Cost: not kept here (figures go stale); `shadowvol bench` measures it
;   on the machine at hand and docs/BENCHMARK.md has the current table.
;
; Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.

%include "sv_abi.inc"

SV_EXTERN sv_count_facing_avx512

%define CFC_CHUNK 960                           ; triangles per list (x 16)

RODATA
cfc_iota:
%assign i 0
%rep 16
        dd i
%assign i i+1
%endrep
cfc_c16: dd 16

; One listed triangle: list entry r14 + %1.
%macro CFC_ENTRY 1
        mov     rvd, [rsp+g12q*4+%1*4]           ; t (in the chunk)
        lea     g4q, [rvq+rvq*2]
        mov     g5q, [g2q+g4q*4]                  ; i0 | i1 << 32
        movsxd  g7q, dword [g2q+g4q*4+8]         ; i2
        movsxd  g6q, g5d                        ; i0
        sar     g5q, 32                          ; i1
        movzx   g6d, byte [g3q+g6q]
        and     g6b, [g3q+g5q]
        and     g6b, [g3q+g7q]                 ; c; ZF = (c == 0)
        setnz   g6b
        mov     [g0q+rvq], g6b                 ; 0 -> 1 when culled
%endmacro

VEC_ZMM
FUNC sv_count_facing_cull_avx512
        mov     g1d, g1d                      ; numTriangles
        test    g1d, g1d
        jle     .zero                           ; negative or zero: touch nothing
        PROLOGUE 4, 14, 4, facing, numTriangles, indices, cullBits
        mov     g9q, rsp
        sub     rsp, (CFC_CHUNK + 16) * 4
        and     rsp, -64
        mov     g10q, g0q                        ; facing
        mov     g11d, g1d                       ; numTriangles
        vpternlogd xmm1, xmm1, xmm1, 0xFF       ; all ones

.chunk:
        mov     g8d, CFC_CHUNK
        cmp     g1q, g8q
        cmovb   g8q, g1q                        ; triangles in this chunk
        sub     g1q, g8q

        ; pass 1: the list of non-facing triangles
        xor     g13d, g13d
        vmovdqa64 zmm0, [cfc_iota]
        mov     g12q, g8q
        xor     g4d, g4d                        ; block offset
        sub     g12q, 16
        jb      .p1_tail
.p1_loop:
        vptestnmb k1, xmm1, [g0q+g4q]            ; facing == 0
        kmovw   rvd, k1
        vpcompressd zmm2{k1}{z}, zmm0
        vmovdqu32 [rsp+g13q*4], zmm2
        popcnt  rvd, rvd
        add     g13q, rvq
        vpaddd  zmm0, zmm0, [cfc_c16]{1to16}
        add     g4q, 16
        sub     g12q, 16
        jae     .p1_loop
.p1_tail:
        add     g12q, 16                         ; 0-15 (only in the last chunk)
        jz      .p2
        mov     rvq, -1
        bzhi    rvq, rvq, g12q
        kmovw   k2, rvd
        vmovdqu8 xmm3{k2}{z}, [g0q+g4q]          ; only the bytes that exist
        vptestnmb k1{k2}, xmm3, xmm3
        kmovw   rvd, k1
        vpcompressd zmm2{k1}{z}, zmm0
        vmovdqu32 [rsp+g13q*4], zmm2
        popcnt  rvd, rvd
        add     g13q, rvq

.p2:    ; pass 2: cull the listed triangles, four per iteration; the list
        ; is padded to a multiple of four with copies of its last entry
        ; (the same byte stored again: the count comes afterwards)
        test    g13q, g13q
        jz      .p2_done
        mov     rvd, [rsp+g13q*4-4]
        mov     [rsp+g13q*4+0], rvd
        mov     [rsp+g13q*4+4], rvd
        mov     [rsp+g13q*4+8], rvd
        xor     g12d, g12d
.p2_loop:
        CFC_ENTRY 0
        CFC_ENTRY 1
        CFC_ENTRY 2
        CFC_ENTRY 3
        add     g12q, 4
        cmp     g12q, g13q
        jb      .p2_loop
.p2_done:
        lea     rvq, [g8q+g8q*2]
        lea     g2q, [g2q+rvq*4]                ; next chunk
        add     g0q, g8q
        test    g1q, g1q
        jnz     .chunk

        mov     g0q, g10q
        mov     g1d, g11d
        mov     rsp, g9q
        RET_VIA sv_count_facing_avx512, clean ; the count (vzeroupper there)

.zero:
        xor     rvd, rvd
        RET_NOFRAME clean
ENDFUNC
