; count_facing_cull_avx2.asm: CountFacingCull for x86-64-v3 (AVX2, BMI2,
; POPCNT).
;
; Computes: for each triangle i with facing[i] == 0, c = cullBits[i0] &
;   cullBits[i1] & cullBits[i2]; if c != 0 (all eight bits count), facing[i]
;   = 1. Returns the number of facing bytes set afterwards. Exactly section
;   5's C, including a cull byte shared in bit 7 only (the sse2_paper limit
;   D-5 is not copied: the AND is tested for zero, not compared signed).
; Approach: not a port. Section 5's C skips the cull lookups of facing
;   triangles with a branch the predictor cannot learn for a moving light;
;   appendix D looks up all three cull bytes of EVERY triangle. This does
;   the lookups only for the non-facing ones, without a branch per triangle:
;   two passes over chunks of up to 992 triangles (the frame stays below a
;   page, so no stack probe is needed).
;   1. List: 32 facing bytes at a time, vpcmpeqb against zero + vpmovmskb
;      give a 32-bit mask of the non-facing triangles; per mask byte, a
;      256-entry table of packed bit positions (vpmovzxbd straight from
;      memory) plus the block's first triangle number are stored to a list
;      on the stack, and popcnt advances the list end: a branch-free
;      left-pack of the non-facing triangle numbers.
;   2. Cull: for each listed triangle t, its three vertex numbers (one
;      qword split by movsxd / sar, one movsxd), their three cull bytes
;      ANDed (`and r8b, [cullBits + v]` sets ZF) and facing[t] = (c != 0)
;      with setnz. Four per iteration; the list is padded with copies of
;      its last entry, which are harmless (the same byte is stored again
;      with the same value).
;   Gathers were measured first and lost: on the Zen 5-class core this
;   was written on, a vpgatherdd lane costs several scalar byte loads, so
;   the lookups stay scalar; the work saved is that of the facing
;   triangles (about half of them). Pass 2 is the cost: a chain of three
;   dependent loads (list entry, vertex numbers, cull bytes) and ~11
;   instructions per non-facing triangle.
;   Two other forms of CULL1's index loads were timed alone and were
;   slower: three movsxd loads instead of the split qword (the load ports
;   are what it is short of), and one 16-byte vmovdqu with vmovq and
;   vpextrd into GPRs (which would also read 4 bytes past the last
;   triangle). The figures: docs/BENCHMARK.md, "Design measurements".
;   The count is that of facing afterwards: a tail call of
;   sv_count_facing_avx2 (which is cheaper than keeping it exact across the
;   padded list).
;
; int sv_count_facing_cull_avx2(uint8_t *facing, int numTriangles,
;                               const int *indices, const uint8_t *cullBits)
;
; Register map (asm/sv_abi.inc names; rv = rax):
;   g10q facing       g11q numTriangles (64-bit, > 0)   g12q indices
;   g13q cullBits     g8q first triangle of the chunk  g9q list entries
;   g1q triangle of the current 32-block (pass 1), list index (pass 2)
;   g7q the position table; rvq, g3q, g2q, g0q, g4q-g6q scratch
;   ymm5 zero; ymm6 the current 8-block's first triangle, broadcast;
;   ymm7 eight, broadcast; ymm0, ymm1 scratch
;   [rsp] the list: LIST_ENTRIES dwords
;
; Contracts: no alignment; facing bytes 0 or 1; indices valid vertex numbers
;   into cullBits (read with movsxd, as C indexes with an int);
;   numTriangles >= 0 (negative or zero: returns 0, touches nothing). Reads
;   exactly facing[0 .. n-1] (the last partial 32-block is loaded as the 32
;   bytes ending at facing + n when n >= 32, else byte by byte), the indices
;   and cull bytes of the non-facing triangles only; writes only facing
;   bytes that were 0. Stack: < 4 KiB.
;
; Cost: not kept here (figures go stale); `shadowvol bench` measures it
;   on the machine at hand and docs/BENCHMARK.md has the current table.
;
; Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.

%include "sv_abi.inc"
%include "avx2_left_pack.inc"

SV_EXTERN sv_count_facing_avx2

%define CHUNK        992                  ; triangles per list (a multiple of 32)
%define LIST_ENTRIES (CHUNK + 16)         ; + 8 (a block's store) + 3 (padding)
%define FRAME        (LIST_ENTRIES*4)     ; + 6 pushes + return + 8 of padding: 4096

RODATA
align 64
; positions[m]: the indices of the set bits of m, in increasing order, one
; per byte, then zero bytes.
positions:
        SET_BIT_POSITIONS 1, 0
align 4
eight:  dd 8

; EMIT8 / EMIT32 and pass 1 (LIST_NONFACING): asm/avx2_left_pack.inc (r11 = the
; table above).

; CULL1 k: list entry k of the current group of four.
%macro CULL1 1
        mov     rvd, [rsp + g1q*4 + %1*4]      ; t
        lea     g3q, [rvq + rvq*2]             ; 3t
        mov     g0q, [g12q + g3q*4]             ; i0 | i1 << 32
        movsxd  g3q, dword [g12q + g3q*4 + 8]   ; i2
        movsxd  g2q, g0d                       ; i0
        sar     g0q, 32                        ; i1
        movzx   g4d, byte [g13q + g2q]
        and     g4b, [g13q + g0q]
        and     g4b, [g13q + g3q]
        setnz   g4b
        mov     [g10q + rvq], g4b
%endmacro

VEC_YMM
FUNC sv_count_facing_cull_avx2
        mov     rvd, g1d
        test    rvd, rvd
        jg      .start
        xor     rvd, rvd                ; negative or zero: 0, nothing touched
        RET_NOFRAME clean
.start:
        PROLOGUE 4, 14, 8, FRAME, facing, numTriangles, indices, cullBits
        mov     g10q, g0q
        mov     g11d, rvd               ; n, zero-extended
        mov     g12q, g2q
        mov     g13q, g3q
        lea     g7q, [positions]
        vpxor   xmm5, xmm5, xmm5
        vpbroadcastd ymm7, [eight]
        xor     g8d, g8d                ; chunk start

.chunk:
        ; ---- pass 1: list the non-facing triangles of [rbx, rbx + len)
        xor     g9d, g9d
        mov     g1q, g8q
        vmovd   xmm6, g8d
        vpbroadcastd ymm6, xmm6
        lea     g5q, [g8q + CHUNK]
        cmp     g5q, g11q
        cmova   g5q, g11q                 ; chunk end
        LIST_NONFACING g10q, g11q, g5q, g6q, .pass2

        ; ---- pass 2: the cull test for each listed triangle
.pass2:
        test    g9d, g9d
        jz      .next_chunk
        mov     rvd, [rsp + g9q*4 - 4]  ; pad to a multiple of 4 with the last
        mov     [rsp + g9q*4], rvd
        mov     [rsp + g9q*4 + 4], rvd
        mov     [rsp + g9q*4 + 8], rvd
        xor     g1d, g1d
.cull4:
        CULL1   0
        CULL1   1
        CULL1   2
        CULL1   3
        add     g1d, 4
        cmp     g1d, g9d
        jb      .cull4

.next_chunk:
        add     g8q, CHUNK
        cmp     g8q, g11q
        jb      .chunk

        ; ---- the count of facing bytes set now
        mov     g0q, g10q
        mov     g1d, g11d
        RET_VIA sv_count_facing_avx2
ENDFUNC
