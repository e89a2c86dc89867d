; count_facing_cull_sse2.asm: CountFacingCull, the faithful port of
; appendix D (x86-64 System V and Windows x64, x86-32 cdecl).
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
; Register map (listing -> port). The listing's registers are kept so the
; two read side by side; the arguments are moved into them first. The body
; names its registers by role (cbits, tris, pair, vert, fend below), each an
; asm/sv_abi.inc logical register chosen per ABI (rv = rax/eax):
;                                                   SysV  win64  x86-32
;   eax  -(triangles left) (+4 inside loop4) rvq    rax   rax    eax
;        (sign-extended once, so [fend+rv-4] addresses below the end
;        pointer as [ebx+eax-4] did)
;   ebx  facing + numTriangles (end pointer) fend   r8    r10    ebx
;   esi  indices, 12 bytes per triangle      tris   rsi   rsi    esi
;   edi  cullBits                            cbits  rdi   rdi    edi
;   ecx  one vertex index (movsxd: int)      vert   rcx   rcx    ecx
;   edx  dl / dh: AND of one triangle's      pair   rdx   rdx    edx
;        cull bytes each
;   xmm0 four c bytes; xmm1 four facing bytes; xmm5 dword counters;
;   xmm6 zero; xmm7 sixteen bytes of 1 (SIMD_B_one, loaded on x86-32
;   through the GOT address in edx: SV_PIC_BASE, no text relocation, D-9)
;   dh is addressable only in an instruction without a REX prefix, so
;   `mov dh, [cbits+vert]` needs pair in rdx and cbits, vert among the
;   eight legacy registers (movsxd, REX.W anyway, is a separate
;   instruction). System V and x86-32 get that from g0..g4 as they are.
;   win64's g0..g4 are rcx, rdx, r8, r9, r10 (dh is g1h, but cbits and vert
;   would be r8/r9), so there the function declares g0..g7 and keeps the
;   listing's registers: rcx, rdx free, rdi and rsi (g6, g7, callee-saved
;   on win64, pushed by the prologue). The instructions are the same on
;   every ABI; only win64 pays two push/pop pairs (and xmm6/xmm7 saved).

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
;   loop walks ~2^29 triangles: the port negates in 64 bits and returns 0
;   (x86-32: `jle` in place of `jz`, port entry D-8).
;   A fix of the D-5 limit would cost nothing: pcmpeqb xmm0, xmm6 / pandn
;   xmm0, xmm7 in place of pcmpgtb / pand. It is not taken here, to stay the
;   listing's code (issue 3 asks for the faithful behaviour, pinned).
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

; CF_REG role, n: the role's register is logical register gn (q, d, b, h).
%macro CF_REG 2
    %xdefine %1q g%2q
    %xdefine %1d g%2d
    %ifdef g%2b
        %xdefine %1b g%2b
    %endif
    %ifdef g%2h
        %xdefine %1h g%2h
    %endif
%endmacro
%ifdef SV_WIN64
    %define CF_NGPRS 8                  ; g6, g7 = rdi, rsi (see the map)
    CF_REG cbits, 6
    CF_REG tris,  7
    CF_REG pair,  1
    CF_REG vert,  0
    CF_REG fend,  4
%else
    %define CF_NGPRS 5
    CF_REG cbits, 0
    CF_REG tris,  1
    CF_REG pair,  2
    CF_REG vert,  3
    CF_REG fend,  4
%endif

RODATA
SIMD_B_one: times 16 db 1

FUNC sv_count_facing_cull_sse2_paper, 4, CF_NGPRS, 8, facing, numTriangles, indices, cullBits
        mov     fendq, facingq          ; facing (first: SysV's rdi becomes cullBits)
        mov     rvd, numTrianglesd      ; (before SysV's rsi becomes indices)
        mov     trisq, indicesq
        mov     cbitsq, cullBitsq
        pxor    xmm5, xmm5              ; moved above the early exit (erratum D-3)
        test    rvd, rvd
%if SV_BITS == 64
        jz      .done
        MOVSXD_P  rvq, rvd                ; 64-bit index from here on (erratum D-7)
%else
        jle     .done                   ; x86-32: no 64-bit neg to make a negative
                                        ; count an empty walk (erratum D-7, port D-8)
%endif
        add     fendq, rvq
        neg     rvq

        pxor    xmm6, xmm6
        SV_PIC_BASE pairq               ; (x86-32: edx = the GOT; free until loop4)
        movdqa  xmm7, [SV_RODATA(pairq, SIMD_B_one)]

        add     rvq, 4
        jg      .run1

.loop4:
        MOVSXD_P  vertq, dword [trisq+0*4]
        movzx   paird, byte [cbitsq+vertq]
        MOVSXD_P  vertq, dword [trisq+1*4]
        and     pairb, byte [cbitsq+vertq]
        MOVSXD_P  vertq, dword [trisq+2*4]
        and     pairb, byte [cbitsq+vertq]

        MOVSXD_P  vertq, dword [trisq+3*4]
        mov     pairh, byte [cbitsq+vertq]
        MOVSXD_P  vertq, dword [trisq+4*4]
        and     pairh, byte [cbitsq+vertq]
        MOVSXD_P  vertq, dword [trisq+5*4]
        and     pairh, byte [cbitsq+vertq]
        movd    xmm0, paird

        MOVSXD_P  vertq, dword [trisq+6*4]
        movzx   paird, byte [cbitsq+vertq]
        MOVSXD_P  vertq, dword [trisq+7*4]
        and     pairb, byte [cbitsq+vertq]
        MOVSXD_P  vertq, dword [trisq+8*4]
        and     pairb, byte [cbitsq+vertq]

        MOVSXD_P  vertq, dword [trisq+9*4]
        mov     pairh, byte [cbitsq+vertq]
        MOVSXD_P  vertq, dword [trisq+10*4]
        and     pairh, byte [cbitsq+vertq]
        MOVSXD_P  vertq, dword [trisq+11*4]
        and     pairh, byte [cbitsq+vertq]
        pinsrw  xmm0, paird, 1

        add     trisq, 12*4

        movd    xmm1, [fendq+rvq-4]
        pcmpgtb xmm0, xmm6              ; SIGNED: c >= 0x80 is "not > 0" (limit D-5)
        pand    xmm0, xmm7
        por     xmm1, xmm0
        movd    [fendq+rvq-4], xmm1

        add     rvq, 4                  ; flags live until jle

        punpcklbw xmm1, xmm6
        punpcklwd xmm1, xmm6
        paddd   xmm5, xmm1              ; listing: padd (erratum D-1)

        jle     .loop4

.run1:
        sub     rvq, 4
        jge     .done

.loop1:
        MOVSXD_P  vertq, dword [trisq+0*4]
        movzx   paird, byte [cbitsq+vertq]
        MOVSXD_P  vertq, dword [trisq+1*4]
        and     pairb, byte [cbitsq+vertq]
        MOVSXD_P  vertq, dword [trisq+2*4]
        and     pairb, byte [cbitsq+vertq]

        neg     paird
        shr     paird, 31
        movzx   vertd, byte [fendq+rvq]
        or      vertd, paird
        mov     byte [fendq+rvq], vertb
        movd    xmm0, vertd
        paddd   xmm5, xmm0

        add     trisq, 3*4
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
