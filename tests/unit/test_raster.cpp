/*
 * The rasteriser (src/raster): watertightness, the fill rule, clipping,
 * vertices at w = 0, 8-bit wrap-around, a canonical depth, and the SIMD
 * triangle walks bit-identical to the C.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>
#include <stdexcept>
#include <vector>

#include "frame.h"
#include "rasterizer.h"
#include "shadowvol.h"
#include "shadowvol_scene.h"
#include "test_conditions.h"

namespace {

using namespace sv::raster;

/* Window pixel (x, y down) and depth to clip space with w = 1. */
ClipVertex px(double x, double y, double z, int w, int h) {
    return {x / w * 2 - 1, 1 - y / h * 2, z * 2 - 1, 1};
}

std::vector<const RowKernels *> runnable_kernels() {
    int n = 0;
    const RowKernels *const *all = row_kernels_all(&n);
    std::vector<const RowKernels *> out;
    for (int i = 0; i < n; i++) {
        if (svtest::in_this_run(all[i]->isa, all[i]->name)) out.push_back(all[i]);
    }
    return out;
}

int8_t signed_count(uint8_t s) { return (int8_t)s; }

/* The bundled character, as clip-space triangles seen from DIR. */
struct Mesh {
    std::vector<ClipVertex> v;
    std::vector<int> idx;
};
Mesh character_in_view(double yaw, double pitch, double distance, double fov) {
    sv::Scene scene;
    sv::add_model(scene, SV_MODELS_DIR "/character_1344.glb", {});
    const sv::PreparedSurface &p = scene.surfaces[0].prepared;
    const sv::Vec3d target{0, 0.9, 0};
    const sv::Vec3d eye{target.x + distance * std::cos(pitch) * std::sin(yaw),
                        target.y + distance * std::sin(pitch),
                        target.z + distance * std::cos(pitch) * std::cos(yaw)};
    const sv::Mat4d vp = sv::infinite_projection(fov, 1.25, 0.05) *
                         sv::look_at(eye, target, {0, 1, 0});
    Mesh m;
    for (int i = 0; i < p.num_vertices(); i++) {
        m.v.push_back(sv::render::to_clip(vp, p.positions[3 * i], p.positions[3 * i + 1],
                                          p.positions[3 * i + 2], 1));
    }
    m.idx.assign(p.indices.begin(), p.indices.end());
    return m;
}

/* A closed mesh drawn into the stencil with nothing in the depth buffer
 * (z-pass, every fragment passes): front +1, back -1. */
std::vector<uint8_t> closed_mesh_sum(const Mesh &m, const RowKernels *k, int w, int h) {
    Target t;
    t.resize(w, h);
    const Rasterizer r(k);
    PassCounters c;
    for (std::size_t i = 0; i < m.idx.size(); i += 3) {
        const ClipVertex v[3] = {m.v[(std::size_t)m.idx[i]], m.v[(std::size_t)m.idx[i + 1]],
                                 m.v[(std::size_t)m.idx[i + 2]]};
        r.draw_stencil(t, v, StencilMode::zpass, c);
    }
    return std::vector<uint8_t>(t.stencil.begin(), t.stencil.end());
}

SV_TIERED_TEST(Raster, ClosedMeshSumsToZeroAtEveryPixel) {
    /* Every pixel centre covered by the character's front faces is covered
     * as often by its back faces: no pixel is lost or counted twice on any
     * of its 2016 shared edges. Views from all around, at sizes that put
     * centres on edges in different ways; near enough that the side
     * planes cut it. */
    for (const RowKernels *k : runnable_kernels()) {
        int views = 0;
        for (double yaw = 0; yaw < 6.28; yaw += 0.7) {
            for (double pitch : {-0.6, 0.0, 0.5, 1.2}) {
                for (double dist : {1.2, 3.0, 12.0}) {
                    const Mesh m = character_in_view(yaw, pitch, dist, 50);
                    const std::vector<uint8_t> s = closed_mesh_sum(m, k, 160, 128);
                    for (std::size_t i = 0; i < s.size(); i++) {
                        ASSERT_EQ(s[i], 0)
                            << k->name << " yaw " << yaw << " pitch " << pitch << " distance "
                            << dist << " pixel " << i % 160 << "," << i / 160;
                    }
                    views++;
                }
            }
        }
        EXPECT_EQ(views, 9 * 4 * 3);
    }
}

