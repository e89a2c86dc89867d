; count_facing_sse2.asm: CountFacing, the faithful x86-64 port of appendix C.
;
; Computes: the number of facing bytes set, n = sum(facing[0 .. n-1]).
; Ports:    J.M.P. van Waveren, "Shadow Volume Construction" (Id Software,
;           2005), appendix C, "SSE Optimized Counting of Facing Triangles".
;           Same instructions, same four loops (256 / 16 / 4 / 1 bytes per
;           iteration), same register roles; 32-bit pointers became 64-bit.
;
; The trick: paddusb adds 16 facing bytes per instruction. A byte lane may
; hold at most 255, so the 256-byte loop sums 16 loads into one register
; (16 per lane) and widens bytes -> words -> dwords (punpck* against the
; zero in xmm7) into the dword accumulator xmm6 every iteration. The 16- and
; 4-byte loops add at most 15 + 3 = 18 into a lane before the one final
; widening at run1. The last 0-3 bytes are added with scalar movzx.
;
; int sv_count_facing_sse2_paper(const uint8_t *facing, int numTriangles)
;
; Register map (asm/sv_abi.inc names; rv = rax) (listing -> port):
;   eax  numTriangles, then the bytes still to count minus the block size
;   edi  facing           -> g0q (already the first argument)
;   ecx  scratch byte     -> g3d;  edx  scalar tail sum -> g2d
;   xmm0 byte sums of the current block; xmm1 scratch; xmm6 dword totals;
;   xmm7 zero. The listing's stack array `n` is replaced by reading xmm6.
;
; Contracts: facing 16-byte aligned (movdqa, and paddusb with a memory
;   operand, fault on anything less); facing bytes 0 or 1 (paddusb saturates
;   at 255, so larger values are not summed as C would); numTriangles >= 0
;   (negative returns 0 and reads nothing). Reads exactly numTriangles bytes.
;
; Errata fixed (docs/ERRATA.md): `padd` is no instruction (paddd); for
;   numTriangles == 0 the listing jumps over every store to `n` and returns
;   the sum of uninitialised stack: the port returns 0; for numTriangles in
;   [INT_MIN, INT_MIN + 255] the listing's `sub eax, 256` / `add eax, 240`
;   overflow and its loops read ~2^28 bytes: the port exits on <= 0;
;   `movzx ecx, [edi]` has no operand size (byte).
;
; Cost: not kept here (figures go stale); `shadowvol bench` measures it
;   on the machine at hand and docs/BENCHMARK.md has the current table.
;
; Copyright (C) 2005 Id Software, Inc. Written by J.M.P. van Waveren.
; Port: Copyright (C) 2026 the shadowvol authors.
; This code is free software; you can redistribute it and/or modify it under
; the terms of the GNU Lesser General Public License as published by the Free
; Software Foundation; either version 2.1 of the License, or (at your option)
; any later version.

%include "sv_abi.inc"

FUNC sv_count_facing_sse2_paper, 2, 4, 8, facing, numTriangles
        mov     rvd, g1d              ; numTriangles (upper half ignored)
        ; edi = facing: already in rdi
        pxor    xmm6, xmm6              ; moved above the early exit (erratum C-2)
        test    rvd, rvd
        jle     .done                   ; listing: jz (erratum C-7)

        pxor    xmm7, xmm7

        sub     rvd, 256
        jl      .run16

.loop256:
        movdqa  xmm0, [g0q+ 0*16]
        movdqa  xmm1, [g0q+ 1*16]
        movdqa  xmm2, [g0q+ 2*16]
        movdqa  xmm3, [g0q+ 3*16]
        paddusb xmm0, [g0q+ 4*16]
        paddusb xmm1, [g0q+ 5*16]
        paddusb xmm2, [g0q+ 6*16]
        paddusb xmm3, [g0q+ 7*16]
        paddusb xmm0, [g0q+ 8*16]
        paddusb xmm1, [g0q+ 9*16]
        paddusb xmm2, [g0q+10*16]
        paddusb xmm3, [g0q+11*16]
        paddusb xmm0, [g0q+12*16]
        paddusb xmm1, [g0q+13*16]
        paddusb xmm2, [g0q+14*16]
        paddusb xmm3, [g0q+15*16]
        paddusb xmm0, xmm1
        paddusb xmm2, xmm3
        paddusb xmm0, xmm2

        add     g0q, 256
        sub     rvd, 256                ; flags live until jge (SSE leaves them)

        movdqa  xmm1, xmm0
        punpcklbw xmm0, xmm7
        punpckhbw xmm1, xmm7
        paddusw xmm0, xmm1
        movdqa  xmm1, xmm0
        punpcklwd xmm0, xmm7
        punpckhwd xmm1, xmm7
        paddd   xmm0, xmm1              ; listing: padd (erratum C-1)
        paddd   xmm6, xmm0

        jge     .loop256

.run16:
        pxor    xmm0, xmm0
        add     rvd, 256 - 16
        jl      .run4

.loop16:
        paddusb xmm0, [g0q]
        add     g0q, 16
        sub     rvd, 16
        jge     .loop16

.run4:
        add     rvd, 16 - 4
        jl      .run1

        pxor    xmm1, xmm1

.loop4:
        movd    xmm1, [g0q]
        paddusb xmm0, xmm1
        add     g0q, 4
        sub     rvd, 4
        jge     .loop4

.run1:
        movdqa  xmm1, xmm0
        punpcklbw xmm0, xmm7
        punpckhbw xmm1, xmm7
        paddusw xmm0, xmm1
        movdqa  xmm1, xmm0
        punpcklwd xmm0, xmm7
        punpckhwd xmm1, xmm7
        paddd   xmm0, xmm1
        paddd   xmm6, xmm0

        add     rvd, 4 - 1
        jl      .done

        movd    g2d, xmm6               ; listing: movdqa n, xmm6; mov edx, n[0]

.loop1:
        movzx   g3d, byte [g0q]
        add     g2d, g3d
        add     g0q, 1
        sub     rvd, 1
        jge     .loop1

        movd    xmm0, g2d               ; listing: mov n[0], edx
        movss   xmm6, xmm0

.done:
        ; return n[0] + n[1] + n[2] + n[3] (the listing's C epilogue)
        pshufd  xmm0, xmm6, SHUFFLE_D(2, 3, 0, 1)
        paddd   xmm6, xmm0
        pshufd  xmm0, xmm6, SHUFFLE_D(1, 0, 3, 2)
        paddd   xmm6, xmm0
        movd    rvd, xmm6
        RET
ENDFUNC
