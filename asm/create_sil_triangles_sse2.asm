; create_sil_triangles_sse2.asm: CreateSilTriangles, the faithful port of
; appendix E (x86-64 System V and Windows x64, x86-32 cdecl).
;
; Computes: for each SilEdge whose two facing bytes f1 = facing[p1],
;   f2 = facing[p2] differ, the two triangles of the extruded edge:
;     v1, v2^f1, v2^f2,   v1^f2, v1^f1, v2^f1^f2   (v1, v2 even, so ^1 = +1)
;   i.e. exactly section 6's branchy C. Returns the number of indices.
; Ports:    J.M.P. van Waveren, "Shadow Volume Construction" (Id Software,
;           2005), appendix E, "SSE Optimized Construction of Shadow Volume
;           Silhouette Triangles". Same instructions, the same four-edge
;           unroll and one-edge tail, the same pointer trick.
;
; The tricks:
;   - No branch per edge: all six indices are always stored, and the output
;     pointer advances by 3 * (f1 ^ f2) eight-byte units (6 ints or none).
;   - The output pointer is kept DIVIDED BY 8 (shr rbx, 3) and addressed as
;     [rbx*8 + k]: then "advance by 6 ints" is lea 3*x, and the scaled
;     index needs no base register. The pointer alternates between rbx and
;     rdx (edge 1 computes rdx from rbx, edge 2 rbx from rdx, ...) so each
;     edge's stores need not wait for the previous edge's update.
;   - movd + pinsrw build (f1, f2, 0, 0); pshufd spreads it to
;     (0, f1, f2, f2) and the edge's (v1, v2) to (v1, v2, v2, v1): one pxor
;     gives the first four indices, a second pxor of (f1, f2) into them
;     gives (v1^f1, v2^f2^f1) = (v1 + f1, v2 + 1) on a silhouette edge.
;
; int sv_create_sil_triangles_sse2_paper(int *shadowIndices, const uint8_t *facing,
;                                        const SilEdge *silEdges, int numSilEdges)
;
; Register map (listing -> port; asm/sv_abi.inc names, rv = rax/eax). The
; output pointer is the role `optr` and the saved shadowIndices `obase`
; (asm/out_ptr8.inc, shared with appendix F):
;                                                         64-bit   x86-32
;   eax  negative byte offset from the end of silEdges   rvq      eax
;   ebx  output pointer / 8 in the 1st and 3rd edge of    optr=g8  optr=g4
;        loop4, scratch (f2, then the next pointer) in    (rbx,    (ebx,
;        the 2nd and 4th                                  pushed)  pushed)
;   edx  the other way round                              g2q      edx
;   ecx  f1, then f1 ^ f2                                 g3q      ecx
;   esi  facing                                           g1q      esi
;   edi  silEdges + numSilEdges (end pointer)             g0q      edi
;   shadowIndices, for the return value                   obase=g4 its stack
;                                                         (r8/r10) argument
;   x86-32 has the listing's six registers and no more, so it re-reads
;   shadowIndices from the stack at the end, as the listing does; x86-64
;   keeps it in a register.
;   xmm2/xmm3 (f1, f2, 0, 0); xmm0 the indices; xmm1 (0, f1, f2, f2)

; Contracts: shadowIndices 8-byte aligned (with less, [ptr/8*8] stores up
;   to 4 bytes BEFORE the buffer); room for 6 * numSilEdges ints (6 are
;   written for every edge, advancing or not); facing bytes 0 or 1 (the xor
;   and the 3 * (f1 ^ f2) advance need it); v1, v2 even; p1, p2 valid
;   indices into facing. No other alignment (movq loads, movlps/movhps
;   stores), although section 6 says the routine "assumes the arrays with
;   indices are aligned on a 16 byte boundary". numSilEdges >= 0
;   (negative returns 0, writes nothing).
;
; Errata fixed (docs/ERRATA.md): for numSilEdges == 0 the listing jumps to
;   `done` before `shr ebx, 3`, so `shl ebx, 3` there returns garbage; the
;   return statement names `shadowIndexes` (the parameter is shadowIndices)
;   and casts a pointer to int; 16 * numSilEdges is computed in 32 bits
;   (wraps for 2^27 edges and more): the port computes it in 64 bits on
;   x86-64; on x86-32 (port entry E-9 in docs/ERRATA.md) a negative count
;   leaves before the shift, and 2^27 edges (2 GiB of edges and 3 GiB of
;   output) cannot exist in a 32-bit address space.
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