SV_TIERED_TEST(Raster, SharedEdgeThroughPixelCentresCoveredOnce) {
    /* Quads split along a diagonal that passes exactly through pixel
     * centres (vertices at half-integer positions), in both windings and
     * all four diagonal directions, and axis-aligned edges on centres: each
     * centre of the quad is covered exactly once. */
    const int w = 64, h = 64;
    std::mt19937 rng(7);
    for (const RowKernels *k : runnable_kernels()) {
        const Rasterizer r(k);
        for (int trial = 0; trial < 200; trial++) {
            std::uniform_int_distribution<int> d(2, 60);
            int x0 = d(rng), y0 = d(rng), x1 = d(rng), y1 = d(rng);
            if (x0 == x1 || y0 == y1) continue;
            if (x0 > x1) std::swap(x0, x1);
            if (y0 > y1) std::swap(y0, y1);
            const double X0 = x0 + 0.5, Y0 = y0 + 0.5, X1 = x1 + 0.5, Y1 = y1 + 0.5;
            const ClipVertex a = px(X0, Y0, 0.5, w, h), b = px(X1, Y0, 0.5, w, h),
                             c = px(X1, Y1, 0.5, w, h), e = px(X0, Y1, 0.5, w, h);
            Target t;
            t.resize(w, h);
            PassCounters pc;
            const bool flip = trial & 1, other_diagonal = trial & 2;
            ClipVertex t1[3] = {a, b, c}, t2[3] = {a, c, e};
            if (other_diagonal) {
                t1[0] = a, t1[1] = b, t1[2] = e;
                t2[0] = b, t2[1] = c, t2[2] = e;
            }
            if (flip) std::swap(t1[1], t1[2]), std::swap(t2[1], t2[2]);
            r.draw_stencil(t, t1, StencilMode::zpass, pc);
            r.draw_stencil(t, t2, StencilMode::zpass, pc);
            for (int y = 0; y < h; y++) {
                for (int x = 0; x < w; x++) {
                    const uint8_t s = t.stencil[(std::size_t)y * w + x];
                    /* Inside the quad: the bottom and left edges own
                     * their centres, the top and right ones do not. */
                    const bool inside = x >= x0 && x < x1 && y > y0 && y <= y1;
                    ASSERT_EQ(s != 0, inside)
                        << k->name << " trial " << trial << " at " << x << "," << y;
                    if (inside) {
                        ASSERT_TRUE(s == 1 || s == 255) << "covered twice at " << x << "," << y;
                    }
                }
            }
        }
    }
}

SV_TIERED_TEST(Raster, BottomLeftRuleAsLlvmpipe) {
    /* A right triangle with corners on pixel centres (2.5, 2.5), (10.5,
     * 2.5), (2.5, 10.5): its left edge (x = 2.5) owns its centres; its top
     * edge (y = 2.5, the triangle below it) and its hypotenuse (x + y =
     * 13) do not. And the mirror image, with the horizontal edge at the
     * bottom (y = 10.5, the triangle above it): that edge owns its
     * centres. */
    const int w = 16, h = 16;
    for (const RowKernels *k : runnable_kernels()) {
        const Rasterizer r(k);
        for (bool reversed : {false, true}) {
            Target t;
            t.resize(w, h);
            PassCounters pc;
            ClipVertex v[3] = {px(2.5, 2.5, 0.5, w, h), px(10.5, 2.5, 0.5, w, h),
                               px(2.5, 10.5, 0.5, w, h)};
            if (reversed) std::swap(v[1], v[2]);
            r.draw_stencil(t, v, StencilMode::zpass, pc);
            for (int y = 0; y < h; y++) {
                for (int x = 0; x < w; x++) {
                    const bool expect = x >= 2 && y >= 3 && (x + 0.5) + (y + 0.5) < 13;
                    EXPECT_EQ(t.stencil[(std::size_t)y * w + x] != 0, expect)
                        << k->name << (reversed ? " reversed" : "") << " at " << x << "," << y;
                }
            }
            EXPECT_EQ(pc.pixels_tested, 7u + 6 + 5 + 4 + 3 + 2 + 1) << k->name;
            /* Flipped upside down: (2.5, 10.5), (10.5, 10.5), (2.5, 2.5). */
            t.clear_stencil();
            PassCounters pb;
            ClipVertex u[3] = {px(2.5, 10.5, 0.5, w, h), px(10.5, 10.5, 0.5, w, h),
                               px(2.5, 2.5, 0.5, w, h)};
            if (reversed) std::swap(u[1], u[2]);
            r.draw_stencil(t, u, StencilMode::zpass, pb);
            for (int y = 0; y < h; y++) {
                for (int x = 0; x < w; x++) {
                    /* Inside: x >= 2.5, y <= 10.5, y - x > 0 (the hypotenuse
                     * from (2.5, 2.5) to (10.5, 10.5) is a right edge). */
                    const bool expect = x >= 2 && y <= 10 && (y + 0.5) - (x + 0.5) > 0;
                    EXPECT_EQ(t.stencil[(std::size_t)y * w + x] != 0, expect)
                        << k->name << " flipped" << (reversed ? " reversed" : "") << " at " << x
                        << "," << y;
                }
            }
            EXPECT_EQ(pb.pixels_tested, 8u + 7 + 6 + 5 + 4 + 3 + 2 + 1) << k->name;
        }
    }
}

