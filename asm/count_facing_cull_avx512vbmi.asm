; count_facing_cull_avx512vbmi.asm: CountFacingCull with the cull bytes
; held in registers (x86-64-v4 + AVX512_VBMI).
;
; Computes: for each triangle i with facing[i] == 0, c = cullBits[i0] &
;   cullBits[i1] & cullBits[i2]; if c != 0 (any of the 8 bits), facing[i]
;   = 1. Returns the number of facing bytes set afterwards: section 5's C
;   for facing bytes of 0 or 1.
; Approach: not a port, and no lookups through memory. Every other
;   CountFacingCull looks the three cull bytes of a triangle up with loads
;   (the AVX2 and AVX-512 kernels for the non-facing triangles only), and
;   those dependent loads are what they spend their time on (`shadowvol
;   bench --limits`). Here, when every vertex number is below 1024, the
;   whole cullBits table sits in zmm16-zmm31 (16 x 64 bytes) and a lookup
;   is a byte permute:
;   0. The largest vertex number, M (vpmaxud over the 3n indices, the tail
;      masked). M >= 1024: the call goes to sv_count_facing_cull_avx512 (a
;      tail call; same arguments), as soon as a block of 128 numbers shows
;      it (a full scan first made this variant slower than c_ref on the
;      large meshes: docs/BENCHMARK.md, "Design measurements").
;   1. The table: cullBits[0 .. M] into zmm16 .. zmm(16 + M / 64), plain
;      loads; the last, partial register is the 64 bytes ending at
;      cullBits[M] moved into place by vpermb (a masked load only when the
;      whole table is under 64 bytes). The registers above are not loaded:
;      no vertex number picks them.
;   2. Per block of 64 triangles, three groups of 64 vertex numbers: four
;      loads, two vpermt2b (one control vector) pick the low and the second
;      byte of every dword, two vshufi64x2 put them in L (bits 0-7 of the
;      64 numbers) and H (bits 8-15). Eight vpermi2b look L up in the eight
;      table pairs (128 bytes each: bit 6 picks the register, bits 0-5 the
;      byte), and a tree of seven vpblendmb picks the pair by bit 7
;      (vpmovb2m of L), bit 8 and bit 9 (vptestmb of H): the 64 cull bytes,
;      in index order.
;      The 192 bytes of a block are de-interleaved into c0, c1, c2 (byte t:
;      vertex k of triangle t) by one vpermi2b over the first two groups and
;      a merge-masked vpermb from the third, per k; vpternlogd ANDs them;
;      vptestmb (c != 0) ANDed with vptestnmb of the facing bytes (== 0) is
;      the mask of a masked store of 1s: on this path only facing bytes
;      that were 0 and are culled are written (the list kernel, for M >=
;      1024, also stores the 0 back into the others it looks up).
;      The last 1-63 triangles: with n >= 64, the last 64 triangles run as
;      one more block, overlapping the one before, with plain loads and k4
;      keeping the r new ones; with n < 64, their 3 n vertex numbers are
;      copied to the frame (masked loads, only as many 64-byte groups as
;      hold them). The maximum's last numbers are likewise the 32 ending
;      the array, read again.
;      Why so few masked loads: on the reference machine a masked load
;      whose masked-off part lies on a page that is unmapped or not yet
;      touched costs several times a whole small call, even when it reads
;      no byte there (timed with the arrays ending at such a page; the
;      figures: docs/BENCHMARK.md, "Design measurements"). Left: a table
;      under 64 bytes and meshes under 64 triangles. The other AVX-512
;      kernels' masked tails still pay it.
;   3. The count: a tail call of sv_count_facing_avx512.
;   No branch on the facing or cull data: the work is the same for every
;   pattern (all triangles are looked up, facing or not). The only branch
;   on the indices is the test of the running maximum, once per 128 vertex
;   numbers and once at the end. Gathers are not used: a
;   vpgatherdd lane costs more than three scalar loads on the reference
;   machine (`bench --limits`).
;
; int sv_count_facing_cull_avx512vbmi(uint8_t *facing, int numTriangles,
;                                     const int *indices, const uint8_t *cullBits)
;
; Register map (asm/sv_abi.inc names; rv = rax):
;   g0q  facing of the block, g2q its vertex numbers, g3q cullBits
;   rvd  numTriangles; g4q triangles left; g5q-g7q scratch
;   g9q  facing, g10q numTriangles (kept for the count's tail call)
;   g8q  the frame (rsp 64-byte aligned below it: the tail's 192 numbers)
;   (steps 0 and 1, the maximum and the table, run before PROLOGUE on
;   System V and after it on win64, where g6, g7 and xmm13 are callee-saved:
;   see CFV_EARLY_FRAME)
;   zmm16-zmm31 cullBits[0 .. 1023] (above M's register: not loaded);
;   zmm13 the last table register's realignment
;   zmm0-zmm8 group scratch; zmm9-zmm11 the block's three groups of cull
;   bytes; zmm12 the byte-pick control; zmm15 64 bytes of 1
;   k1-k3 a group's bits 7-9, then the store mask; k4 the block's existing
;   triangles; k5, k6 the de-interleave's third-group lanes
;
; Contracts: facing bytes 0 or 1 (only 0 is culled; the count sums bytes);
;   vertex numbers valid indices into cullBits (non-negative ints, as the
;   checked entry point requires); all 8 cull bits count. No alignment.
;   numTriangles >= 0 (negative or zero: returns 0, touches nothing).
;   Reads exactly facing[0 .. n-1], indices[0 .. 3n-1] and cullBits[0 ..
;   M]; writes only facing bytes that were 0. Needs AVX512_VBMI (vpermb,
;   vpermi2b, vpermt2b) on top of x86-64-v4: the caller checks CPUID
;   (SV_ISA_AVX512_VBMI). Stack: under 1 KiB.
;
; Cost: not kept here (figures go stale); `shadowvol bench` measures it
;   on the machine at hand and docs/BENCHMARK.md has the current table.
;
; Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.

%include "sv_abi.inc"

SV_EXTERN sv_count_facing_cull_avx512
SV_EXTERN sv_count_facing_avx512

%define CFV_MAX_VERTS 1024              ; 16 zmm registers of 64 cull bytes

RODATA
align 64
; vpermt2b control over (A | B), 32 dwords: bytes 0-31 the low byte of
; dword 0-31, bytes 32-63 its second byte.
cfv_pick:
%assign p 0
%rep 64
%if p < 32
%assign i p
%assign o 0
%else
%assign i p - 32
%assign o 1
%endif
%if i < 16
        db 4*i + o
%else
        db 64 + 4*(i - 16) + o
%endif
%assign p p+1
%endrep
cfv_last: dd CFV_MAX_VERTS - 1
align 64
cfv_one: times 64 db 1
cfv_iota:
%assign i 0
%rep 64
        db i
%assign i i+1
%endrep
cfv_two: times 64 db 2
; De-interleave: vertex k of triangle t is byte s = 3t + k of the block's
; 192 cull bytes (groups G0 | G1 | G2). cfv_lo_k: s for s < 128 (vpermi2b
; over G0 | G1); cfv_hi_k: s - 128 for s >= 128 (vpermb of G2).
%assign k 0
%rep 3
cfv_lo_ %+ k:
%assign t 0
%rep 64
%assign s 3*t + k
%if s < 128
        db s
%else
        db 0
%endif
%assign t t+1
%endrep
cfv_hi_ %+ k:
%assign t 0
%rep 64
%assign s 3*t + k
%if s >= 128
        db s - 128
%else
        db 0
%endif
%assign t t+1
%endrep
%assign k k+1
%endrep

; CFV_GROUP src, dst: the cull bytes of the 64 vertex numbers at src.
%macro CFV_GROUP 2
        vmovdqu32 zmm0, [%1 + 0*64]
        vmovdqu32 zmm1, [%1 + 1*64]
        vmovdqu32 zmm2, [%1 + 2*64]
        vmovdqu32 zmm3, [%1 + 3*64]
        vpermt2b zmm0, zmm12, zmm1              ; low | second bytes of 0-31
        vpermt2b zmm2, zmm12, zmm3              ; of 32-63
        vshufi64x2 zmm4, zmm0, zmm2, 0x44       ; L: bits 0-7 of the 64
        vshufi64x2 zmm5, zmm0, zmm2, 0xEE       ; H: bits 8-15
        vpmovb2m k1, zmm4                       ; bit 7: odd pair
        vptestmb k2, zmm5, [cfv_one]            ; bit 8
        vptestmb k3, zmm5, [cfv_two]            ; bit 9
        vmovdqa64 zmm0, zmm4
        vpermi2b zmm0, zmm16, zmm17             ; pair 0: vertices 0-127
        vmovdqa64 zmm1, zmm4
        vpermi2b zmm1, zmm18, zmm19
        vmovdqa64 zmm2, zmm4
        vpermi2b zmm2, zmm20, zmm21
        vmovdqa64 zmm3, zmm4
        vpermi2b zmm3, zmm22, zmm23
        vmovdqa64 zmm6, zmm4
        vpermi2b zmm6, zmm24, zmm25
        vmovdqa64 zmm7, zmm4
        vpermi2b zmm7, zmm26, zmm27
        vmovdqa64 zmm8, zmm4
        vpermi2b zmm8, zmm28, zmm29
        vpermi2b zmm4, zmm30, zmm31             ; pair 7: vertices 896-1023
        vpblendmb zmm0{k1}, zmm0, zmm1          ; by bit 7: pairs 0|1
        vpblendmb zmm2{k1}, zmm2, zmm3          ;   2|3
        vpblendmb zmm6{k1}, zmm6, zmm7          ;   4|5
        vpblendmb zmm8{k1}, zmm8, zmm4          ;   6|7
        vpblendmb zmm0{k2}, zmm0, zmm2          ; by bit 8
        vpblendmb zmm6{k2}, zmm6, zmm8
        vpblendmb %2{k3}, zmm0, zmm6            ; by bit 9
%endmacro

; CFV_DEINTERLEAVE k, dst, mask: vertex k's cull bytes of the 64 triangles.
%macro CFV_DEINTERLEAVE 3
        vmovdqa64 %2, [cfv_lo_ %+ %1]
        vpermi2b %2, zmm9, zmm10
        vmovdqa64 zmm1, [cfv_hi_ %+ %1]
        vpermb  %2{%3}, zmm1, zmm11
%endmacro

; CFV_BLOCK: 64 triangles, vertex numbers at rdx, facing at rdi, k4 the
; triangles that exist.
%macro CFV_BLOCK 0
        CFV_GROUP g2q, zmm9
        CFV_GROUP g2q + 256, zmm10
        CFV_GROUP g2q + 512, zmm11
        CFV_DEINTERLEAVE 0, zmm0, k5
        CFV_DEINTERLEAVE 1, zmm2, k5
        CFV_DEINTERLEAVE 2, zmm3, k6
        vpternlogd zmm0, zmm2, zmm3, 0x80       ; c = c0 & c1 & c2
        vmovdqu8 zmm1{k4}{z}, [g0q]             ; only the bytes that exist
        vptestnmb k1{k4}, zmm1, zmm1            ; facing == 0
        vptestmb k1{k1}, zmm0, zmm0             ; and c != 0
        vmovdqu8 [g0q]{k1}, zmm15               ; facing = 1
%endmacro

; CFV_TABLE j: register 16 + j of the table; r10 = M + 1 bytes in all. A
; whole register: one plain load. The last, partial one (1-63 bytes left):
; for j > 0 the 64 bytes ending at cullBits[M] (M >= 64 here) are loaded
; without a mask and moved into place by vpermb (byte b of the register is
; byte b + 64 - left of the load; the bytes past M get garbage, never
; picked); for j = 0 (M < 63: the table is shorter than a register) a
; zero-masked load of the M + 1 bytes is the only way.
%macro CFV_TABLE 1
%assign reg 16+%1
        mov     g7q, g6q
        sub     g7q, 64*%1                      ; bytes of it from 64 j on
%if %1 > 0
        jle     .tables_done                    ; none: the registers above M's
%endif                                          ; are never picked, not loaded
        cmp     g7q, 64
        jb      %%last
        vmovdqu8 zmm%[reg], [g3q+64*%1]
        jmp     %%next
%%last:
%if %1 == 0
        mov     g5q, -1
        bzhi    g5q, g5q, g7q                     ; (1-63: bzhi reads 8 bits of it)
        kmovq   k1, g5q
        vmovdqu8 zmm%[reg]{k1}{z}, [g3q]
%else
        mov     g5d, 64
        sub     g5d, g7d                       ; 64 - left
        vpbroadcastb zmm13, g5d
        vpaddb  zmm13, zmm13, [cfv_iota]
        vmovdqu8 zmm%[reg], [g3q+g6q-64]        ; cullBits[M - 63 .. M]
        vpermb  zmm%[reg], zmm13, zmm%[reg]
%endif
        jmp     .tables_done
%%next:
%endmacro

; Where the frame is made. Steps 0 and 1 run before PROLOGUE on System V:
; they use g4-g7 (r8-r11, scratch there) and zmm13, zmm16-31, none of them
; callee-saved, and the path that leaves for the list kernel (.list) then
; needs no frame at all. On win64 g6, g7 are rdi, rsi and xmm13 is
; callee-saved, so the frame comes first there and .list leaves through
; the epilogue (RET_VIA) instead of a bare tail call.
%ifdef SV_WIN64
    %define CFV_EARLY_FRAME 1
%endif

VEC_ZMM
FUNC sv_count_facing_cull_avx512vbmi
        mov     rvd, g1d                      ; numTriangles
        test    rvd, rvd
        jle     .zero                           ; negative or zero: touch nothing
%ifdef CFV_EARLY_FRAME
        PROLOGUE 4, 11, 32, facing, numTriangles, indices, cullBits
%endif

        ; 0. M, the largest vertex number (unsigned). Every 128 numbers the
        ;    running maximum is tested against the table's size: a large
        ;    mesh leaves for the list kernel after its first vertex number
        ;    of 1024 or more, not after reading all of its indices.
        lea     g4q, [rvq+rvq*2]                 ; vertex numbers
        xor     g5d, g5d
        vpxord  xmm0, xmm0, xmm0
        vpxord  xmm1, xmm1, xmm1
        vpbroadcastd zmm2, [cfv_last]           ; 1023
        mov     g6q, g4q
        sub     g6q, 128
        jb      .max_rest
.max_loop128:
        vpmaxud zmm0, zmm0, [g2q+g5q*4]
        vpmaxud zmm1, zmm1, [g2q+g5q*4+64]
        vpmaxud zmm0, zmm0, [g2q+g5q*4+128]
        vpmaxud zmm1, zmm1, [g2q+g5q*4+192]
        vpmaxud zmm0, zmm0, [g2q+g5q*4+256]
        vpmaxud zmm1, zmm1, [g2q+g5q*4+320]
        vpmaxud zmm0, zmm0, [g2q+g5q*4+384]
        vpmaxud zmm1, zmm1, [g2q+g5q*4+448]
        vpmaxud zmm3, zmm0, zmm1
        vpcmpud k1, zmm3, zmm2, 6               ; > 1023
        kortestw k1, k1
        jnz     .list
        add     g5q, 128
        sub     g6q, 128
        jae     .max_loop128
.max_rest:
        add     g6q, 128                        ; 0-127 left
        sub     g6q, 32
        jb      .max_tail
.max_loop:
        vpmaxud zmm0, zmm0, [g2q+g5q*4]
        vpmaxud zmm1, zmm1, [g2q+g5q*4+64]
        add     g5q, 32
        sub     g6q, 32
        jae     .max_loop
.max_tail:
        add     g6q, 32                         ; 0-31 left
        jz      .max_reduce                     ; none: no load at all
        cmp     g4q, 32
        jb      .max_masked
        vpmaxud zmm0, zmm0, [g2q+g4q*4-128]      ; the last 32 numbers, some
        vpmaxud zmm1, zmm1, [g2q+g4q*4-64]       ; seen already: no mask needed
        jmp     .max_reduce
.max_masked:                                    ; under 32 numbers in all: (a
        mov     g7q, -1                         ; masked load over a page that
        bzhi    g7q, g7q, g6q                   ; is unmapped or never touched
        kmovd   k1, g7d                        ; is very slow here, even
        vmovdqu32 zmm2{k1}{z}, [g2q+g5q*4]       ; fully masked)
        vpmaxud zmm0, zmm0, zmm2
        cmp     g6q, 16
        jbe     .max_reduce                     ; none in the second vector
        kshiftrd k2, k1, 16
        vmovdqu32 zmm3{k2}{z}, [g2q+g5q*4+64]
        vpmaxud zmm1, zmm1, zmm3
.max_reduce:
        vpmaxud zmm0, zmm0, zmm1
        vextracti64x4 ymm1, zmm0, 1
        vpmaxud ymm0, ymm0, ymm1
        vextracti128 xmm1, ymm0, 1
        vpmaxud xmm0, xmm0, xmm1
        vpshufd xmm1, xmm0, SHUFFLE_D(2, 3, 0, 1)
        vpmaxud xmm0, xmm0, xmm1
        vpshufd xmm1, xmm0, SHUFFLE_D(1, 0, 3, 2)
        vpmaxud xmm0, xmm0, xmm1
        vmovd   g5d, xmm0                       ; M
        cmp     g5d, CFV_MAX_VERTS - 1
        ja      .list                           ; beyond the registers

        ; 1. cullBits[0 .. M] into zmm16 .. zmm(16 + M / 64) (CFV_TABLE)
        lea     g6q, [g5q+1]                     ; bytes of the table, 1-1024
%assign j 0
%rep 16
        CFV_TABLE j
%assign j j+1
%endrep
.tables_done:

%ifndef CFV_EARLY_FRAME
        PROLOGUE 4, 11, 32, facing, numTriangles, indices, cullBits
%endif
        mov     g8q, rsp
        sub     rsp, 768                        ; the tail's 192 vertex numbers
        and     rsp, -64
        mov     g9q, g0q
        mov     g10d, rvd
        vmovdqa64 zmm12, [cfv_pick]
        vmovdqa64 zmm15, [cfv_one]
        mov     g5q, -1
        shl     g5q, 43
        kmovq   k5, g5q                          ; t >= 43: 3t + k >= 128 (k = 0, 1)
        mov     g5q, -1
        shl     g5q, 42
        kmovq   k6, g5q                          ; t >= 42 (k = 2)
        kxnorq  k4, k0, k0                      ; every triangle of a block exists

        ; 2. blocks of 64 triangles
        mov     g4q, rvq
        sub     g4q, 64
        jb      .tail
.block:
        CFV_BLOCK
        add     g2q, 768
        add     g0q, 64
        sub     g4q, 64
        jae     .block
.tail:
        add     g4q, 64                          ; 1-63 left, or 0
        jz      .count
        cmp     g10d, 64
        jb      .tail_small
        ; n >= 64: the last 64 triangles, overlapping the block before, with
        ; plain loads; k4 keeps the r that are new
        lea     g5q, [g4q-64]                     ; r - 64 (< 0)
        add     g0q, g5q                         ; facing of triangle n - 64
        lea     g5q, [g5q+g5q*2]
        lea     g2q, [g2q+g5q*4]                 ; its vertex numbers
        mov     g6d, 64
        sub     g6d, g4d
        mov     g7q, -1
        shlx    g7q, g7q, g6q                   ; the top r bits
        kmovq   k4, g7q
        CFV_BLOCK
        jmp     .count
.tail_small:                                    ; n < 64: through the frame
        lea     g5q, [g4q+g4q*2]                   ; their vertex numbers, 3-189
%assign q 0
%rep 12
        mov     g6q, g5q
        sub     g6q, 16*q
%if q > 0
        jle     .tail_copied                    ; (the frame's lanes past them:
%endif                                          ;  triangles k4 leaves out)
        mov     g7d, 16
        cmp     g6q, g7q
        cmova   g6q, g7q                        ; at most 16
        mov     g7d, -1
        bzhi    g7d, g7d, g6d
        kmovw   k1, g7d
        vmovdqu32 zmm0{k1}{z}, [g2q+64*q]       ; nothing past the array
        vmovdqa64 [rsp+64*q], zmm0
%assign q q+1
%endrep
.tail_copied:
        mov     g7q, -1
        bzhi    g7q, g7q, g4q
        kmovq   k4, g7q                         ; the r triangles that exist
        mov     g2q, rsp
        CFV_BLOCK

        ; 3. the count
.count:
        mov     g0q, g9q
        mov     g1d, g10d
        mov     rsp, g8q
        RET_VIA sv_count_facing_avx512, clean ; (vzeroupper there)

.list:  ; same arguments, untouched
%ifdef CFV_EARLY_FRAME
        RET_VIA sv_count_facing_cull_avx512
%else
        TAIL_SV sv_count_facing_cull_avx512
%endif

.zero:
        xor     rvd, rvd
        RET_NOFRAME clean
ENDFUNC
