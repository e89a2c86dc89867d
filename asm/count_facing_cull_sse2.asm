; count_facing_cull_sse2.asm: CountFacingCull, the faithful x86-64 port of
; appendix D.
;
; Computes: for each triangle i, c = cullBits[i0] & cullBits[i1] &
;   cullBits[i2] (its three vertices share a plane they are all outside of);
;   if c != 0, facing[i] = 1 (a triangle outside the light volume casts no
;   shadow). Returns the number of facing bytes set afterwards.
; Ports:    J.M.P. van Waveren, "Shadow Volume Construction" (Id Software,
;           2005), appendix D, "SSE Optimized Culling and Counting of Facing
;           Triangles". Same instructions, the same four-triangle loop and
;           one-triangle tail, the same negative-index walk over facing.
;
; The trick: the cull bytes are scattered (any vertex), so they are loaded
;   one by one and ANDed in dl/dh, two triangles per edx; movd + pinsrw put
;   four triangles' c into the low dword of xmm0. pcmpgtb against zero turns
;   each c into 0x00/0xFF, pand with 1s into 0/1, por into the four facing
;   bytes loaded with one movd; the new bytes are stored with one movd and
;   widened (punpcklbw, punpcklwd) into the dword counters of xmm5. The
;   tail uses the scalar (-c) >> 31 of section 5 (neg; shr 31).
;
; int sv_count_facing_cull_sse2_paper(uint8_t *facing, int numTriangles,
;                                     const int *indices, const uint8_t *cullBits)
;
; Register map (asm/sv_abi.inc names; rv = rax) (listing -> port). The listing's registers are kept so the
; two read side by side; the System V arguments are moved into them first.
;   eax  -(triangles left) (+4 inside loop4)  -> rvq (sign-extended once, so
;        [g4q+rvq-4] addresses below the end pointer as [ebx+eax-4] did)
;   ebx  facing + numTriangles (end pointer)  -> g4q (r8 on System V, ebx on x86-32)
;   esi  indices, 12 bytes per triangle       -> g1q
;   edi  cullBits                             -> g0q
;   ecx  one vertex index                     -> g3q (movsxd: int index)
;   edx  dl / dh: AND of one triangle's cull bytes each
;   xmm0 four c bytes; xmm1 four facing bytes; xmm5 dword counters;
;   xmm6 zero; xmm7 sixteen bytes of 1 (SIMD_B_one)
;   dh is addressable because no instruction that touches it needs a REX
;   prefix (rdi + rcx addressing only; movsxd is a separate instruction).
;
; Contracts: no alignment (movd only). Facing bytes 0 or 1. Vertex numbers
;   valid indices into cullBits. numTriangles >= 0 (negative returns 0).
;   LIMIT (faithful, pinned by a test): pcmpgtb compares signed, so in the
;   four-triangle loop a c of 0x80..0xFF (only bit 7 shared, or bit 7 with
;   others) counts as NOT culled, while the one-triangle tail and the C
;   culls it. Use cull bits 0..6 only.
;
; Errata fixed (docs/ERRATA.md): `padd` -> paddd; `numFaces` / `cull` are
;   not the parameters (numTriangles / cullBits); for numTriangles == 0 the
;   listing jumps over `pxor xmm5, xmm5` and returns whatever xmm5 held;
;   `movdqa dword ptr n, xmm5` names a dword for a 16-byte store; for
;   numTriangles == INT_MIN the listing's 32-bit `neg eax` overflows and its
;   loop walks ~2^29 triangles: the port negates in 64 bits and returns 0.
;   A fix of the D-5 limit would cost nothing: pcmpeqb xmm0, xmm6 / pandn
;   xmm0, xmm7 in place of pcmpgtb / pand. It is not taken here, to stay the
;   listing's code (issue 3 asks for the faithful behaviour, pinned).
;
; Cost: not kept here (figures go stale); `shadowvol bench` measures it
;   on the machine at hand and docs/benchmark.md has the current table.
;
; Copyright (C) 2005 Id Software, Inc. Written by J.M.P. van Waveren.
; Port: Copyright (C) 2026 the shadowvol authors.
; This code is free software; you can redistribute it and/or modify it under
; the terms of the GNU Lesser General Public License as published by the Free
; Software Foundation; either version 2.1 of the License, or (at your option)
; any later version.