; One edge of loop4. %1: edge slot (4..1, as in -%1*16), %2: xmm for (f1,f2)
; (xmm2 / xmm3 alternate), %3: register holding pointer/8 on entry, %4: the
; register that receives the next pointer/8 (and is scratch before that).
; Written out as a macro only to keep the four copies identical; the
; expansion is instruction for instruction the listing's.
%macro SIL_EDGE 4
        MOVSXD_P g3q, dword [g0q+rvq-%1*16+0]       ; p1
        movzx   g3d, byte [g1q+g3q]                  ; f1
        movd    %2, g3d
        MOVSXD_P %4q, dword [g0q+rvq-%1*16+4]        ; p2
        movzx   %4d, byte [g1q+%4q]                   ; f2
        pinsrw  %2, %4d, 2                           ; (f1, f2, 0, 0)
        movq    xmm0, qword [g0q+rvq-%1*16+8]       ; (v1, v2, 0, 0)
        pshufd  xmm1, %2, SHUFFLE_D(2, 0, 1, 1)      ; (0, f1, f2, f2)
        xor     g3d, %4d                             ; f1 ^ f2
        pshufd  xmm0, xmm0, SHUFFLE_D(0, 1, 1, 0)    ; (v1, v2, v2, v1)
        lea     %4d, [g3q*2+g3q]                     ; 3 * (f1 ^ f2)
        pxor    xmm0, xmm1                           ; (v1, v2^f1, v2^f2, v1^f2)
        add     %4q, %3q                               ; next pointer / 8
        movlps  qword [%3q*8+0*4], xmm0
        pxor    %2, xmm0                             ; (v1^f1, v2^f2^f1, ..)
        movhps  qword [%3q*8+2*4], xmm0
%endmacro

FUNC sv_create_sil_triangles_sse2_paper, 4, OUT8_NGPRS, 4, shadowIndices, facing, silEdges, numSilEdges
%if SV_BITS == 64
        movsxd  rvq, g3d              ; numSilEdges
        mov     optr%+q, g0q          ; shadowIndices
        mov     obase, g0q
        ; rsi = facing already
        mov     g0q, g2q              ; silEdges
        shr     optr%+q, 3              ; moved above the early exit (erratum E-1)
        shl     rvq, 4                  ; 64-bit: no wrap (erratum E-3)
        jz      .done
%else
        mov     rvd, g3d              ; numSilEdges
        mov     optr%+q, g0q          ; shadowIndices (obase: its stack slot)
        ; esi = facing already
        mov     g0q, g2q              ; silEdges
        shr     optr%+q, 3              ; moved above the early exit (erratum E-1)
        test    rvd, rvd                ; 0 or negative: nothing (port entry E-9;
        jle     .done                   ; the 64-bit path: jz, then an empty walk)
        shl     rvd, 4
%endif
        add     g0q, rvq
        neg     rvq

        add     rvq, 4*16
        jg      .run1

.loop4:
        SIL_EDGE 4, xmm2, optr, g2
        movlps  qword [optr%+q*8+4*4], xmm2
        SIL_EDGE 3, xmm3, g2, optr
        movlps  qword [g2q*8+4*4], xmm3
        SIL_EDGE 2, xmm2, optr, g2
        movlps  qword [optr%+q*8+4*4], xmm2
        SIL_EDGE 1, xmm3, g2, optr
        add     rvq, 4*16               ; the listing moves this above the last store
        movlps  qword [g2q*8+4*4], xmm3

        jle     .loop4

.run1:
        sub     rvq, 4*16
        jge     .done

.loop1:
        MOVSXD_P g3q, dword [g0q+rvq+0]
        movzx   g3d, byte [g1q+g3q]
        movd    xmm2, g3d
        MOVSXD_P g2q, dword [g0q+rvq+4]
        movzx   g2d, byte [g1q+g2q]
        pinsrw  xmm2, g2d, 2
        movq    xmm0, qword [g0q+rvq+8]
        pshufd  xmm1, xmm2, SHUFFLE_D(2, 0, 1, 1)
        pshufd  xmm0, xmm0, SHUFFLE_D(0, 1, 1, 0)
        pxor    xmm0, xmm1
        movlps  qword [optr%+q*8+0*4], xmm0
        movhps  qword [optr%+q*8+2*4], xmm0
        pxor    xmm2, xmm0
        movlps  qword [optr%+q*8+4*4], xmm2
        xor     g3d, g2d
        lea     g2d, [g3q*2+g3q]
        add     optr%+q, g2q

        add     rvq, 16
        jl      .loop1

.done:
        OUT8_RETURN
        RET
ENDFUNC
