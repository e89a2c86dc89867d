/*
 * The scene in time (src/scene/sequence.h, issue 13) on the demo scene the
 * build writes: the file's lights and camera; only the skinned character
 * moves, so only it gets a new revision and new planes; times outside the
 * walk clamp; frames reuse the static volumes; the frame is the same with
 * every skinning kernel and planes variant (all bit-identical to their
 * references); an unknown animation is refused with the list.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "frame.h"
#include "sequence.h"
#include "test_conditions.h"

namespace {

using namespace sv;

#ifdef SV_TEST_SMALL_FRAMES
constexpr int kW = 96, kH = 64;
#else
constexpr int kW = 240, kH = 136;
#endif

SequenceOptions demo() {
    SequenceOptions o;
    o.file = SV_DEMO_SCENE;
    o.aspect = (double)kW / kH;
    return o;
}

int find(const Scene &s, const std::string &suffix) {
    for (std::size_t i = 0; i < s.surfaces.size(); i++) {
        const std::string &n = s.surfaces[i].name;
        if (n.size() >= suffix.size() &&
            n.compare(n.size() - suffix.size(), suffix.size(), suffix) == 0) {
            return (int)i;
        }
    }
    return -1;
}

TEST(Sequence, DemoSceneHasItsLightsCameraAndWalk) {
    SceneSequence seq(demo());
    const Scene &s = seq.scene();
    EXPECT_TRUE(seq.animated());
    EXPECT_EQ(seq.animation_name(), "walk");
    EXPECT_DOUBLE_EQ(seq.start(), 0.0);
    EXPECT_DOUBLE_EQ(seq.end(), 1.0);
    ASSERT_EQ(s.lights.size(), 4u);
    EXPECT_EQ(s.lights[0].kind, LightKind::point);
    EXPECT_GT(s.lights[0].range, 0);
    EXPECT_EQ(s.lights[1].kind, LightKind::spot);
    EXPECT_EQ(s.lights[2].kind, LightKind::spot);
    EXPECT_EQ(s.lights[3].kind, LightKind::directional);
    EXPECT_GT(s.camera.near_distance, 0);
    EXPECT_GE(find(s, "terrain @ terrain"), 0);
    EXPECT_GT(s.triangles(), 100000);
    /* The terrain is declared ground in its file (docs/CASTERS.md, "The
     * ground hint"), through the animated loader too; nothing else is. */
    for (const SceneSurface &surface : s.surfaces)
        EXPECT_EQ(surface.declared_ground,
                  surface.name.find("terrain @ terrain") != std::string::npos)
            << surface.name;
}

TEST(Sequence, OnlyTheCharacterMovesAndTimesClamp) {
    SceneSequence seq(demo());
    const int ch = find(seq.scene(), "character @ character");
    ASSERT_GE(ch, 0);
    std::vector<uint64_t> rev;
    for (const SceneSurface &s : seq.scene().surfaces) rev.push_back(s.revision);
    const PoseStats a = seq.set_time(0.25);
    EXPECT_EQ(a.surfaces_moved, 1);
    EXPECT_EQ(a.planes_derived, seq.scene().surfaces[(std::size_t)ch].prepared.num_triangles());
    for (std::size_t i = 0; i < rev.size(); i++) {
        EXPECT_EQ(seq.scene().surfaces[i].revision, rev[i] + ((int)i == ch))
            << seq.scene().surfaces[i].name;
    }
    /* The same time again: nothing moves. */
    EXPECT_EQ(seq.set_time(0.25).surfaces_moved, 0);
    /* Beyond the walk's end: the end's pose (glTF clamps). */
    seq.set_time(1.0);
    const std::vector<float> at_end = seq.scene().surfaces[(std::size_t)ch].prepared.positions;
    EXPECT_EQ(seq.set_time(7.5).surfaces_moved, 0);
    EXPECT_EQ(seq.scene().surfaces[(std::size_t)ch].prepared.positions, at_end);
    seq.set_time(-3);
    const std::vector<float> before = seq.scene().surfaces[(std::size_t)ch].prepared.positions;
    seq.set_time(0);
    EXPECT_EQ(seq.scene().surfaces[(std::size_t)ch].prepared.positions, before);
}