%include "sv_abi.inc"

%ifdef SV_WIN64
    %error "count_facing_cull_sse2.asm: the listing packs cull bytes in dl/dh; on win64 g2 is r8, which has no bits 8-15 register (not ported yet)"
%endif

RODATA
SIMD_B_one: times 16 db 1

FUNC sv_count_facing_cull_sse2_paper, 4, 5, 8, facing, numTriangles, indices, cullBits
        mov     g4q, g0q              ; facing (first: rdi becomes cullBits)
        mov     rvd, g1d              ; numTriangles
        mov     g1q, g2q              ; indices
        mov     g0q, g3q              ; cullBits
        pxor    xmm5, xmm5              ; moved above the early exit (erratum D-3)
        test    rvd, rvd
        jz      .done
        MOVSXD_P  rvq, rvd                ; 64-bit index from here on (erratum D-7)
        add     g4q, rvq
        neg     rvq

        pxor    xmm6, xmm6
        movdqa  xmm7, [SIMD_B_one]

        add     rvq, 4
        jg      .run1

.loop4:
        MOVSXD_P  g3q, dword [g1q+0*4]
        movzx   g2d, byte [g0q+g3q]
        MOVSXD_P  g3q, dword [g1q+1*4]
        and     g2b, byte [g0q+g3q]
        MOVSXD_P  g3q, dword [g1q+2*4]
        and     g2b, byte [g0q+g3q]

        MOVSXD_P  g3q, dword [g1q+3*4]
        mov     g2h, byte [g0q+g3q]
        MOVSXD_P  g3q, dword [g1q+4*4]
        and     g2h, byte [g0q+g3q]
        MOVSXD_P  g3q, dword [g1q+5*4]
        and     g2h, byte [g0q+g3q]
        movd    xmm0, g2d

        MOVSXD_P  g3q, dword [g1q+6*4]
        movzx   g2d, byte [g0q+g3q]
        MOVSXD_P  g3q, dword [g1q+7*4]
        and     g2b, byte [g0q+g3q]
        MOVSXD_P  g3q, dword [g1q+8*4]
        and     g2b, byte [g0q+g3q]

        MOVSXD_P  g3q, dword [g1q+9*4]
        mov     g2h, byte [g0q+g3q]
        MOVSXD_P  g3q, dword [g1q+10*4]
        and     g2h, byte [g0q+g3q]
        MOVSXD_P  g3q, dword [g1q+11*4]
        and     g2h, byte [g0q+g3q]
        pinsrw  xmm0, g2d, 1

        add     g1q, 12*4

        movd    xmm1, [g4q+rvq-4]
        pcmpgtb xmm0, xmm6              ; SIGNED: c >= 0x80 is "not > 0" (limit D-5)
        pand    xmm0, xmm7
        por     xmm1, xmm0
        movd    [g4q+rvq-4], xmm1

        add     rvq, 4                  ; flags live until jle

        punpcklbw xmm1, xmm6
        punpcklwd xmm1, xmm6
        paddd   xmm5, xmm1              ; listing: padd (erratum D-1)

        jle     .loop4

.run1:
        sub     rvq, 4
        jge     .done

.loop1:
        MOVSXD_P  g3q, dword [g1q+0*4]
        movzx   g2d, byte [g0q+g3q]
        MOVSXD_P  g3q, dword [g1q+1*4]
        and     g2b, byte [g0q+g3q]
        MOVSXD_P  g3q, dword [g1q+2*4]
        and     g2b, byte [g0q+g3q]

        neg     g2d
        shr     g2d, 31
        movzx   g3d, byte [g4q+rvq]
        or      g3d, g2d
        mov     byte [g4q+rvq], g3b
        movd    xmm0, g3d
        paddd   xmm5, xmm0

        add     g1q, 3*4
        add     rvq, 1
        jl      .loop1

.done:
        ; return n[0] + n[1] + n[2] + n[3]
        pshufd  xmm0, xmm5, SHUFFLE_D(2, 3, 0, 1)
        paddd   xmm5, xmm0
        pshufd  xmm0, xmm5, SHUFFLE_D(1, 0, 3, 2)
        paddd   xmm5, xmm0
        movd    rvd, xmm5
        RET
ENDFUNC