SV_TIERED_TEST(Raster, ACutVertexFarOffItsPlaneStaysInTheFrame) {
    /* A triangle whose ends differ by fifteen orders of magnitude in w (as
     * an extruded edge of a light almost on a vertex): the vertex clipping
     * cuts on the right plane comes out with x / w near -6e20 pixels
     * (found by a random search of the clipper). Before snap_polygon's
     * guard band, its int64 cast and the edge functions overflowed, and
     * set-up handed the row walk a first column of -1. */
    const int w = 320, h = 256;
    const ClipVertex v[3] = {{37911.6083537019, 94284.774335987197, 135032.97678016024,
                              -52248.863284100065},
                             {-1.2192594770244772e-08, -1.7967216210245658e-08,
                              2.0756543708408483e-08, 9.5473339540958948e-09},
                             {38737202.925246969, -10898806.902987299, -4193642.9211302507,
                              11989775.399345443}};
    for (const RowKernels *k : runnable_kernels()) {
        const Rasterizer r(k);
        PassCounters pc;
        std::vector<SetupTriangle> pieces;
        r.setup(v, w, h, 7, pc, pieces);
        EXPECT_EQ(pc.triangles_clipped, 1u) << k->name;
        for (const SetupTriangle &t : pieces) {
            EXPECT_GE(t.x_first, 0) << k->name;
            EXPECT_LE(t.x_last, w - 1) << k->name;
            EXPECT_GE(t.y_first, 0) << k->name;
            EXPECT_LE(t.y_last, h - 1) << k->name;
        }
        Target t;
        t.resize(w, h);
        r.draw_depth(t, v, 7, pc);
        EXPECT_LE(pc.pixels_written, (uint64_t)w * h) << k->name;
    }
}

TEST(Raster, RefusesTargetsBeyondTheProvedSide) {
    Target t;
    EXPECT_THROW(t.resize(kMaxTargetSide + 1, 8), std::invalid_argument);
    EXPECT_THROW(t.resize(8, 0), std::invalid_argument);
    t.resize(kMaxTargetSide, 1);
    EXPECT_EQ(t.width, kMaxTargetSide);
    const Rasterizer r(&kRowKernelsC);
    PassCounters pc;
    std::vector<SetupTriangle> pieces;
    const ClipVertex v[3] = {{-1, -1, 0, 1}, {1, -1, 0, 1}, {-1, 1, 0, 1}};
    EXPECT_THROW(r.setup(v, kMaxTargetSide + 1, 8, 0, pc, pieces), std::invalid_argument);
    EXPECT_TRUE(pieces.empty());
}

TEST(Raster, FrontIsCounterClockwiseWithYUp) {
    /* Counter-clockwise on the screen with y up (GL's default front face)
     * counts +1 in z-pass, the other winding -1 (255). */
    const int w = 8, h = 8;
    const Rasterizer r(&kRowKernelsC);
    Target t;
    t.resize(w, h);
    PassCounters pc;
    /* Window y down: (1,7) (7,7) (1,1) is counter-clockwise with y up. */
    const ClipVertex ccw[3] = {px(1, 7, 0.5, w, h), px(7, 7, 0.5, w, h), px(1, 1, 0.5, w, h)};
    r.draw_stencil(t, ccw, StencilMode::zpass, pc);
    EXPECT_EQ(t.stencil[3 * w + 2], 1);
    const ClipVertex cw[3] = {ccw[0], ccw[2], ccw[1]};
    r.draw_stencil(t, cw, StencilMode::zpass, pc);
    r.draw_stencil(t, cw, StencilMode::zpass, pc);
    EXPECT_EQ(t.stencil[3 * w + 2], 255);
}

SV_TIERED_TEST(Raster, StencilWrapsAround256) {
    const int w = 8, h = 8;
    for (const RowKernels *k : runnable_kernels()) {
        const Rasterizer r(k);
        Target t;
        t.resize(w, h);
        PassCounters pc;
        const ClipVertex full[3] = {{-1, -1, 0, 1}, {3, -1, 0, 1}, {-1, 3, 0, 1}};
        for (int i = 0; i < 300; i++) r.draw_stencil(t, full, StencilMode::zpass, pc);
        for (uint8_t s : t.stencil) ASSERT_EQ(s, 300 % 256) << k->name;
        const ClipVertex back[3] = {full[0], full[2], full[1]};
        for (int i = 0; i < 556; i++) r.draw_stencil(t, back, StencilMode::zpass, pc);
        for (uint8_t s : t.stencil) ASSERT_EQ(s, (uint8_t)(300 - 556)) << k->name;
        EXPECT_EQ(pc.pixels_written, 856u * w * h);
    }
}

