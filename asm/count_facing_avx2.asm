; count_facing_avx2.asm: being written (issue 6); no functions yet.
%include "sv_abi.inc"
