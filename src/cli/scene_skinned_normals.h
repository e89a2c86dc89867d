/*
 * `shadowvol scene --volume extrude --skinned-normals WAY` (issue 31, seed
 * 002's Figure 4): the skinned surfaces' shadow meshes get their face
 * normals WAY (src/extrude/skinned_normals.h: straightforward, face
 * weights, recomputed, or the neighbour fix with its own program), and
 * each frame is drawn again with the recomputed normals (the default's:
 * the per-frame planes) to count the shadow pixels that differ where the
 * light reaches (compare_frames' mask_in_reach: out of reach, shortcuts
 * may leave other counts, and nothing is lit either way).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_CLI_SCENE_SKINNED_NORMALS_H
#define SV_CLI_SCENE_SKINNED_NORMALS_H

#include <memory>
#include <string>
#include <vector>

#include "frame.h"
#include "sequence.h"
#include "skinned_normals.h"

namespace svcli {

class SceneSkinnedNormals {
public:
    /* SEQ's skinned surfaces (their static data made here), WAY. */
    SceneSkinnedNormals(const sv::SceneSequence &seq, sv::SkinnedNormals way);

    /* After each set_time: the skinned surfaces' joint matrices and
     * positions of the current frame, which OPT's hooks (set here) read.
     * The hooks follow the caster rule's shadow mesh: a two-sided caster's
     * reverses get their sources' normals negated. */
    void apply(sv::render::RenderOptions &opt);

private:
    struct Surface {
        const sv::AnimatedSurface *animated = nullptr;
        sv::SkinnedNormalData data;
        sv::SkinnedFrame frame;
    };
    const sv::SceneSequence &seq_;
    sv::SkinnedNormals way_;
    std::vector<std::unique_ptr<Surface>> surfaces_; /* per scene surface; null: not skinned */
};

} // namespace svcli

#endif
