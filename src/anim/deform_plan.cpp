/*
 * The deforming pass chosen by measurement (include/shadowvol_anim.h,
 * "The deforming pass chosen by measurement"): reading the planner's
 * choices, checked against this layer's tables, and measuring them.
 *
 * Why measure: the widest kernel is not always the fastest. On an Intel
 * Xeon guest (family 6 model 207) the AVX2 planes beat the AVX-512 ones
 * (docs/PLANES.md), and whether the one-pass kernel beats the two passes
 * depends on how much of a surface the first-level cache holds.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "shadowvol_anim.h"

#include <x86intrin.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace sv {

namespace {

bool runs(unsigned isa) { return (isa & sv_cpu_isa()) == isa; }

/* The class's choice for R when its name is in the table and runs here. */
template <class T, class Lookup>
const T *chosen(int size_class, sv_deform_routine r, Lookup lookup, const char **source) {
    sv_deform_choice c;
    if (sv_deform_choice_for(size_class, r, &c) != 1) return nullptr;
    const T *k = lookup(c.variant);
    if (!k || !runs(k->isa)) return nullptr;
    *source = c.source;
    return k;
}

/* A height field of about TRIANGLES triangles, skinned to 24 joints with 4
 * influences each, vertices in row order (as exported meshes number them:
 * by first use). */
struct SkinnedField {
    std::vector<float> rest, weights, matrices;
    std::vector<uint16_t> joints;
    std::vector<int> indices;
    std::size_t vertices = 0;
    int triangles = 0;
};

SkinnedField skinned_field(int triangles) {
    SkinnedField f;
    const int n = std::max(1, (int)std::lround(std::sqrt(triangles / 2.0)));
    const int w = n + 1;
    uint64_t s = 0x9E3779B97F4A7C15ull;
    auto unit = [&]() {
        s = s * 6364136223846793005ull + 1442695040888963407ull;
        return (double)(s >> 11) / (double)(1ull << 53);
    };
    for (int j = 0; j < w; j++) {
        for (int i = 0; i < w; i++) {
            f.rest.push_back((float)(i * 0.25));
            f.rest.push_back((float)(0.5 * std::sin(i * 0.1) * std::cos(j * 0.07)));
            f.rest.push_back((float)(j * 0.25));
            for (int k = 0; k < 4; k++) {
                f.joints.push_back((uint16_t)((i / 8 + j / 8 + k) % 24));
                f.weights.push_back((float)(0.1 + unit()));
            }
        }
    }
    for (int j = 0; j < n; j++) {
        for (int i = 0; i < n; i++) {
            const int a = j * w + i, b = a + 1, c = a + w, d = c + 1;
            const int tri[6] = {a, c, b, b, c, d};
            f.indices.insert(f.indices.end(), tri, tri + 6);
        }
    }
    f.vertices = (std::size_t)w * (std::size_t)w;
    f.triangles = 2 * n * n;
    f.matrices.resize(16 * 24);
    for (int m = 0; m < 24; m++) { /* near-rigid: a rotation about y and a shift */
        const double a = 0.3 * unit() - 0.15, c = std::cos(a), sn = std::sin(a);
        const float col[16] = {(float)c,
                               0,
                               (float)-sn,
                               0,
                               0,
                               1,
                               0,
                               0,
                               (float)sn,
                               0,
                               (float)c,
                               0,
                               (float)unit(),
                               (float)unit(),
                               (float)unit(),
                               1};
        std::copy(col, col + 16, f.matrices.begin() + 16 * m);
    }
    return f;
}

/* Median ticks of CALLS calls of RUN. */
template <class Run> double median_ticks(int calls, Run run) {
    std::vector<uint64_t> t((std::size_t)calls);
    for (int i = 0; i < calls; i++) {
        const uint64_t t0 = __rdtsc();
        run();
        t[(std::size_t)i] = __rdtsc() - t0;
    }
    std::nth_element(t.begin(), t.begin() + calls / 2, t.end());
    return (double)t[(std::size_t)calls / 2];
}

} // namespace

