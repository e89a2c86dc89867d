; create_cap_triangles_avx512.asm: being written (issue 6); no functions yet.
%include "sv_abi.inc"