SV_TIERED_TEST(Sequence, StaticVolumesAreReusedAndKernelsAgree) {
    render::RenderOptions o;
    o.width = kW, o.height = kH;
    render::VolumeCache cache;
    o.cache = &cache;
    SceneSequence seq(demo());
    (void)render::render_frame(seq.scene(), o);
    seq.set_time(0.125);
    const render::Frame f = render::render_frame(seq.scene(), o);
    int reused = 0, built = 0;
    for (const auto &lf : f.lights) reused += lf.reused, built += lf.built;
    EXPECT_GT(reused, 0);
    EXPECT_LE(built, (int)f.lights.size()) << "only the character's volumes are built again";
    /* Every skinning kernel and planes variant this CPU runs: the same frame. */
    int nk = 0, np = 0;
    const SkinningKernel *kernels = skinning_kernels(&nk);
    const sv_planes_variant *planes = sv_planes_variants(&np);
    for (int k = 0; k < nk; k++) {
        if (!svtest::in_this_run(kernels[k].isa, kernels[k].name)) continue;
        for (int p = 0; p < np; p++) {
            if (!svtest::in_this_run(planes[p].isa, planes[p].name)) continue;
            SequenceOptions so = demo();
            so.skinning = &kernels[k];
            so.planes = &planes[p];
            SceneSequence other(so);
            other.set_time(0.125);
            render::RenderOptions q = o;
            q.cache = nullptr;
            const render::Frame g = render::render_frame(other.scene(), q);
            EXPECT_EQ(g.rgb, f.rgb) << kernels[k].name << " / " << planes[p].name;
        }
    }
    /* The planes by clusters: the same planes, bit for bit, and frame. */
    int nc = 0;
    const sv_planes_clustered_variant *clustered = sv_planes_clustered_variants(&nc);
    for (int c = 0; c < nc; c++) {
        if (!svtest::in_this_run(clustered[c].isa, clustered[c].name)) continue;
        SequenceOptions so = demo();
        so.clustered = &clustered[c];
        SceneSequence other(so);
        for (double t : {0.125, 0.5}) {
            seq.set_time(t);
            other.set_time(t);
            const Scene &a = seq.scene(), &b = other.scene();
            ASSERT_EQ(a.surfaces.size(), b.surfaces.size());
            for (std::size_t i = 0; i < a.surfaces.size(); i++) {
                const auto &pa = a.surfaces[i].prepared.planes, &pb = b.surfaces[i].prepared.planes;
                ASSERT_EQ(pa.size(), pb.size());
                EXPECT_EQ(std::memcmp(pa.data(), pb.data(), pa.size() * sizeof(Plane)), 0)
                    << clustered[c].name << ", surface " << i << ", time " << t;
            }
        }
        render::RenderOptions q = o;
        q.cache = nullptr;
        other.set_time(0.125);
        seq.set_time(0.125);
        EXPECT_EQ(render::render_frame(other.scene(), q).rgb, f.rgb) << clustered[c].name;
    }
}

TEST(Sequence, UnknownAnimationIsRefusedWithTheList) {
    SequenceOptions o = demo();
    o.animation = "run";
    try {
        SceneSequence seq(o);
        FAIL() << "an unknown animation was accepted";
    } catch (const GltfError &e) {
        EXPECT_NE(std::string(e.what()).find("'walk'"), std::string::npos) << e.what();
    }
    o.animation = "0";
    EXPECT_NO_THROW(SceneSequence{o});
}

/* Each added file plays its own animation (issue 30), and a refusal names
 * the file it is about, not the scene file. */
TEST(Sequence, AnAddedFilePlaysItsOwnAnimation) {
    SequenceOptions o = demo();
    o.adds.push_back(parse_model_placement(std::string(SV_DEMO_SCENE) + "@30,0,0:walk"));
    SceneSequence named(o);
    EXPECT_NE(named.describe().at(1).find("animation 0 'walk'"), std::string::npos)
        << named.describe().at(1);
    o.adds.back() = parse_model_placement(std::string(SV_DEMO_SCENE) + "@30,0,0:run");
    o.file = SV_MODELS_DIR "/character_1344.glb"; /* no animations: the error is the add's */
    try {
        SceneSequence seq(o);
        FAIL() << "an added file's unknown animation was accepted";
    } catch (const GltfError &e) {
        const std::string m = e.what();
        EXPECT_EQ(m.rfind(SV_DEMO_SCENE, 0), 0u) << "the message names the added file: " << m;
        EXPECT_NE(m.find("no animation 'run'"), std::string::npos) << m;
        EXPECT_NE(m.find("'walk'"), std::string::npos) << "it lists the file's: " << m;
    }
}

} // namespace