DeformPlan deform_plan_for(int num_triangles) {
    const int c = sv_size_class(num_triangles);
    DeformPlan p;
    const char *source = "static";
    p.skinning = chosen<SkinningKernel>(c, SV_DEFORM_SKINNING, skinning_kernel_by_name, &source);
    if (!p.skinning) p.skinning = best_skinning_kernel();
    p.planes = chosen<sv_planes_variant>(c, SV_DEFORM_DERIVE_PLANES, sv_planes_variant_by_name,
                                         &source);
    if (!p.planes) p.planes = sv_best_planes_variant();
    p.clustered = chosen<sv_planes_clustered_variant>(c, SV_DEFORM_PLANES_CLUSTERED,
                                                      sv_planes_clustered_variant_by_name, &source);
    source = "static";
    p.skin_planes = chosen<SkinPlanesKernel>(c, SV_DEFORM_SKIN_PLANES, skin_planes_kernel_by_name,
                                             &source);
    sv_deform_choice two;
    if (!p.skin_planes && sv_deform_choice_for(c, SV_DEFORM_SKIN_PLANES, &two) == 1 &&
        std::strcmp(two.variant, "none") == 0) {
        source = two.source;
    }
    p.source = source;
    return p;
}

std::vector<DeformTiming> measure_deform_plan(int size_class) {
    const int target = sv_size_class_triangles(size_class);
    if (target <= 0) {
        throw std::runtime_error("measure_deform_plan: no size class " +
                                 std::to_string(size_class));
    }
    const SkinnedField f = skinned_field(target);
    const double per = 1.0 / f.triangles;
    const SkinPlanesSchedule sch = skin_planes_schedule(f.indices.data(), f.triangles, f.vertices);

    AlignedVector<float> want(3 * f.vertices), pos(3 * f.vertices);
    AlignedVector<Plane> want_planes((std::size_t)f.triangles), planes((std::size_t)f.triangles);
    const SkinningKernel *cref = skinning_kernel_by_name("c_ref");
    cref->fn(f.matrices.data(), f.rest.data(), f.joints.data(), f.weights.data(), 4, f.vertices,
             want.data());
    sv_derive_planes_c_ref(want.data(), f.indices.data(), f.triangles, want_planes.data());

    struct Candidate {
        sv_deform_routine routine;
        std::string name;
        std::function<void()> run;
        bool planes_too;
        double best = INFINITY;
    };
    std::vector<Candidate> cands;
    int n = 0;
    const SkinningKernel *sk = skinning_kernels(&n);
    for (int i = 0; i < n; i++) {
        if (!runs(sk[i].isa)) continue;
        const SkinningKernel *k = &sk[i];
        cands.push_back({SV_DEFORM_SKINNING, k->name,
                         [&, k] {
                             k->fn(f.matrices.data(), f.rest.data(), f.joints.data(),
                                   f.weights.data(), 4, f.vertices, pos.data());
                         },
                         false});
    }
    const sv_planes_variant *pv = sv_planes_variants(&n);
    for (int i = 0; i < n; i++) {
        if (!runs(pv[i].isa)) continue;
        const sv_planes_variant *v = &pv[i];
        cands.push_back({SV_DEFORM_DERIVE_PLANES, v->name,
                         [&, v] {
                             v->derive_planes(want.data(), f.indices.data(), f.triangles,
                                              planes.data());
                         },
                         true});
    }
    const PlaneClusters clusters = plane_clusters(f.indices.data(), f.triangles, (int)f.vertices);
    const sv_plane_clusters cview = clusters.view();
    const sv_planes_clustered_variant *cv = sv_planes_clustered_variants(&n);
    for (int i = 0; i < n; i++) {
        if (!runs(cv[i].isa)) continue;
        const sv_planes_clustered_variant *v = &cv[i];
        cands.push_back({SV_DEFORM_PLANES_CLUSTERED, v->name,
                         [&, v] { v->derive_planes(want.data(), &cview, planes.data()); }, true});
    }
    sv_skin_planes_args args{};
    args.joint_matrices = f.matrices.data();
    args.rest = f.rest.data();
    args.joints = f.joints.data();
    args.weights = f.weights.data();
    args.influences = 4;
    args.num_vertices = f.vertices;
    args.indices = f.indices.data();
    args.num_triangles = f.triangles;
    args.segments = (int)sch.triangle_end.size();
    args.vertex_end = sch.vertex_end.data();
    args.triangle_end = sch.triangle_end.data();
    args.out = pos.data();
    args.planes = planes.data();
    const SkinPlanesKernel *fk = skin_planes_kernels(&n);
    for (int i = 0; i < n; i++) {
        if (!runs(fk[i].isa)) continue;
        const SkinPlanesKernel *k = &fk[i];
        cands.push_back({SV_DEFORM_SKIN_PLANES, k->name, [&, k] { k->fn(&args); }, true});
    }

    /* Rounds of a few calls each, all candidates per round, so that a slow
     * phase of a shared machine hits them all; the lowest round median. */
    const int rounds = 5;
    const int calls = std::clamp(200000 / std::max(1, f.triangles), 1, 50);
    for (int r = 0; r < rounds; r++) {
        for (Candidate &c : cands) {
            std::memset(pos.data(), 0xCD, 4 * pos.size());
            std::memset(static_cast<void *>(planes.data()), 0xCD, sizeof(Plane) * planes.size());
            c.run();
            const bool pos_ok = c.routine == SV_DEFORM_DERIVE_PLANES ||
                                c.routine == SV_DEFORM_PLANES_CLUSTERED ||
                                std::memcmp(pos.data(), want.data(), 4 * pos.size()) == 0;
            const bool planes_ok = !c.planes_too ||
                                   std::memcmp(static_cast<const void *>(planes.data()),
                                               static_cast<const void *>(want_planes.data()),
                                               sizeof(Plane) * planes.size()) == 0;
            if (!pos_ok || !planes_ok) {
                throw std::runtime_error(std::string("measure_deform_plan: ") +
                                         sv_deform_routine_name(c.routine) + " " + c.name +
                                         " differs from the C reference");
            }
            c.best = std::min(c.best, median_ticks(calls, c.run) * per);
        }
    }

    /* The winners: the static choice unless another is > 3% faster. */
    auto pick = [&](sv_deform_routine r, const std::string &stat) {
        const Candidate *best = nullptr, *st = nullptr;
        for (const Candidate &c : cands) {
            if (c.routine != r) continue;
            if (!best || c.best < best->best) best = &c;
            if (c.name == stat) st = &c;
        }
        return st && !(best->best < st->best / 1.03) ? st : best;
    };
    const Candidate *ks = pick(SV_DEFORM_SKINNING, best_skinning_kernel()->name);
    const Candidate *kp = pick(SV_DEFORM_DERIVE_PLANES, sv_best_planes_variant()->name);
    /* Clusters only when more than 3% faster than the chosen variant. */
    const Candidate *kc = nullptr;
    for (const Candidate &c : cands) {
        if (c.routine == SV_DEFORM_PLANES_CLUSTERED && c.best < kp->best / 1.03 &&
            (!kc || c.best < kc->best)) {
            kc = &c;
        }
    }
    const double two = ks->best + (kc ? kc->best : kp->best);
    const Candidate *kf = nullptr;
    for (const Candidate &c : cands) {
        if (c.routine == SV_DEFORM_SKIN_PLANES && c.best < two / 1.03 &&
            (!kf || c.best < kf->best)) {
            kf = &c;
        }
    }
    sv_deform_choice_set(size_class, SV_DEFORM_SKINNING, ks->name.c_str(), ks->best);
    sv_deform_choice_set(size_class, SV_DEFORM_DERIVE_PLANES, kp->name.c_str(), kp->best);
    sv_deform_choice_set(size_class, SV_DEFORM_PLANES_CLUSTERED, kc ? kc->name.c_str() : "none",
                         kc ? kc->best : kp->best);
    sv_deform_choice_set(size_class, SV_DEFORM_SKIN_PLANES, kf ? kf->name.c_str() : "none",
                         kf ? kf->best : two);

    std::vector<DeformTiming> out;
    out.reserve(cands.size() + 2);
    for (std::size_t i = 0; i < cands.size(); i++) {
        const Candidate &c = cands[i];
        out.push_back({c.routine, c.name, c.best});
        /* "none" (the chosen planes variant) after the clustered kernels. */
        if (c.routine == SV_DEFORM_PLANES_CLUSTERED &&
            (i + 1 == cands.size() || cands[i + 1].routine != SV_DEFORM_PLANES_CLUSTERED)) {
            out.push_back({SV_DEFORM_PLANES_CLUSTERED, "none", kp->best});
        }
    }
    out.push_back({SV_DEFORM_SKIN_PLANES, "two_passes", two});
    return out;
}

} // namespace sv
