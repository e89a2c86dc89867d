/*
 * open_scene (scene_open.h).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "scene_open.h"

#include <cstdio>
#include <string>

#include "shadowvol_gltf.h"
#include "shadowvol_plan.h"

#ifndef SV_DEMO_SCENE
#define SV_DEMO_SCENE "models/demo_scene.glb"
#endif

namespace svcli {

std::unique_ptr<sv::SceneSequence> open_scene(const char *command, SceneArgs &args,
                                              int &exit_status) {
    constexpr int kExitUsage = 2, kExitBadModel = 3;
    if (args.seq.file.empty()) args.seq.file = SV_DEMO_SCENE;
    if (!args.skinning.empty()) {
        args.seq.skinning = sv::skinning_kernel_by_name(args.skinning.c_str());
        if (!args.seq.skinning ||
            (args.seq.skinning->isa & sv_cpu_isa()) != args.seq.skinning->isa) {
            std::fprintf(stderr, "shadowvol %s: --skinning %s: %s\n", command,
                         args.skinning.c_str(),
                         args.seq.skinning ? "this CPU (or SV_ISA) does not run it"
                                           : "unknown (c_ref, sse2, avx2, avx512)");
            exit_status = kExitUsage;
            return nullptr;
        }
    }
    args.seq.aspect = (double)args.width / args.height;
    /* The plans `shadowvol tune` measured for this CPU (the volume kernels',
     * the skinned surfaces' deforming pass and the stencil method), as bench
     * and check read them; without the file, the static choices. Every
     * choice gives the same bytes. */
    char wisdom[1024];
    sv_wisdom_load(sv_wisdom_default_path(wisdom, sizeof wisdom));
    take_stencil_default(args.stencil);
    std::unique_ptr<sv::SceneSequence> seq;
    try {
        seq = std::make_unique<sv::SceneSequence>(args.seq);
    } catch (const sv::GltfError &e) {
        std::fprintf(stderr, "shadowvol %s: %s\n", command, e.what());
        if (!args.seq.animation.empty() && !args.seq.adds.empty()) {
            /* What a new user tried (issue 30): --animation for the file just added. */
            std::fprintf(stderr,
                         "note: --animation is the scene file's (%s); an added file's is "
                         "--add FILE:ANIMATION\n",
                         args.seq.file.c_str());
        }
        exit_status = kExitBadModel;
        return nullptr;
    } catch (const sv::PrepareError &e) {
        std::fprintf(stderr, "shadowvol %s: %s: %s\n", command, args.seq.file.c_str(), e.what());
        exit_status = kExitBadModel;
        return nullptr;
    } catch (const sv::SceneError &e) {
        std::fprintf(stderr, "shadowvol %s: %s\n", command, e.what());
        exit_status = kExitUsage;
        return nullptr;
    }
    for (const std::string &n : seq->scene().notes) std::fprintf(stderr, "note: %s\n", n.c_str());
    return seq;
}

} // namespace svcli
