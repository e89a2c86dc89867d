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
;   Measured on the way (ticks for the 1344-triangle character, moving
;   light, this Zen 5-class core): appendix F's scheme with one vpermd and
;   one 32-byte store per triangle, offsets from a prefix-sum multiply,
;   ~880; this, ~690.
;
; int sv_create_cap_triangles_avx2(int *shadowIndices, const uint8_t *facing,
;                                  const int *indices, int numIndices)
;
; Register map:
;   r12 output position     r13 shadowIndices    r14 indices   r15 facing
;   r10 triangles (n)       r9  3 * (n - 3): the last first-index position
;                               whose 32-byte window stays inside indices
;   rbx first triangle of the chunk    rdi end of the chunk
;   rsi triangle of the current 32-block    rbp list entries
;   r11 the packed-positions table; rax, rcx, rdx, r8 scratch
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
; Measured cost (`shadowvol bench`, the
;   1344-triangle / 2016-edge character; AMD EPYC "Turin-like" KVM guest,
;   TSC 2.097 GHz (core ~3.7 GHz), cpuid-serialised rdtsc; min / median
;   ticks, range over three runs on a busy 2-core VM; base commit 5430ca6):
;   moving light 693-735 / 756-798 (sse2_paper 1533-1554 / 1554-1575,
;   c_ref 2499-2520 / 2730-2793); fixed light 651-672 / 672 (sse2_paper
;   1554 / 1575, c_ref 2373-2394 / 2415).
;
; Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.

%include "sv_abi.inc"
%include "avx2_left_pack.inc"

%define CHUNK        992                  ; triangles per list: a multiple of 32
%define LIST_ENTRIES (CHUNK + 16)         ; + 8 for an 8-block's 32-byte store
%define FRAME        (LIST_ENTRIES*4 + 8) ; + 6 pushes + return: < 4096

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
        mov     ecx, [rsp + rax*4 + %1*4]
        vpermd  %2, ymm8, [r14 + rcx*4]
        vpaddd  %2, %2, %2
        vpxor   %2, %2, ymm9
%endmacro

FUNCTION sv_create_cap_triangles_avx2
        mov     eax, arg4d
        test    eax, eax
        jg      .start
        xor     eax, eax                ; negative or zero: 0, nothing touched
        ret
.start:
        push    rbx
        push    rbp
        push    r12
        push    r13
        push    r14
        push    r15
        sub     rsp, FRAME
        mov     r12, rdi
        mov     r13, rdi
        mov     r14, rdx
        mov     r15, rsi
        mov     r8d, 0xAAAAAAAB         ; numIndices / 3 (exact for 32-bit unsigned)
        imul    rax, r8
        shr     rax, 33
        jz      .done                   ; 1 or 2 indices: no whole triangle
        mov     r10, rax
        lea     r9, [rax + rax*2 - 9]   ; signed: negative when n < 3
        lea     r11, [positions3]
        vpxor   xmm5, xmm5, xmm5
        vpbroadcastd ymm7, [step24]
        vmovdqa ymm8, [perm_cap]
        vmovdqa ymm9, [far_plus1]
        xor     ebx, ebx

.chunk:
        ; ---- phase 1: list the casting triangles of [rbx, rdi)
        xor     ebp, ebp
        mov     rsi, rbx
        lea     rax, [rbx + rbx*2]      ; < 2^31
        vmovd   xmm6, eax
        vpbroadcastd ymm6, xmm6
        lea     rdi, [rbx + CHUNK]
        cmp     rdi, r10
        cmova   rdi, r10
        LIST_NONFACING r15, r10, rdi, rax, .emit

        ; ---- phase 2: six indices per listed triangle, in order
.emit:
        mov     rbx, rdi                ; the next chunk
        ; the listed triangles whose window stays inside indices (3t <= r9)
        ; are a prefix of the list; the rest (0..2) are among the last two
        mov     edx, ebp
        test    edx, edx
        jz      .next
        mov     eax, [rsp + rdx*4 - 4]
        cmp     rax, r9
        jle     .split
        dec     edx
        jz      .split
        mov     eax, [rsp + rdx*4 - 4]
        cmp     rax, r9
        jle     .split
        dec     edx
.split:
        xor     eax, eax
.fast2:
        lea     ecx, [rax + 2]
        cmp     ecx, edx
        ja      .fast1
        CAP1    0, ymm1
        CAP1    1, ymm2
        vmovdqu [r12], ymm1
        vmovdqu [r12 + 24], ymm2
        add     r12, 48
        add     eax, 2
        jmp     .fast2
.fast1:
        cmp     eax, edx
        jae     .slow
        CAP1    0, ymm1
        vmovdqu [r12], ymm1
        add     r12, 24
        inc     eax
.slow:                                  ; 12 bytes in, 24 bytes out
        cmp     eax, ebp
        jae     .next
        mov     ecx, [rsp + rax*4]
        vmovq   xmm0, [r14 + rcx*4]
        vpinsrd xmm0, xmm0, [r14 + rcx*4 + 8], 2
        vpermd  ymm1, ymm8, ymm0
        vpaddd  ymm1, ymm1, ymm1
        vpxor   ymm1, ymm1, ymm9
        vmovdqu [r12], xmm1
        vextracti128 xmm2, ymm1, 1
        vmovq   [r12 + 16], xmm2
        add     r12, 24
        inc     eax
        jmp     .slow
.next:
        cmp     rbx, r10
        jb      .chunk
        vzeroupper

.done:
        mov     rax, r12                ; return (end - shadowIndices) / 4
        sub     rax, r13
        shr     rax, 2
        add     rsp, FRAME
        pop     r15
        pop     r14
        pop     r13
        pop     r12
        pop     rbp
        pop     rbx
        ret
ENDFUNCTION
