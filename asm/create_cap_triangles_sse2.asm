; create_cap_triangles_sse2.asm: CreateCapTriangles, the faithful port of
; appendix F (x86-64 System V and Windows x64, x86-32 cdecl).
;
; Computes: for each triangle j with facing[j] == 0 and doubled vertex
;   numbers i0, i1, i2: the near cap (i2, i1, i0) and the far cap
;   (i0+1, i1+1, i2+1), exactly section 7's C. Returns the number of indices.
; Ports:    J.M.P. van Waveren, "Shadow Volume Construction" (Id Software,
;           2005), appendix F, "SSE Optimized Construction of Shadow Volume
;           Cap Triangles". Same instructions, the same four-triangle unroll
;           (three movdqa for twelve indices) and one-triangle tail, the
;           same output-pointer trick.
;
; The tricks:
;   - paddd x, x doubles four vertex numbers at once; pshufd / shufps lay
;     them out as (i2, i1, i0, i0) and (i1, i2, ...); pxor with the constants
;     c0 = (0,0,0,1) and c1 = (1,1,0,0) adds the +1 of the far cap (the
;     numbers are even, so ^1 = +1). Triangle 1 of each four straddles two
;     loads: shufps gathers (i0, i0, i2, i1) and c2 = (0,1,0,0) fixes it up,
;     stored high half first.
;   - No branch per triangle: all six indices are always stored and the
;     output pointer (kept divided by 8, as in appendix E) advances by
;     (facing - 1) & 3 = 3 eight-byte units when facing is 0, else 0. The
;     pointer alternates between rbx and rcx.
;
; int sv_create_cap_triangles_sse2_paper(int *shadowIndices, const uint8_t *facing,
;                                        const int *indices, int numIndices)
;
; Register map (listing -> port; asm/sv_abi.inc names, rv = rax/eax). The
; output pointer pair is the roles `optr` (ebx) and g3 (ecx), the saved
; shadowIndices `obase` (asm/out_ptr8.inc, shared with appendix E):
;                                                   64-bit       x86-32
;   eax  -(triangles left) (+4 inside loop4)        rvq          eax
;   edx  3 * eax: index offset into indices         g2q          edx
;   ebx  output pointer / 8, alternating with ecx   optr=g8 (rbx, ebx (g4,
;                                                   pushed), g3q pushed), ecx
;   esi  facing + numTriangles                      g1q          esi
;   edi  indices + numIndices                       g0q          edi
;   shadowIndices, for the return value             obase=g4     its stack
;                                                   (r8/r10)     argument
;   num = numIndices / 3 (the listing's C           g5 (r9/r11)  edx, once
;   `int num = numIndices / 3`)
;   x86-32 has the listing's six registers and no more: it re-reads
;   shadowIndices from the stack at the end, and computes num with the
;   32-bit reciprocal (mul by 0xAAAAAAAB, shr edx, 1) in edx before edx
;   becomes the index offset (port entry F-12 in docs/ERRATA.md).
;   xmm6 c0, xmm7 c1, xmm5 c2 (SIMD_DW_capTris_c0..c2); on x86-32 edx holds
;   the GOT address while they are loaded (SV_PIC_BASE: no text relocation, F-13)

; Contracts: indices 16-byte aligned (movdqa); numIndices a multiple of 3
;   (the end pointer is indices + numIndices but the walk counts whole
;   triangles, so anything else misaligns every load); vertex numbers in
;   [0, 2^30) (doubled in 32 bits); facing bytes 0 or 1 ((f - 1) & 3 is 3
;   only for 0 and 0 only for 1); shadowIndices 8-byte aligned, room for
;   2 * numIndices ints (6 written per triangle). numIndices >= 0.
;
; Errata fixed (docs/ERRATA.md): `padd` -> paddd; for numIndices == 0 the
;   listing skips `shr ebx, 3` and returns garbage; the tail loop's
;   `movdqu xmm0, [edi+edx*4]` reads 16 bytes for a 12-byte triangle, 4
;   past the end of indices on the last one (inside the last aligned 16-byte
;   block when indices is 16-byte aligned, so it cannot fault then, but it
;   is a read outside the array): the port loads 8 + 4 bytes; the return
;   statement names
;   `shadowIndexes` and casts a pointer to int.
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
%include "out_ptr8.inc"                 ; optr, obase, OUT8_RETURN