SV_TIERED_TEST(Raster, ZPassAndZFailAgainstTheDepth) {
    /* A receiver at depth 0.5; a triangle in front counts in z-pass only,
     * one behind in z-fail only; a triangle at exactly the receiver's
     * depth fails LESS, so it counts in z-fail. */
    const int w = 16, h = 16;
    for (const RowKernels *k : runnable_kernels()) {
        const Rasterizer r(k);
        Target t;
        t.resize(w, h);
        PassCounters pc;
        const ClipVertex recv[3] = {{-1, -1, 0, 1}, {3, -1, 0, 1}, {-1, 3, 0, 1}};
        r.draw_depth(t, recv, 7, pc);
        EXPECT_EQ(t.ids[5], 7);
        for (double z : {-0.5, 0.5, 0.0}) {
            for (StencilMode m : {StencilMode::zpass, StencilMode::zfail}) {
                t.clear_stencil();
                const ClipVertex tri[3] = {{-1, -1, z, 1}, {3, -1, z, 1}, {-1, 3, z, 1}};
                r.draw_stencil(t, tri, m, pc);
                const bool in_front = z < 0.0;
                const bool counts = (m == StencilMode::zpass) == in_front;
                /* Front face: z-pass +1, z-fail -1. */
                const uint8_t expect = !counts ? 0 : m == StencilMode::zpass ? 1 : 255;
                for (uint8_t s : t.stencil) ASSERT_EQ(s, expect) << k->name << " z " << z;
            }
        }
    }
}

SV_TIERED_TEST(Raster, VertexAtInfinityLandsAtTheVanishingPoint) {
    /* The extruded vertices have w = 0: a direction. Straight ahead
     * (0, 0, -1, 0) in eye space projects to the screen's centre at depth
     * 1 - 2^-21 with the infinite projection. */
    const int w = 64, h = 64;
    const sv::Mat4d p = sv::infinite_projection(60, 1, 0.1);
    const auto far = sv::render::to_clip(p, 0, 0, -1, 0);
    EXPECT_DOUBLE_EQ(far.z / far.w, 1 - sv::kInfiniteFarEpsilon);
    const ClipVertex a = sv::render::to_clip(p, -1, -1, -2, 1),
                     b = sv::render::to_clip(p, 1, -1, -2, 1);
    const ClipVertex v[3] = {a, b, far};
    for (const RowKernels *k : runnable_kernels()) {
        const Rasterizer r(k);
        Target t;
        t.resize(w, h);
        PassCounters pc;
        r.draw_depth(t, v, 1, pc);
        /* Just below the centre: covered, almost at the far plane. */
        EXPECT_EQ(t.ids[(std::size_t)(h / 2 + 1) * w + w / 2], 1) << k->name;
        EXPECT_EQ(t.ids[(std::size_t)(h / 2 - 2) * w + w / 2], -1) << k->name; /* above: not */
        const float zc = t.depth[(std::size_t)(h / 2 + 1) * w + w / 2];
        EXPECT_GT(zc, 0.99f);
        EXPECT_LT(zc, 1.0f);
        EXPECT_EQ(pc.triangles_outside, 0u);
    }
}

SV_TIERED_TEST(Raster, NearPlaneClipsAVolumeWatertight) {
    /* The character from so close that the near plane cuts it: the part in
     * front of the near plane is gone, so z-pass sums are no longer zero
     * where the cut is; but pixels whose whole column lies behind the near
     * plane still sum to zero, and clipping created no pixel that is
     * counted twice: every sum is -1, 0 or +1. */
    for (const RowKernels *k : runnable_kernels()) {
        const Mesh m = character_in_view(0.3, 0.1, 0.12, 70);
        const std::vector<uint8_t> s = closed_mesh_sum(m, k, 200, 160);
        int nonzero = 0;
        for (uint8_t v : s) {
            ASSERT_TRUE(v == 0 || v == 1 || v == 255) << k->name << ": " << (int)signed_count(v);
            nonzero += v != 0;
        }
        EXPECT_GT(nonzero, 0) << "the near plane was expected to cut the mesh";
    }
}

