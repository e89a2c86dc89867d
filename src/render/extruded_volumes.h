/*
 * Seed 002's shadow volumes in the frame (issue 31; C. Brennan, "Shadow
 * Volume Extrusion using a Vertex Shader", ShaderX 2002): `render --volume
 * extrude`. For every (light, surface) pair the volume pass decided to
 * draw, the paper's volume is replaced by the seed's: the surface's shadow
 * mesh (build_shadow_mesh under the frame's caster rule, ground hints
 * aside: see use_extruded_volumes) through the
 * vertex program emulated on the CPU (shadowvol_extrude.h), drawn whole in
 * z-fail.
 *
 * The seed's vertices are written in the paper's numbering, so every
 * stencil method, both judges and the overlays draw it unchanged: vertex
 * 3t + k of the shadow mesh (corner k of face t, vertex v of the surface)
 * becomes 2v where the program keeps it in place and 2v + 1 where it
 * extrudes it, and Volume::extruded[v] is the program's output for v
 * (every copy of v extruded comes out the same: the program reads only
 * the position, the light and its range). The quads that stay degenerate
 * become triangles with a repeated vertex, which set-up counts and rejects
 * as zero-area, as a GPU would.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_RENDER_EXTRUDED_VOLUMES_H
#define SV_RENDER_EXTRUDED_VOLUMES_H

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "frame.h"
#include "shadowvol_extrude.h"

namespace sv::render {

const char *volume_source_name(VolumeSource v);
/* "silhouette" or "extrude"; false for anything else. */
bool volume_source_by_name(const std::string &name, VolumeSource &out);

/* The seed's light for LIGHT: its shadow_light() and its range (0 = to
 * infinity; directional lights go to infinity whatever their range). With
 * TO_INFINITY the range is dropped: the seed's program then extrudes as
 * the paper does. */
sv_extrude_light extrude_light_for(const SceneLight &light, bool to_infinity);

/* Another vertex program for a shadow mesh (RenderOptions::extrude_program
 * for one surface): true where it wrote the output. */
using ExtrudeProgram =
    std::function<bool(const ShadowMesh &mesh, const sv_extrude_light &light, Vec4 *out)>;

/* Seed 002's volume of caster CASTER (the surface itself, or its two-sided
 * caster: the same vertex numbers) under LIGHT, by VARIANT (or by PROGRAM
 * where it is given and writes): indices in the paper's numbering and the
 * extruded vertices, as above. MESH is CASTER's shadow mesh.
 * PROGRAM_TICKS, where given, gets the TSC ticks of the vertex program's
 * call alone (what a GPU would run; the renumbering is this CPU
 * renderer's). */
Volume extruded_volume(const PreparedSurface &caster, const ShadowMesh &mesh,
                       const sv_extrude_light &light, const sv_extrude_variant *variant,
                       uint64_t *program_ticks = nullptr, const ExtrudeProgram &program = {});

/* Replaces the volumes of LIGHTS (after volume_pass) by the seed's, for
 * each surface whose decision is built or reused (the light reaches it,
 * its shadow may reach the view, something casts: the paper's shortcuts 1
 * and 2, which hold for the seed's volume, a part of the paper's); the
 * volume's decision says z-fail and its indices; the extrusion's ticks go
 * to ticks_extrude. OPT: the caster rule, extrude_to_infinity. The ground
 * hints do not apply to the seed's volumes: a declared ground keeps the
 * paper's rule because the paper's volume (near cap: the faces turned
 * away from the light) is exact for a surface never seen from below; the
 * seed's near cap is the faces turned to the light, and an open surface's
 * seed volume is closed only by the general rule (two-sided). */
void use_extruded_volumes(const Scene &scene, const RenderOptions &opt,
                          std::vector<LightFrame> &lights);

} // namespace sv::render

#endif