RODATA
SIMD_DW_capTris_c0: dd 0, 0, 0, 1
SIMD_DW_capTris_c1: dd 1, 1, 0, 0
SIMD_DW_capTris_c2: dd 0, 1, 0, 0

FUNC sv_create_cap_triangles_sse2_paper, 4, OUT8_NGPRS, 8, shadowIndices, facing, indices, numIndices
%if SV_BITS == 64
        movsxd  rvq, g3d              ; numIndices
        mov     optr%+q, g0q          ; shadowIndices
        mov     obase, g0q
        ; rsi = facing already
        mov     g0q, g2q              ; indices
        ; num = numIndices / 3, rounded toward zero as C does
        imul    g5q, rvq, 0x55555556
        mov     g3q, g5q
        shr     g3q, 63
        sar     g5q, 32
        add     g5d, g3d
        shr     optr%+q, 3              ; moved above the early exit (erratum F-2)
        shl     rvq, 2
        jz      .done
        add     g0q, rvq
        movsxd  rvq, g5d                ; mov eax, num
        add     g1q, rvq
        neg     rvq
%else
        mov     rvd, g3d              ; numIndices
        mov     optr%+q, g0q          ; shadowIndices (obase: its stack slot)
        ; esi = facing already
        mov     g0q, g2q              ; indices
        shr     optr%+q, 3              ; moved above the early exit (erratum F-2)
        test    rvd, rvd                ; 0 or negative: nothing (the 64-bit
        jle     .done                   ; path: jz, or num <= 0, an empty walk)
        lea     g0q, [g0q+rvq*4]        ; indices + numIndices
        ; num = numIndices / 3 for 0 <= numIndices < 2^31: the high dword of
        ; n * 0xAAAAAAAB (= (2^33 + 1) / 3) is n * 2/3 + a fraction < 1/3,
        ; so shr 1 gives floor(n / 3) exactly (port entry F-12)
        mov     g2d, 0xAAAAAAAB
        mul     g2d                     ; edx:eax = n * 0xAAAAAAAB
        shr     g2d, 1
        mov     rvd, g2d                ; mov eax, num
        add     g1q, rvq
        neg     rvq
%endif

        SV_PIC_BASE g2q                 ; (x86-32: edx = the GOT; free until the lea below)
        movaps  xmm6, [SV_RODATA(g2q, SIMD_DW_capTris_c0)]
        movaps  xmm7, [SV_RODATA(g2q, SIMD_DW_capTris_c1)]
        movaps  xmm5, [SV_RODATA(g2q, SIMD_DW_capTris_c2)]

        add     rvq, 4
        lea     g2q, [rvq*2+rvq]
        jg      .run1