SV_TIERED_TEST(Raster, DepthDoesNotDependOnCornerOrder) {
    /* The same triangle drawn in all six corner orders (a near cap is the
     * triangle reversed), also cut by the near plane and the sides, gives
     * bitwise the same depths: a receiver never fights its own cap. */
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-1.5, 1.5), zz(-1.2, 1.0), ww(0.2, 2.0);
    const int w = 48, h = 40;
    for (const RowKernels *k : runnable_kernels()) {
        const Rasterizer r(k);
        for (int trial = 0; trial < 100; trial++) {
            ClipVertex v[3];
            for (ClipVertex &q : v) {
                const double wv = ww(rng);
                q = {u(rng) * wv, u(rng) * wv, zz(rng) * wv, wv};
            }
            std::vector<float> first;
            Rasterizer::PlaneCoefficients first_plane{};
            const int orders[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1},
                                      {2, 1, 0}, {1, 0, 2}, {0, 2, 1}};
            for (const auto &o : orders) {
                Target t;
                t.resize(w, h);
                PassCounters pc;
                const ClipVertex q[3] = {v[o[0]], v[o[1]], v[o[2]]};
                r.draw_depth(t, q, 1, pc);
                const Rasterizer::PlaneCoefficients pl = r.depth_plane(q, w, h);
                std::vector<float> d(t.depth.begin(), t.depth.end());
                if (first.empty()) {
                    first = d;
                    first_plane = pl;
                } else {
                    ASSERT_EQ(0, std::memcmp(first.data(), d.data(), d.size() * sizeof(float)))
                        << k->name << " trial " << trial;
                    ASSERT_EQ(first_plane.ok, pl.ok);
                    const double a[5] = {first_plane.x0, first_plane.y0, first_plane.z0,
                                         first_plane.a, first_plane.b};
                    const double b[5] = {pl.x0, pl.y0, pl.z0, pl.a, pl.b};
                    if (pl.ok) {
                        ASSERT_EQ(0, std::memcmp(a, b, sizeof a)) << "trial " << trial;
                    }
                }
            }
        }
    }
}

SV_TIERED_TEST(Raster, SimdKernelsMatchTheCBitForBit) {
    /* Random triangles of every shape (slivers, huge, cut by the near and
     * side planes, vertices at w = 0), drawn in all three passes over a
     * random depth buffer by each kernel: the buffers and the counters are
     * identical to the C kernel's. */
    const std::vector<const RowKernels *> ks = runnable_kernels();
    std::mt19937 rng(12345);
    std::uniform_real_distribution<double> u(-1, 1);
    const int w = 97, h = 61; /* odd sizes: every block alignment and tail */
    auto random_vertex = [&](int shape) -> ClipVertex {
        const double s = shape == 0 ? 0.05 : shape == 1 ? 1.0 : 4.0;
        const double wv = (rng() % 8 == 0) ? 0.0 : 0.3 + std::fabs(u(rng));
        return {u(rng) * s, u(rng) * s, u(rng) * 1.2, wv == 0 ? 0.0 : wv};
    };
    for (int trial = 0; trial < 300; trial++) {
        std::vector<std::array<ClipVertex, 3>> tris;
        for (int i = 0; i < 40; i++) {
            const int shape = (int)(rng() % 3);
            std::array<ClipVertex, 3> t = {random_vertex(shape), random_vertex(shape),
                                           random_vertex(shape)};
            if (rng() % 4 == 0) { /* a sliver */
                t[1] = {t[0].x + 1e-3, t[0].y + u(rng), t[0].z, t[0].w == 0 ? 1 : t[0].w};
            }
            tris.push_back(t);
        }
        std::vector<float> depth0((std::size_t)w * h);
        for (float &d : depth0) d = (float)(0.5 + 0.5 * u(rng));
        std::vector<Target> results;
        std::vector<PassCounters> counters;
        for (const RowKernels *k : ks) {
            const Rasterizer r(k);
            Target t;
            t.resize(w, h);
            std::copy(depth0.begin(), depth0.end(), t.depth.begin());
            PassCounters c;
            for (std::size_t i = 0; i < tris.size(); i++) {
                switch (i % 3) {
                case 0: r.draw_depth(t, tris[i].data(), (int32_t)i, c); break;
                case 1: r.draw_stencil(t, tris[i].data(), StencilMode::zpass, c); break;
                default: r.draw_stencil(t, tris[i].data(), StencilMode::zfail, c); break;
                }
            }
            results.push_back(std::move(t));
            counters.push_back(c);
        }
        for (std::size_t k = 1; k < ks.size(); k++) {
            ASSERT_EQ(0, std::memcmp(results[0].depth.data(), results[k].depth.data(),
                                     depth0.size() * 4))
                << ks[k]->name << " trial " << trial;
            ASSERT_TRUE(results[0].ids == results[k].ids) << ks[k]->name << " trial " << trial;
            ASSERT_TRUE(results[0].stencil == results[k].stencil)
                << ks[k]->name << " trial " << trial;
            ASSERT_EQ(counters[0].pixels_tested, counters[k].pixels_tested) << ks[k]->name;
            ASSERT_EQ(counters[0].pixels_written, counters[k].pixels_written) << ks[k]->name;
            ASSERT_EQ(counters[0].rows, counters[k].rows) << ks[k]->name;
        }
    }
}

