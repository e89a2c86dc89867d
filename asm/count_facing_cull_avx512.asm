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
;   The lookups stay scalar: on the reference machine (AMD Zen 5 class)
;   vpgatherdd zmm costs about 13 cycles for 16 lanes, whatever the mask,
;   and blocks the load ports meanwhile. The only data-dependent branch is
;   the exit of pass 2's loop, once per chunk.
;
; int sv_count_facing_cull_avx512(uint8_t *facing, int numTriangles,
;                                 const int *indices, const uint8_t *cullBits)
;
; Register map:
;   r12  facing, r13 numTriangles (both kept for the count's tail call)
;   rdi  the chunk's facing, rdx its indices; rcx cullBits
;   rsi  triangles after this chunk; rbx triangles in the chunk
;   rbp  the frame (rsp is 64-byte aligned below it); r15 list length
;   r14  pass 1's block counter, pass 2's list position
;   rax, r8-r11 scratch
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
; Measured cost (`shadowvol bench --variant c_ref --variant sse2_paper
;   --variant avx512`, the 1344-triangle character, 4 runs, the lowest min
;   and lowest median of the runs; AMD EPYC "Turin-like" KVM guest (Zen 5
;   class), TSC 2.097 GHz, ticks):
;   moving light 1260 / 1302 (sse2_paper 1512 / 1596, c_ref 1386 / 1554);
;   fixed light 1197 / 1218 (sse2_paper 1533 / 1596, c_ref 1218 / 1239: the
;   predictor learns c_ref's branches there). About 11 instructions per
;   non-facing triangle, 6 of them loads: the loop runs at the ~4
;   instructions per cycle this guest sustains; the loads alone (3 per
;   cycle) would allow about 850 ticks.
;   Split, with a harness that times the kernel alone (lfence-fenced TSC,
;   random facing and cull bytes, median of 4000 calls): on 1344 triangles
;   pass 1 and the count take ~290 ticks here against ~230 for the AVX2
;   kernel's table left-pack (vpcompressd plus kmov plus popcnt per 16
;   costs more than two table loads per 16 on this core), pass 2 ~1060 in
;   both. Chunks grew from 512 to 960 triangles (one list for Fox.glb's
;   576, two for the character): Fox 586 -> 569 ticks per call. The AVX2
;   kernel stays the faster of the two on every mesh measured, by 3-7%.
;   `shadowvol bench --limits`: this routine's floor on the character is
;   ~410 ticks; the distance is pass 2's chain of three dependent loads
;   per triangle (list entry, vertex numbers, cull bytes).
;
; Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.

%include "sv_abi.inc"

extern sv_count_facing_avx512

%define CFC_CHUNK 960                           ; triangles per list (x 16)

section .rodata align=64
cfc_iota:
%assign i 0
%rep 16
        dd i
%assign i i+1
%endrep
cfc_c16: dd 16

; One listed triangle: list entry r14 + %1.
%macro CFC_ENTRY 1
        mov     eax, [rsp+r14*4+%1*4]           ; t (in the chunk)
        lea     r8, [rax+rax*2]
        mov     r9, [rdx+r8*4]                  ; i0 | i1 << 32
        movsxd  r11, dword [rdx+r8*4+8]         ; i2
        movsxd  r10, r9d                        ; i0
        sar     r9, 32                          ; i1
        movzx   r10d, byte [rcx+r10]
        and     r10b, [rcx+r9]
        and     r10b, [rcx+r11]                 ; c; ZF = (c == 0)
        setnz   r10b
        mov     [rdi+rax], r10b                 ; 0 -> 1 when culled
%endmacro

FUNCTION sv_count_facing_cull_avx512
        mov     esi, arg2d                      ; numTriangles
        test    esi, esi
        jle     .zero                           ; negative or zero: touch nothing
        push    rbx
        push    rbp
        push    r12
        push    r13
        push    r14
        push    r15
        mov     rbp, rsp
        sub     rsp, (CFC_CHUNK + 16) * 4
        and     rsp, -64
        mov     r12, rdi                        ; facing
        mov     r13d, esi                       ; numTriangles
        vpternlogd xmm1, xmm1, xmm1, 0xFF       ; all ones

.chunk:
        mov     ebx, CFC_CHUNK
        cmp     rsi, rbx
        cmovb   rbx, rsi                        ; triangles in this chunk
        sub     rsi, rbx

        ; pass 1: the list of non-facing triangles
        xor     r15d, r15d
        vmovdqa64 zmm0, [cfc_iota]
        mov     r14, rbx
        xor     r8d, r8d                        ; block offset
        sub     r14, 16
        jb      .p1_tail
.p1_loop:
        vptestnmb k1, xmm1, [rdi+r8]            ; facing == 0
        kmovw   eax, k1
        vpcompressd zmm2{k1}{z}, zmm0
        vmovdqu32 [rsp+r15*4], zmm2
        popcnt  eax, eax
        add     r15, rax
        vpaddd  zmm0, zmm0, [cfc_c16]{1to16}
        add     r8, 16
        sub     r14, 16
        jae     .p1_loop
.p1_tail:
        add     r14, 16                         ; 0-15 (only in the last chunk)
        jz      .p2
        mov     rax, -1
        bzhi    rax, rax, r14
        kmovw   k2, eax
        vmovdqu8 xmm3{k2}{z}, [rdi+r8]          ; only the bytes that exist
        vptestnmb k1{k2}, xmm3, xmm3
        kmovw   eax, k1
        vpcompressd zmm2{k1}{z}, zmm0
        vmovdqu32 [rsp+r15*4], zmm2
        popcnt  eax, eax
        add     r15, rax

.p2:    ; pass 2: cull the listed triangles, four per iteration; the list
        ; is padded to a multiple of four with copies of its last entry
        ; (the same byte stored again: the count comes afterwards)
        test    r15, r15
        jz      .p2_done
        mov     eax, [rsp+r15*4-4]
        mov     [rsp+r15*4+0], eax
        mov     [rsp+r15*4+4], eax
        mov     [rsp+r15*4+8], eax
        xor     r14d, r14d
.p2_loop:
        CFC_ENTRY 0
        CFC_ENTRY 1
        CFC_ENTRY 2
        CFC_ENTRY 3
        add     r14, 4
        cmp     r14, r15
        jb      .p2_loop
.p2_done:
        lea     rax, [rbx+rbx*2]
        lea     rdx, [rdx+rax*4]                ; next chunk
        add     rdi, rbx
        test    rsi, rsi
        jnz     .chunk

        mov     rdi, r12
        mov     esi, r13d
        mov     rsp, rbp
        pop     r15
        pop     r14
        pop     r13
        pop     r12
        pop     rbp
        pop     rbx
        jmp     sv_count_facing_avx512 wrt ..plt ; the count (vzeroupper there)

.zero:
        xor     eax, eax
        ret
ENDFUNCTION
