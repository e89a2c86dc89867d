/*
 * The CPU skinning kernels behind sv::SkinningKernel (include/shadowvol_anim.h
 * gives the contract and the order of operations every one of them keeps).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_SKINNING_KERNELS_H
#define SV_SKINNING_KERNELS_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define SV_SKIN_ARGS                                                                               \
    const float *joint_matrices, const float *rest, const uint16_t *joints, const float *weights,  \
        int influences, size_t num_vertices, float *out

void sv_skin_c_ref(SV_SKIN_ARGS);
void sv_skin_sse2(SV_SKIN_ARGS);
void sv_skin_avx2(SV_SKIN_ARGS);
void sv_skin_avx512(SV_SKIN_ARGS);

#ifdef __cplusplus
}
#endif

#endif