.loop4:
        movdqa  xmm0, [g0q+g2q*4-4*3*4+0]            ; xmm0 = 0, 1, 2, 3
        paddd   xmm0, xmm0                           ; listing: padd (erratum F-1)
        pshufd  xmm1, xmm0, SHUFFLE_D(2, 1, 0, 0)    ; xmm1 = 2, 1, 0, 0
        movzx   g3d, byte [g1q+rvq-4]
        pshufd  xmm2, xmm0, SHUFFLE_D(1, 2, 1, 2)    ; xmm2 = 1, 2, 1, 2
        sub     g3d, 1
        pxor    xmm1, xmm6
        and     g3d, 3
        movlps  qword [optr%+q*8+0*4], xmm1
        add     g3q, optr%+q
        movhps  qword [optr%+q*8+2*4], xmm1
        pxor    xmm2, xmm7
        movlps  qword [optr%+q*8+4*4], xmm2

        movdqa  xmm3, [g0q+g2q*4-3*3*4+4]            ; xmm3 = 4, 5, 6, 7
        paddd   xmm3, xmm3
        shufps  xmm0, xmm3, SHUFFLE_D(3, 3, 1, 0)    ; xmm0 = 3, 3, 5, 4
        movzx   optr%+d, byte [g1q+rvq-3]
        movdqa  xmm2, xmm3                           ; xmm2 = 4, 5, 6, 7
        sub     optr%+d, 1
        pxor    xmm0, xmm5
        and     optr%+d, 3
        movhps  qword [g3q*8+0*4], xmm0
        add     optr%+q, g3q
        movlps  qword [g3q*8+2*4], xmm0
        pxor    xmm2, xmm7
        movlps  qword [g3q*8+4*4], xmm2

        movdqa  xmm0, [g0q+g2q*4-1*3*4-4]            ; xmm0 = 8, 9, 10, 11
        paddd   xmm0, xmm0
        shufps  xmm3, xmm0, SHUFFLE_D(2, 3, 0, 1)    ; xmm3 = 6, 7, 8, 9
        pshufd  xmm1, xmm3, SHUFFLE_D(2, 1, 0, 0)    ; xmm1 = 8, 7, 6, 6
        movzx   g3d, byte [g1q+rvq-2]
        pshufd  xmm2, xmm3, SHUFFLE_D(1, 2, 1, 2)    ; xmm2 = 7, 8, 7, 8
        sub     g3d, 1
        pxor    xmm1, xmm6
        and     g3d, 3
        movlps  qword [optr%+q*8+0*4], xmm1
        add     g3q, optr%+q
        movhps  qword [optr%+q*8+2*4], xmm1
        pxor    xmm2, xmm7
        movlps  qword [optr%+q*8+4*4], xmm2

        pshufd  xmm1, xmm0, SHUFFLE_D(3, 2, 1, 1)    ; xmm1 = 11, 10, 9, 9
        movzx   optr%+d, byte [g1q+rvq-1]
        pshufd  xmm2, xmm0, SHUFFLE_D(2, 3, 2, 3)    ; xmm2 = 10, 11, 10, 11
        sub     optr%+d, 1
        pxor    xmm1, xmm6
        and     optr%+d, 3
        movlps  qword [g3q*8+0*4], xmm1
        add     optr%+q, g3q
        movhps  qword [g3q*8+2*4], xmm1
        pxor    xmm2, xmm7
        movlps  qword [g3q*8+4*4], xmm2

        add     g2q, 3*4
        add     rvq, 4
        jle     .loop4

.run1:
        sub     rvq, 4
        jge     .done

.loop1:
        lea     g2q, [rvq*2+rvq]
        ; listing: movdqu xmm0, [edi+edx*4+0], 16 bytes for a 12-byte
        ; triangle (erratum F-3). Lane 3 is never used, so load 8 + 4.
        movq    xmm0, qword [g0q+g2q*4+0]
        movd    xmm1, dword [g0q+g2q*4+8]
        punpcklqdq xmm0, xmm1
        paddd   xmm0, xmm0
        pshufd  xmm1, xmm0, SHUFFLE_D(2, 1, 0, 0)
        pshufd  xmm2, xmm0, SHUFFLE_D(1, 2, 1, 2)
        pxor    xmm1, xmm6
        movlps  qword [optr%+q*8+0*4], xmm1
        pxor    xmm2, xmm7
        movhps  qword [optr%+q*8+2*4], xmm1
        movzx   g3d, byte [g1q+rvq]
        movlps  qword [optr%+q*8+4*4], xmm2
        sub     g3d, 1
        and     g3d, 3
        add     optr%+q, g3q

        add     rvq, 1
        jl      .loop1

.done:
        OUT8_RETURN
        RET
ENDFUNC