TEST(Raster, CoveredSpansAreThePixelsTheWalksTest) {
    /* Rasterizer::covered_spans against the walks: random triangles
     * (slivers, corners on pixel centres and on pixel edges, cut by the
     * near and side planes), each piece walked in z-fail over a depth of 0
     * (its test fails everywhere, so the walk counts every centre it
     * covers) and its spans added with the same delta, in random bands:
     * the same stencil, and as many pixels as the walk tested. */
    std::mt19937 rng(2027);
    std::uniform_real_distribution<double> u(-1.3, 1.3);
    const int w = 67, h = 45;
    const Rasterizer r(row_kernels_best());
    auto on_grid = [&](double v, int side, double offset) {
        return (std::floor((v + 1) / 2 * side) + offset) / side * 2 - 1;
    };
    for (int trial = 0; trial < 400; trial++) {
        ClipVertex v[3];
        for (ClipVertex &q : v) {
            q = {u(rng), u(rng), u(rng) * 1.1, 1.0};
            const int snap = (int)(rng() % 4); /* 0: free; 1: centres; 2: edges; 3: mixed */
            if (snap == 1 || snap == 3) q.x = on_grid(q.x, w, 0.5);
            if (snap == 1 || snap == 2) q.y = on_grid(q.y, h, snap == 1 ? 0.5 : 0.0);
            if (snap == 2) q.x = on_grid(q.x, w, 0.0);
        }
        if (trial % 5 == 0) v[1] = {v[0].x + 2e-3, v[0].y + u(rng), v[0].z, 1.0}; /* a sliver */
        std::vector<SetupTriangle> pieces;
        PassCounters pc;
        r.setup(v, w, h, 0, pc, pieces);
        const RowBand band{(int)(rng() % 8), h - (int)(rng() % 8)};
        std::vector<float> depth((std::size_t)w * h + kFrameSlack / sizeof(float), 0.0f);
        std::vector<uint8_t> walked((std::size_t)w * h, 0), spanned((std::size_t)w * h, 0);
        RowCounts rc;
        uint64_t covered = 0;
        std::vector<Rasterizer::CoveredSpan> spans;
        for (const SetupTriangle &p : pieces) {
            r.walk_stencil(p, depth.data(), walked.data(), w, h, band, StencilMode::zfail, rc);
            spans.clear();
            Rasterizer::covered_spans(p, band, spans);
            const uint8_t delta = p.front ? 255 : 1; /* z-fail: back +1, front -1 */
            for (const Rasterizer::CoveredSpan &sp : spans) {
                ASSERT_GE(sp.y, band.row_begin);
                ASSERT_LT(sp.y, band.row_end);
                ASSERT_GE(sp.x_begin, 0);
                ASSERT_LE(sp.x_end, w);
                ASSERT_LT(sp.x_begin, sp.x_end);
                for (int x = sp.x_begin; x < sp.x_end; x++) {
                    uint8_t &s = spanned[(std::size_t)sp.y * w + (std::size_t)x];
                    s = (uint8_t)(s + delta);
                }
                covered += (uint64_t)(sp.x_end - sp.x_begin);
            }
        }
        ASSERT_TRUE(walked == spanned) << "trial " << trial;
        ASSERT_EQ(rc.tested, covered) << "trial " << trial;
    }
}

