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
; Register map:
;   rdi  facing (walks forward)      rsi  facing + n (end)
;   ecx  bytes still to count        eax  scalar sum (popcnt tails)
;   ymm0, ymm1 qword accumulators    ymm5 zero
;   ymm2-ymm4 loads / byte sums
;
; Contracts: no alignment; facing bytes 0 or 1 (a byte of 2..255 adds its
;   value, and four such in one lane could wrap: the C counts it as 1);
;   numTriangles >= 0 (negative returns 0 and reads nothing). Reads exactly
;   facing[0 .. n-1]: never a byte before or after.
;
; Measured cost (`shadowvol bench`, batches of 23 calls, the
;   1344-triangle / 2016-edge character; AMD EPYC "Turin-like" KVM guest,
;   TSC 2.097 GHz (core ~3.7 GHz), cpuid-serialised rdtsc; min / median
;   ticks, range over three runs on a busy 2-core VM; base commit 5430ca6):
;   moving light 19.2-20.1 / 21.0-22.8 (sse2_paper 31.0-32.0 / 32.0-32.9,
;   c_ref 322-323); fixed light 15.5-17.3 / 16.4-18.3 (sse2_paper
;   27.4-30.1 / 28.3-31.0). Bound: 42 loads of 32 bytes at the 2 per cycle
;   measured here are 21 cycles = 11.9 ticks, plus call and reduction: the
;   256-bit loads, not the arithmetic, set the pace.
;
; Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.

%include "sv_abi.inc"

RODATA
align 32
; 32 zero bytes then 32 0xFF bytes: a 32-byte load at tail_mask + r
; keeps the last r bytes of a vector (byte p is kept when p >= 32 - r).
tail_mask:  times 32 db 0
            times 32 db 0xFF

FUNCTION sv_count_facing_avx2
        mov     ecx, arg2d              ; numTriangles (upper half ignored)
        xor     eax, eax
        test    ecx, ecx
        jle     .ret                    ; negative or zero: 0, nothing read
        lea     rsi, [rdi + rcx]        ; end (ecx > 0: zero-extended is right)
        cmp     ecx, 32
        jb      .small

        vpxor   xmm0, xmm0, xmm0
        vpxor   xmm1, xmm1, xmm1
        vpxor   xmm5, xmm5, xmm5
        sub     ecx, 128                ; signed from here: n <= 2^31 - 1
        jl      .run32

.loop128:
        vmovdqu ymm2, [rdi]
        vpaddb  ymm2, ymm2, [rdi + 32]
        vmovdqu ymm3, [rdi + 64]
        vpaddb  ymm3, ymm3, [rdi + 96]
        vpsadbw ymm2, ymm2, ymm5
        vpsadbw ymm3, ymm3, ymm5
        vpaddq  ymm0, ymm0, ymm2
        vpaddq  ymm1, ymm1, ymm3
        add     rdi, 128
        sub     ecx, 128
        jge     .loop128

.run32:
        add     ecx, 128 - 32           ; bytes left - 32
        jl      .last
.loop32:
        vpsadbw ymm2, ymm5, [rdi]
        vpaddq  ymm0, ymm0, ymm2
        add     rdi, 32
        sub     ecx, 32
        jge     .loop32

.last:
        add     ecx, 32                 ; 0..31 bytes left
        jz      .reduce
        lea     rdx, [tail_mask]
        vmovdqu ymm2, [rdx + rcx]       ; keeps the last ecx bytes
        vpand   ymm2, ymm2, [rsi - 32]  ; n >= 32: never before facing
        vpsadbw ymm2, ymm2, ymm5
        vpaddq  ymm0, ymm0, ymm2

.reduce:
        vpaddq  ymm0, ymm0, ymm1
        vextracti128 xmm1, ymm0, 1
        vpaddq  xmm0, xmm0, xmm1
        vpshufd xmm1, xmm0, SHUFFLE_D(2, 3, 0, 1)
        vpaddq  xmm0, xmm0, xmm1
        vmovq   rax, xmm0
        vzeroupper
.ret:
        ret

        ; 1 <= n < 32: no vector register touched, so no vzeroupper needed
.small:
        sub     ecx, 8
        jb      .bytes
.qwords:                                ; n >= 8
        popcnt  rdx, [rdi]
        add     eax, edx
        add     rdi, 8
        sub     ecx, 8
        jae     .qwords
        add     ecx, 8                  ; 0..7 bytes left
        jz      .ret
        ; the qword ending at the end holds 8 - ecx bytes already counted:
        ; shift them out (low bytes are the lower addresses)
        mov     rdx, [rsi - 8]
        neg     ecx
        lea     ecx, [rcx*8 + 64]       ; 8 * (8 - left)
        shrx    rdx, rdx, rcx
        popcnt  rdx, rdx
        add     eax, edx
        ret
.bytes:                                 ; 1 <= n < 8
        movzx   edx, byte [rdi]
        add     eax, edx
        inc     rdi
        cmp     rdi, rsi
        jb      .bytes
        ret
ENDFUNCTION