SV_TIERED_TEST(Raster, TriangleWalksMatchTheCInAnyBandAndClamp) {
    /* The triangle walks (row_kernels.h) of every version over random
     * set-up triangles (slivers among them), each walked in bands of 1 to
     * 9 rows as the passes' threads walk them, and clamped to a column
     * range as the hierarchical stencil clamps a piece to its tile: the
     * depth, ids, stencil and counts of the C walk over the whole frame,
     * and nothing written outside the clamp. */
    const std::vector<const RowKernels *> ks = runnable_kernels();
    const int w = 83, h = 47;
    std::mt19937 rng(4242);
    std::uniform_real_distribution<double> u(-1.3, 1.3);
    const Rasterizer setup_r(&kRowKernelsC);
    for (int trial = 0; trial < 200; trial++) {
        std::vector<SetupTriangle> pieces;
        PassCounters pc;
        for (int i = 0; i < 12; i++) {
            ClipVertex v[3] = {{u(rng), u(rng), u(rng) * 0.9, 1},
                               {u(rng), u(rng), u(rng) * 0.9, 1},
                               {u(rng), u(rng), u(rng) * 0.9, 1}};
            if (i % 3 == 0) v[1] = {v[0].x + 0.004, v[0].y + u(rng), v[0].z, 1}; /* a sliver */
            setup_r.setup(v, w, h, i, pc, pieces);
        }
        FrameBuffer<float> depth0((std::size_t)w * h);
        for (float &d : depth0) d = (float)(0.5 + 0.45 * u(rng) / 1.3);
        const int clamp_lo = (int)(rng() % 40), clamp_hi = clamp_lo + (int)(rng() % 50);
        const int mode = trial % 3; /* depth, z-pass, z-fail */
        auto run = [&](const RowKernels *k, bool banded, FrameBuffer<float> &depth,
                       FrameBuffer<int32_t> &ids, std::vector<uint8_t> &st, RowCounts &n) {
            depth = depth0;
            ids.assign((std::size_t)w * h, -1);
            st.assign((std::size_t)w * h, 7);
            std::mt19937 band_rng(trial);
            for (SetupTriangle p : pieces) {
                p.x_first = std::max(p.x_first, clamp_lo);
                p.x_last = std::min(p.x_last, clamp_hi);
                if (p.x_first > p.x_last) continue;
                const WalkBuffers b{depth.data(), ids.data(), st.data(), w, h};
                for (int y0 = 0; y0 < h;) {
                    const int y1 = banded ? std::min(h, y0 + 1 + (int)(band_rng() % 9)) : h;
                    const RowBand band{y0, y1};
                    if (mode == 0)
                        k->walk_depth(p, band, b, n);
                    else
                        (mode == 1 ? k->walk_zpass : k->walk_zfail)(p, band, b, p.front ? 1 : 255,
                                                                    n);
                    y0 = y1;
                }
            }
        };
        FrameBuffer<float> d_ref;
        FrameBuffer<int32_t> i_ref;
        std::vector<uint8_t> s_ref;
        RowCounts n_ref;
        run(&kRowKernelsC, false, d_ref, i_ref, s_ref, n_ref);
        for (int i = 0; i < w * h; i++) {
            const int x = i % w;
            if (x >= clamp_lo && x <= clamp_hi) continue;
            ASSERT_EQ(d_ref[(std::size_t)i], depth0[(std::size_t)i]) << "outside the clamp";
            ASSERT_EQ(s_ref[(std::size_t)i], 7) << "outside the clamp";
        }
        for (const RowKernels *k : ks) {
            FrameBuffer<float> d;
            FrameBuffer<int32_t> ids;
            std::vector<uint8_t> st;
            RowCounts n;
            run(k, true, d, ids, st, n);
            ASSERT_EQ(0, std::memcmp(d.data(), d_ref.data(), (std::size_t)w * h * 4))
                << k->name << " trial " << trial;
            ASSERT_TRUE(ids == i_ref) << k->name << " trial " << trial;
            ASSERT_TRUE(st == s_ref) << k->name << " trial " << trial;
            ASSERT_EQ(n.tested, n_ref.tested) << k->name << " trial " << trial;
            ASSERT_EQ(n.written, n_ref.written) << k->name << " trial " << trial;
            ASSERT_EQ(n.rows, n_ref.rows) << k->name << " trial " << trial;
        }
    }
}

SV_TIERED_TEST(Raster, WalksWriteNothingOutsideTheSpan) {
    /* A triangle covering all of a one-row target, its pixel bounds
     * clamped to every [x0, x1) inside a row of 40 pixels, over buffers
     * whose other pixels hold a pattern (the stencil without slack, as a
     * frame's per-light stencils): every walk changes only pixels of
     * [x0, x1), and changes each of them. */
    for (const RowKernels *k : runnable_kernels()) {
        for (int x0 = 0; x0 < 40; x0++) {
            for (int x1 = x0 + 1; x1 <= 40; x1++) {
                FrameBuffer<float> depth(120, 0.25f);
                FrameBuffer<int32_t> ids(120, -5);
                std::vector<uint8_t> st(120, 77);
                for (int mode = 0; mode < 3; mode++) {
                    SetupTriangle t{};
                    t.e_origin[0] = t.e_origin[1] = t.e_origin[2] = 0; /* everything covered */
                    t.z0 = mode == 0 ? 0.1 : 0.3; /* depth pass: nearer; stencil: behind */
                    t.x_first = 40 + x0;
                    t.x_last = 40 + x1 - 1;
                    t.y_first = t.y_last = 0;
                    t.id = 9;
                    const WalkBuffers b{depth.data(), ids.data(), st.data(), 120, 1};
                    RowCounts n;
                    if (mode == 0)
                        k->walk_depth(t, {0, 1}, b, n);
                    else
                        (mode == 1 ? k->walk_zpass : k->walk_zfail)(t, {0, 1}, b, 1, n);
                    ASSERT_EQ(n.tested, (uint64_t)(x1 - x0)) << k->name;
                }
                for (int i = 0; i < 120; i++) {
                    const bool in = i >= 40 + x0 && i < 40 + x1;
                    ASSERT_EQ(depth[(std::size_t)i], in ? 0.1f : 0.25f)
                        << k->name << " " << x0 << ".." << x1 << " at " << i;
                    ASSERT_EQ(ids[(std::size_t)i], in ? 9 : -5) << k->name;
                    /* z-pass: 0.3 is behind the new depth 0.1, no change;
                     * z-fail: +1 there. */
                    ASSERT_EQ(st[(std::size_t)i], in ? 78 : 77)
                        << k->name << " " << x0 << ".." << x1 << " at " << i;
                }
            }
        }
    }
}

} // namespace

namespace {

TEST(Raster, SharedCornersSetUpAsEachTriangleAlone) {
    /* setup_shared (the depth pass: each vertex snapped once) gives the
     * pieces and counts setup gives, bit for bit: triangles inside the
     * view volume, across its planes, wholly outside, behind the eye and
     * degenerate, among 600 vertices in and around a 97x61 frame. */
    const int w = 97, h = 61;
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> xy(-1.6, 1.6), z(-1.3, 1.0), wd(-0.2, 2.0);
    std::uniform_real_distribution<double> in(-0.95, 0.95), win(0.3, 2.0);
    std::vector<ClipVertex> verts(600);
    for (std::size_t k = 0; k < verts.size(); k++) {
        /* Half inside the view volume, half anywhere around it. */
        const double ww = k < 300 ? win(rng) : wd(rng), a = std::fabs(ww);
        verts[k] = k < 300 ? ClipVertex{in(rng)*a, in(rng)*a, in(rng)*a, ww}
                           : ClipVertex{xy(rng) * a, xy(rng) * a, z(rng) * a, ww};
    }
    verts[7] = verts[8]; /* a degenerate pair */
    std::vector<WindowVertex> window;
    for (const ClipVertex &v : verts) window.push_back(window_vertex(v, w, h));
    const Rasterizer r(row_kernels_best());
    std::uniform_int_distribution<int> pick(0, (int)verts.size() - 1);
    int inside = 0;
    PassCounters ca, cb;
    for (int t = 0; t < 3000; t++) {
        int i[3] = {pick(rng), pick(rng), pick(rng)};
        if (t % 3 == 0) i[0] %= 300, i[1] %= 300, i[2] %= 300; /* all three inside */
        if (t % 50 == 0) i[1] = 7, i[2] = 8;
        const ClipVertex v[3] = {verts[(std::size_t)i[0]], verts[(std::size_t)i[1]],
                                 verts[(std::size_t)i[2]]};
        const WindowVertex wv[3] = {window[(std::size_t)i[0]], window[(std::size_t)i[1]],
                                    window[(std::size_t)i[2]]};
        inside += (wv[0].outside | wv[1].outside | wv[2].outside) == 0;
        std::vector<SetupTriangle> a, b;
        r.setup(v, w, h, t, ca, a);
        r.setup_shared(v, wv, w, h, t, cb, b);
        ASSERT_EQ(a.size(), b.size()) << "triangle " << t;
        for (std::size_t k = 0; k < a.size(); k++) {
            const SetupTriangle &p = a[k], &q = b[k];
            bool same = p.id == q.id && p.front == q.front && p.x_first == q.x_first &&
                        p.x_last == q.x_last && p.y_first == q.y_first && p.y_last == q.y_last;
            for (int e = 0; e < 3; e++) {
                same = same && p.e_origin[e] == q.e_origin[e] && p.step_x[e] == q.step_x[e] &&
                       p.step_y[e] == q.step_y[e];
            }
            const double pd[5] = {p.x0, p.y0, p.z0, p.a, p.b}, qd[5] = {q.x0, q.y0, q.z0, q.a, q.b};
            same = same && std::memcmp(pd, qd, sizeof pd) == 0; /* the depth plane's bits */
            ASSERT_TRUE(same) << "triangle " << t << " piece " << k;
        }
    }
    EXPECT_GT(inside, 900);
    EXPECT_EQ(ca.triangles, cb.triangles);
    EXPECT_EQ(ca.triangles_clipped, cb.triangles_clipped);
    EXPECT_EQ(ca.triangles_outside, cb.triangles_outside);
    EXPECT_EQ(ca.triangles_degenerate, cb.triangles_degenerate);
    EXPECT_GT(ca.triangles_clipped, 100u);
    EXPECT_GT(ca.triangles_outside, 10u);
    EXPECT_GT(ca.triangles_degenerate, 10u);
}

} // namespace
