// The Mesa judge (src/judge/mesa_stencil.h) checked against what the math
// says: read-back orientation, INCR_WRAP/DECR_WRAP counts, z-pass against
// z-fail around a receiver, the section 3 extrusion of w = 0 vertices with
// the infinite far plane, bad jobs rejected before GL sees them, and the
// pixel-level rules of llvmpipe (pixel centres, the tie rule for centres on
// an edge, sub-pixel precision) that the project's rasteriser must match.
//
// Where no GL context can be made (no OSMesa at build time, or creation
// fails) every test prints a NOTE and skips; nowhere else.
//
// Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "mesa_stencil.h"

namespace {

// Vec4: shadowvol.h's C struct (global namespace).
using sv::gl::MesaContext;
using sv::gl::MesaStencilJob;
using sv::gl::MesaStencilResult;

std::unique_ptr<MesaContext> context(int w, int h) {
    std::string why;
    auto ctx = MesaContext::create(w, h, 1, &why);
    if (!ctx)
        std::printf("NOTE: no Mesa GL context (%s); the Mesa judge is not tested here\n",
                    why.c_str());
    return ctx;
}

#define SV_MESA_CONTEXT(var, w, h)                                                                 \
    auto var = context(w, h);                                                                      \
    if (!var) GTEST_SKIP() << "no Mesa GL context"

// A job's geometry, owned here; job() points the MesaStencilJob at it.
struct Scene {
    int width, height;
    std::array<double, 16> vp{};
    Vec4 light{0, 0, 0, 1};
    struct Vol {
        std::vector<Vec4> v;
        std::vector<int> i;
        bool zfail;
    };
    struct Rec {
        std::vector<float> p;
        std::vector<int> i;
    };
    std::vector<Vol> volumes;
    std::vector<Rec> receivers;

    Scene(int w, int h) : width(w), height(h) {
        vp[0] = vp[5] = vp[10] = vp[15] = 1; // identity: positions are clip coordinates
    }
    // Triangles of one volume: each Vec4 as given (w 1 or 0).
    void volume(std::vector<Vec4> verts, bool zfail = false) {
        Vol vol{std::move(verts), {}, zfail};
        for (int k = 0; k < static_cast<int>(vol.v.size()); ++k) vol.i.push_back(k);
        volumes.push_back(std::move(vol));
    }
    void receiver(std::vector<float> xyz) {
        Rec r{std::move(xyz), {}};
        for (int k = 0; k < static_cast<int>(r.p.size() / 3); ++k) r.i.push_back(k);
        receivers.push_back(std::move(r));
    }
    MesaStencilJob job() const {
        MesaStencilJob j;
        j.width = width;
        j.height = height;
        for (int k = 0; k < 16; ++k) j.view_proj[k] = vp[k];
        j.light = light;
        for (const Rec &r : receivers)
            j.receivers.push_back({r.p.data(), static_cast<int>(r.p.size() / 3), r.i.data(),
                                   static_cast<int>(r.i.size())});
        for (const Vol &v : volumes)
            j.volumes.push_back({v.v.data(), static_cast<int>(v.v.size()), v.i.data(),
                                 static_cast<int>(v.i.size()), v.zfail, nullptr});
        return j;
    }
};

// Two counter-clockwise triangles covering [x0, x1] x [y0, y1] (in the
// positions' own coordinates) at Z with W.
void quad(std::vector<Vec4> &out, float x0, float y0, float x1, float y1, float z = 0,
          float w = 1) {
    out.insert(out.end(), {{x0, y0, z, w},
                           {x1, y0, z, w},
                           {x1, y1, z, w},
                           {x0, y0, z, w},
                           {x1, y1, z, w},
                           {x0, y1, z, w}});
}

void reverse_winding(std::vector<Vec4> &tris) {
    for (size_t k = 0; k + 2 < tris.size(); k += 3) std::swap(tris[k + 1], tris[k + 2]);
}

// The Everitt-Kilgard infinite projection with epsilon (camera at the
// origin looking down -z; the view is the identity).
constexpr double kEps = 1.0 / (1 << 20);
std::array<double, 16> infinite_perspective(double fovy_deg, double aspect, double n) {
    const double f = 1.0 / std::tan(fovy_deg * M_PI / 360.0);
    std::array<double, 16> p{};
    p[0] = f / aspect;      // (0,0)
    p[5] = f;               // (1,1)
    p[10] = kEps - 1;       // (2,2)
    p[14] = n * (kEps - 2); // (2,3)
    p[11] = -1;             // (3,2)
    return p;
}

uint8_t at(const MesaStencilResult &r, int w, int row, int col) {
    return r.stencil[static_cast<size_t>(row) * static_cast<size_t>(w) + static_cast<size_t>(col)];
}

TEST(MesaStencil, DescribesLlvmpipeCore45) {
    SV_MESA_CONTEXT(ctx, 16, 16);
    const std::string d = ctx->describe();
    std::printf("Mesa judge: %s; LP_NUM_THREADS=%d; stencil read back as %s\n", d.c_str(),
                ctx->lp_num_threads(),
                ctx->readback() == MesaContext::Readback::stencil_index
                    ? "GL_STENCIL_INDEX"
                    : "GL_DEPTH_STENCIL/GL_FLOAT_32_UNSIGNED_INT_24_8_REV");
    EXPECT_NE(d.find("llvmpipe"), std::string::npos) << d;
    EXPECT_NE(d.find("4.5"), std::string::npos) << d;
    EXPECT_NE(d.find("Core"), std::string::npos) << d;
    EXPECT_EQ(ctx->lp_num_threads(), 1);
    EXPECT_TRUE(sv::gl::mesa_available_at_build());
}

// Row 0 of the image is the top: a triangle in the top-left quarter of the
// clip square (x < 0, y > 0) shows at small rows and small columns only.
// And a receiver over the top half shows its depth in the top rows.
TEST(MesaStencil, ReadBackRowZeroIsTop) {
    const int W = 64, H = 48;
    SV_MESA_CONTEXT(ctx, W, H);
    Scene s(W, H);
    s.volume({{-1, 1, 0, 1}, {-1, 0, 0, 1}, {0, 1, 0, 1}}); // counter-clockwise: +1
    s.receiver({-1, 0, 0.5f, 1, 0, 0.5f, 1, 1, 0.5f, -1, 0, 0.5f, 1, 1, 0.5f, -1, 1, 0.5f});
    MesaStencilResult r = ctx->run(s.job());
    ASSERT_EQ(r.stencil.size(), static_cast<size_t>(W * H));
    ASSERT_EQ(r.depth.size(), static_cast<size_t>(W * H));
    EXPECT_EQ(at(r, W, 1, 1), 1);                 // top-left corner: inside
    EXPECT_EQ(at(r, W, 1, W / 2 - 4), 1);         // along the top, near the middle
    EXPECT_EQ(at(r, W, H / 2 - 4, 1), 1);         // down the left side, near the middle
    EXPECT_EQ(at(r, W, H - 2, 1), 0);             // bottom-left
    EXPECT_EQ(at(r, W, 1, W - 2), 0);             // top-right
    EXPECT_EQ(at(r, W, H - 2, W - 2), 0);         // bottom-right
    EXPECT_EQ(at(r, W, H / 2 - 2, W / 2 - 2), 0); // beyond the hypotenuse
    int ones = 0;
    for (uint8_t v : r.stencil) ones += v == 1;
    // Half of a quarter: W*H/8 pixel centres, give or take the diagonal.
    EXPECT_NEAR(ones, W * H / 8, W / 2);
    // Receiver at clip z 0.5: window depth 0.75 in the top half, the
    // cleared 1 in the bottom half.
    EXPECT_FLOAT_EQ(r.depth[static_cast<size_t>(2 * W + 5)], 0.75f);
    EXPECT_FLOAT_EQ(r.depth[static_cast<size_t>((H - 3) * W + 5)], 1.0f);
    EXPECT_GE(r.depth_pass_seconds, 0.0);
    EXPECT_GE(r.stencil_pass_seconds, 0.0);
}

// N full-screen front faces give N mod 256 (INCR_WRAP, not INCR's clamp at
// 255); a back face alone gives 255 (DECR_WRAP from 0, not DECR's 0).
TEST(MesaStencil, CountsWrapAround) {
    const int W = 32, H = 16;
    SV_MESA_CONTEXT(ctx, W, H);
    for (int n : {1, 2, 255, 256, 257, 511}) {
        Scene s(W, H);
        std::vector<Vec4> tris;
        for (int k = 0; k < n; ++k) quad(tris, -1, -1, 1, 1);
        s.volume(tris);
        MesaStencilResult r = ctx->run(s.job());
        for (size_t p = 0; p < r.stencil.size(); ++p)
            ASSERT_EQ(r.stencil[p], n % 256) << n << " quads, pixel " << p;
    }
    {
        Scene s(W, H);
        std::vector<Vec4> tris;
        quad(tris, -1, -1, 1, 1);
        reverse_winding(tris);
        s.volume(tris);
        MesaStencilResult r = ctx->run(s.job());
        for (size_t p = 0; p < r.stencil.size(); ++p)
            ASSERT_EQ(r.stencil[p], 255) << "back face, pixel " << p;
        // Two back faces: 254; and one more front face on top: back to 255.
        s.volume(tris);
        r = ctx->run(s.job());
        EXPECT_EQ(r.stencil[0], 254);
        std::vector<Vec4> front;
        quad(front, -1, -1, 1, 1);
        s.volume(front);
        r = ctx->run(s.job());
        EXPECT_EQ(r.stencil[0], 255);
    }
}

// Against a receiver square at z = -5 over the left half of the view: a
// volume quad in front of it (z = -3) counts in z-pass everywhere it
// covers and never in z-fail; one behind it (z = -8) counts in z-pass only
// where there is no receiver, and in z-fail only over the receiver, front
// faces down (DECR_WRAP: 255) and back faces up (1).
TEST(MesaStencil, ZPassAndZFailAroundAReceiver) {
    const int W = 64, H = 64;
    SV_MESA_CONTEXT(ctx, W, H);
    const double n = 1.0;
    // 90 degrees, aspect 1: at depth z the view spans x, y in [z, -z].
    auto vp = infinite_perspective(90, 1, n);
    // Receiver: x in [-6, 0], y in [-6, 6] at z = -5: the left half.
    std::vector<float> rec = {-6, -6, -5, 0, -6, -5, 0, 6, -5, -6, -6, -5, 0, 6, -5, -6, 6, -5};
    struct Case {
        float z;
        bool zfail, back;
        int on_receiver, off_receiver;
    };
    const Case cases[] = {
        {-3, false, false, 1, 1},  {-3, true, false, 0, 0},  {-3, false, true, 255, 255},
        {-3, true, true, 0, 0},    {-8, false, false, 0, 1}, {-8, true, false, 255, 0},
        {-8, false, true, 0, 255}, {-8, true, true, 1, 0},
    };
    for (const Case &c : cases) {
        Scene s(W, H);
        std::copy(vp.begin(), vp.end(), s.vp.begin());
        s.receiver(rec);
        // The volume quad spans the middle half of the view at its depth.
        const float h = -c.z / 2;
        std::vector<Vec4> tris;
        quad(tris, -h, -h, h, h, c.z);
        if (c.back) reverse_winding(tris);
        s.volume(tris, c.zfail);
        MesaStencilResult r = ctx->run(s.job());
        const char *what = c.zfail ? "z-fail" : "z-pass";
        // Row 32 is the view's middle; columns 20 (receiver, volume) and
        // 44 (volume only); column 4 and row 4 are outside the volume.
        EXPECT_EQ(at(r, W, 32, 20), c.on_receiver) << what << " z " << c.z << " back " << c.back;
        EXPECT_EQ(at(r, W, 32, 44), c.off_receiver) << what << " z " << c.z << " back " << c.back;
        EXPECT_EQ(at(r, W, 32, 4), 0) << what;
        EXPECT_EQ(at(r, W, 4, 20), 0) << what;
        // The receiver's depth: ndc z = ((eps-1)(-5) + n(eps-2)) / 5.
        const double ndc = ((kEps - 1) * -5.0 + n * (kEps - 2)) / 5.0;
        EXPECT_NEAR(r.depth[32 * W + 20], (ndc + 1) / 2, 1e-6);
        EXPECT_EQ(r.depth[32 * W + 44], 1.0f);
    }
}

// Where the math says a triangle lands: its pixel centres, by
// point-in-triangle in double from the projected vertices, must be the
// stencil's pixels, except within a pixel of an edge (where rounding and
// the tie rule decide; the FillRule tests pin those down).
struct Expect {
    double x[3], y[3]; // window coordinates, y up
};

Expect project(const std::array<double, 16> &m, const Vec4 *clip_in, int W, int H) {
    Expect e{};
    for (int k = 0; k < 3; ++k) {
        const double v[4] = {clip_in[k].x, clip_in[k].y, clip_in[k].z, clip_in[k].w};
        double c[4];
        for (int r = 0; r < 4; ++r)
            c[r] = m[r] * v[0] + m[4 + r] * v[1] + m[8 + r] * v[2] + m[12 + r] * v[3];
        e.x[k] = (c[0] / c[3] + 1) * W / 2;
        e.y[k] = (c[1] / c[3] + 1) * H / 2;
    }
    return e;
}

// Signed distance (in pixels) of (px, py) inside triangle E: > 0 inside.
double inside_margin(const Expect &e, double px, double py) {
    double area = (e.x[1] - e.x[0]) * (e.y[2] - e.y[0]) - (e.y[1] - e.y[0]) * (e.x[2] - e.x[0]);
    double s = area > 0 ? 1 : -1, m = 1e300;
    for (int k = 0; k < 3; ++k) {
        int j = (k + 1) % 3;
        double ex = e.x[j] - e.x[k], ey = e.y[j] - e.y[k];
        double d = s * (ex * (py - e.y[k]) - ey * (px - e.x[k])) / std::hypot(ex, ey);
        m = std::min(m, d);
    }
    return m;
}

// Checks the one-triangle z-pass volume's stencil against the projection
// of its vertices DIR (what the vertex program should have made of them):
// 1 inside where the projection is counter-clockwise (front), 255 where it
// is clockwise (back), so the winding through the w = 0 vertex is checked
// too.
void expect_lands(const MesaStencilResult &r, int W, int H, const std::array<double, 16> &vp,
                  const Vec4 *dir, const char *what) {
    Expect e = project(vp, dir, W, H);
    const double area = (e.x[1] - e.x[0]) * (e.y[2] - e.y[0]) -
                        (e.y[1] - e.y[0]) * (e.x[2] - e.x[0]);
    const int value = area > 0 ? 1 : 255;
    int inside = 0, wrong = 0;
    for (int row = 0; row < H; ++row)
        for (int col = 0; col < W; ++col) {
            double m = inside_margin(e, col + 0.5, (H - 1 - row) + 0.5);
            if (std::fabs(m) < 1.0) continue;
            int want = m > 0 ? value : 0;
            inside += m > 0;
            if (at(r, W, row, col) != want && wrong++ < 5)
                ADD_FAILURE() << what << ": pixel row " << row << " col " << col << " is "
                              << int(at(r, W, row, col)) << ", the math says " << want;
        }
    EXPECT_EQ(wrong, 0) << what;
    EXPECT_GT(inside, 100) << what << ": the expected triangle is too small to test";
}

// The section 3 vertex program: a w = 0 vertex V is drawn at infinity in
// the direction V - L away from a point light L, and in the direction -L
// for a directional light (L pointing towards it); with the infinite far
// plane it lands at depth 1 - eps/2 and is not clipped.
TEST(MesaStencil, ExtrudesWZeroVerticesAwayFromTheLight) {
    const int W = 96, H = 64;
    SV_MESA_CONTEXT(ctx, W, H);
    const auto vp = infinite_perspective(60, double(W) / H, 0.5);

    { // Point light: all three vertices at infinity.
        Scene s(W, H);
        std::copy(vp.begin(), vp.end(), s.vp.begin());
        s.light = {2, 1, 0.5f, 1};
        const Vec4 d[3] = {{-1, -1, -4, 0}, {1.5f, -1, -4, 0}, {0, 1.2f, -4, 0}};
        std::vector<Vec4> tri;
        for (const Vec4 &k : d) // V = L + direction; w = 0
            tri.push_back({s.light.x + k.x, s.light.y + k.y, s.light.z + k.z, 0});
        s.volume(tri);
        MesaStencilResult r = ctx->run(s.job());
        expect_lands(r, W, H, vp, d, "point light, three w = 0 vertices");
        // Depth at infinity is 1 - eps/2 < 1: the z-pass counted there, and
        // the same triangle in z-fail counts nothing (it is never behind
        // the cleared depth).
        s.volumes[0].zfail = true;
        r = ctx->run(s.job());
        for (uint8_t v : r.stencil) ASSERT_EQ(v, 0);
    }
    { // Point light: an extruded side, two w = 1 vertices and one w = 0.
        Scene s(W, H);
        std::copy(vp.begin(), vp.end(), s.vp.begin());
        s.light = {-1, 2, 1, 1};
        const Vec4 a{-1.5f, -1, -3, 1}, b{1, -0.5f, -3.5f, 1}, far{0.5f, 1, -2, 0};
        s.volume({a, b, far});
        const Vec4 d[3] = {a, b, {far.x - s.light.x, far.y - s.light.y, far.z - s.light.z, 0}};
        MesaStencilResult r = ctx->run(s.job());
        expect_lands(r, W, H, vp, d, "point light, an extruded side");
    }
    { // Directional light: the w = 0 vertex goes to -L, wherever it starts.
        Scene s(W, H);
        std::copy(vp.begin(), vp.end(), s.vp.begin());
        s.light = {-0.3f, -0.2f, 1, 0};
        const Vec4 a{-1.5f, -1, -3, 1}, b{1, -0.5f, -3.5f, 1}, far{40, -7, 3, 0};
        s.volume({a, b, far});
        const Vec4 d[3] = {a, b, {-s.light.x, -s.light.y, -s.light.z, 0}};
        MesaStencilResult r = ctx->run(s.job());
        expect_lands(r, W, H, vp, d, "directional light, an extruded side");
    }
}

// A job that does not fit is refused before GL draws anything, with a
// message that says what is wrong, and the context still works after.
TEST(MesaStencil, BadJobsThrow) {
    const int W = 16, H = 16;
    SV_MESA_CONTEXT(ctx, W, H);
    Scene s(W, H);
    std::vector<Vec4> tris;
    quad(tris, -1, -1, 1, 1);
    s.volume(tris);
    s.receiver({-1, -1, 0, 1, -1, 0, 1, 1, 0});
    auto expect_throw = [&](MesaStencilJob j, const char *needle) {
        try {
            ctx->run(j);
            ADD_FAILURE() << "no exception for " << needle;
        } catch (const std::runtime_error &e) {
            EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
        }
    };
    MesaStencilJob j = s.job();
    j.width = 17;
    expect_throw(j, "differs from the context");
    j = s.job();
    j.volumes[0].indices = nullptr;
    expect_throw(j, "indices is null");
    j = s.job();
    j.volumes[0].shadow_vertices = nullptr;
    expect_throw(j, "vertices are null");
    j = s.job();
    j.receivers[0].positions = nullptr;
    expect_throw(j, "vertices are null");
    j = s.job();
    j.volumes[0].num_shadow_vertices = 5; // index 5 is now one past the end
    expect_throw(j, "outside the 5 vertices");
    j = s.job();
    j.volumes[0].num_indices = 5;
    expect_throw(j, "not a multiple of 3");
    j = s.job();
    j.volumes[0].num_indices = -3;
    expect_throw(j, "negative");
    j = s.job();
    j.receivers[0].num_vertices = -1;
    expect_throw(j, "negative");
    std::vector<int> neg = {0, -1, 2};
    j = s.job();
    j.receivers[0].indices = neg.data();
    expect_throw(j, "= -1 is outside");
    j = s.job();
    j.view_proj[3] = NAN;
    expect_throw(j, "non-finite");
    j = s.job();
    j.light.w = INFINITY;
    expect_throw(j, "non-finite");
    // And the context is unharmed.
    MesaStencilResult r = ctx->run(s.job());
    EXPECT_EQ(r.stencil[0], 1);
    // Counts of zero with null pointers are an empty draw, not an error.
    MesaStencilJob empty;
    empty.width = W;
    empty.height = H;
    empty.volumes.push_back({});
    empty.receivers.push_back({});
    r = ctx->run(empty);
    EXPECT_EQ(r.stencil[0], 0);
    EXPECT_EQ(r.depth[0], 1.0f);
}

TEST(MesaStencil, CreateRefusesBadSizes) {
    std::string why;
    if (!sv::gl::mesa_available_at_build()) {
        std::printf("NOTE: built without OSMesa\n");
        EXPECT_EQ(MesaContext::create(16, 16, 1, &why), nullptr);
        EXPECT_NE(why.find("libosmesa6-dev"), std::string::npos) << why;
        GTEST_SKIP() << "built without OSMesa";
    }
    EXPECT_EQ(MesaContext::create(0, 16, 1, &why), nullptr);
    EXPECT_NE(why.find("not positive"), std::string::npos) << why;
    EXPECT_EQ(MesaContext::create(16, -1, 1, &why), nullptr);
    EXPECT_EQ(MesaContext::create(1 << 20, 16, 1, &why), nullptr);
    EXPECT_NE(why.find("exceeds"), std::string::npos) << why;
}

// Both read-back paths give the same stencil and depth, on an image with
// many different values.
TEST(MesaStencil, ReadBackPathsAgree) {
    const int W = 40, H = 24;
    SV_MESA_CONTEXT(ctx, W, H);
    Scene s(W, H);
    std::vector<Vec4> tris;
    for (int k = 0; k < 300; ++k) { // overlapping strips: counts 0..255 and wrapped
        float x0 = -1 + 2.0f * float(k % 37) / 40, y0 = -1 + 2.0f * float(k % 11) / 24;
        quad(tris, x0, y0, x0 + 0.5f, y0 + 0.9f);
    }
    s.volume(tris);
    s.receiver({-1, -1, -0.5f, 1, -1, 0.25f, 0, 1, 0.75f});
    const MesaContext::Readback chosen = ctx->readback();
    ctx->set_readback(MesaContext::Readback::stencil_index);
    MesaStencilResult a = ctx->run(s.job());
    ctx->set_readback(MesaContext::Readback::depth_stencil_packed);
    MesaStencilResult b = ctx->run(s.job());
    ctx->set_readback(chosen);
    EXPECT_EQ(a.stencil, b.stencil);
    EXPECT_EQ(a.depth, b.depth);
    int distinct = 0;
    std::vector<bool> seen(256);
    for (uint8_t v : a.stencil)
        if (!seen[v]) {
            seen[v] = true;
            ++distinct;
        }
    EXPECT_GT(distinct, 5);
}

// ---- The pixel rules (fill convention) of llvmpipe -------------------------
//
// Found by the experiments below on Mesa 22.3.6 (llvmpipe, LLVM 15), in GL
// WINDOW coordinates (x right, y UP, window row 0 at the bottom), into an
// FBO with the default lower-left origin and half-pixel centres:
//   * The centre of pixel (i, j) is (i + 0.5, j + 0.5).
//   * A centre exactly on an edge is covered when the triangle's interior
//     lies on the +x side of that edge (a "left" edge, any slope), or, for
//     an exactly horizontal edge, when the interior lies on the +y side
//     (the triangle's BOTTOM edge in GL's y-up window). Right edges and
//     horizontal top edges (interior at -y) exclude their centres. With a
//     counter-clockwise (y up) triangle and an edge A -> B, d = B - A: the
//     edge includes its centres iff d.y < 0, or d.y == 0 and d.x > 0. Same
//     coverage for either winding.
//     In the project's image coordinates (row 0 at the TOP, y down) that
//     is a "bottom-left" rule, not Direct3D's top-left one: left edges
//     included, and of horizontal edges the one whose triangle lies at
//     SMALLER row numbers (above it in the picture) is included.
//   * Vertices are snapped to 1/256 pixel (8 sub-pixel bits) by rounding
//     to nearest; a position exactly halfway (1/512 from a centre's grid
//     point) goes to the centre's side, on both sides (as round-to-nearest-
//     even does: a centre is an even multiple of 1/256).
// Every comparison below is exact: the sizes are powers of two and every
// position a multiple of 1/256 (or 1/65536 for the sweeps), so window
// coordinates are computed without rounding. (A 1280-wide window is not:
// 2/1280 is not a binary fraction, so a renderer must do GL's float steps,
// clip = VP * p, x / w, x * W/2 + W/2, to land on the same 1/256 grid
// point at ties.)

// A job in window coordinates: VP maps (x, y) in [0, W] x [0, H] to clip
// coordinates exactly when W and H are powers of two.
struct Window {
    int W, H;
    struct Pt {
        double x, y;
    };
    using Tri = std::array<Pt, 3>;
    // The stencil in GL window orientation: [y * W + x], y up.
    std::vector<uint8_t> draw(MesaContext &ctx, const std::vector<Tri> &tris) const {
        std::vector<Vec4> v;
        for (const Tri &t : tris)
            for (const Pt &p : t)
                v.push_back({static_cast<float>(p.x), static_cast<float>(p.y), 0, 1});
        Scene s(W, H);
        s.vp = {};
        s.vp[0] = 2.0 / W;
        s.vp[5] = 2.0 / H;
        s.vp[12] = -1;
        s.vp[13] = -1;
        s.vp[15] = 1;
        s.volume(v);
        MesaStencilResult r = ctx.run(s.job());
        std::vector<uint8_t> g(static_cast<size_t>(W) * static_cast<size_t>(H));
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) g[static_cast<size_t>(y * W + x)] = at(r, W, H - 1 - y, x);
        return g;
    }
};

Window::Tri reversed(Window::Tri t) {
    std::swap(t[1], t[2]);
    return t;
}

// Each edge kind through a column or row of pixel centres, both windings:
// the centres on the edge are covered exactly for left edges and
// horizontal bottom edges (GL y up); the centres one pixel outside never,
// one pixel inside always (so the centres are at the half-integers).
TEST(FillRule, TieRuleOnEdgesThroughPixelCentres) {
    const Window w{64, 64};
    SV_MESA_CONTEXT(ctx, w.W, w.H);
    struct Case {
        const char *what;
        Window::Tri tri;
        int cx, cy;         // a pixel whose centre lies on the edge
        int out_dx, out_dy; // towards the outside of the triangle
        bool included;
    };
    const Case cases[] = {
        {"vertical x = 10.5, interior +x (left edge)",
         {{{10.5, 1}, {50, 30}, {10.5, 60}}},
         10,
         30,
         -1,
         0,
         true},
        {"vertical x = 40.5, interior -x (right edge)",
         {{{40.5, 1}, {40.5, 60}, {2, 30}}},
         40,
         30,
         1,
         0,
         false},
        {"horizontal y = 7.5, interior +y (bottom edge, y up)",
         {{{1, 7.5}, {60, 7.5}, {30, 50}}},
         30,
         7,
         0,
         -1,
         true},
        {"horizontal y = 40.5, interior -y (top edge, y up)",
         {{{1, 40.5}, {30, 2}, {60, 40.5}}},
         30,
         40,
         0,
         1,
         false},
        {"diagonal y = x, interior +x -y (left edge)",
         {{{10.5, 10.5}, {50.5, 10.5}, {50.5, 50.5}}},
         30,
         30,
         -1,
         1,
         true},
        {"diagonal y = x, interior -x +y (right edge)",
         {{{10.5, 10.5}, {50.5, 50.5}, {10.5, 50.5}}},
         30,
         30,
         1,
         -1,
         false},
        {"diagonal y = -x, interior +x +y (left edge)",
         {{{10.5, 50.5}, {50.5, 10.5}, {50.5, 50.5}}},
         30,
         30,
         -1,
         -1,
         true},
        {"diagonal y = -x, interior -x -y (right edge)",
         {{{10.5, 50.5}, {10.5, 10.5}, {50.5, 10.5}}},
         30,
         30,
         1,
         1,
         false},
    };
    for (const Case &c : cases)
        for (bool cw : {false, true}) {
            const std::vector<uint8_t> g = w.draw(*ctx, {cw ? reversed(c.tri) : c.tri});
            const int value = cw ? 255 : 1; // a clockwise triangle is a back face
            auto px = [&](int x, int y) { return g[static_cast<size_t>(y * w.W + x)]; };
            EXPECT_EQ(px(c.cx, c.cy), c.included ? value : 0)
                << c.what << (cw ? " (clockwise)" : " (counter-clockwise)");
            EXPECT_EQ(px(c.cx + c.out_dx, c.cy + c.out_dy), 0) << c.what;
            EXPECT_EQ(px(c.cx - c.out_dx, c.cy - c.out_dy), value) << c.what;
        }
}

// An edge moved off a column (or row) of centres by k/65536 pixel, for
// k = 0..255, one band of 4 rows (columns) per k: the centre's coverage
// changes exactly between k = 128 (1/512: snapped back onto the centre)
// and k = 129 (snapped to the next 1/256), and only where moving the edge
// changes the tie's outcome. That is 8 sub-pixel bits, round to nearest,
// with the tie at exactly 1/512 going to the centre.
TEST(FillRule, SubPixelPrecisionIsOneIn256RoundToNearest) {
    for (bool along_y : {false, true}) {
        // Bands stacked along the other axis: 256 bands of 4 pixels.
        const Window w{along_y ? 1024 : 64, along_y ? 64 : 1024};
        SV_MESA_CONTEXT(ctx, w.W, w.H);
        for (bool left : {true, false}) // left (bottom) edge, or right (top)
            for (int sign : {+1, -1}) {
                std::vector<Window::Tri> tris;
                const double base = left ? 10.5 : 40.5;
                for (int k = 0; k < 256; ++k) {
                    const double e = base + sign * k / 65536.0, b0 = 4 * k + 0.25,
                                 b1 = 4 * k + 3.75;
                    Window::Tri t = left ? Window::Tri{{{e, b0}, {60, b0}, {e, b1}}}
                                         : Window::Tri{{{e, b0}, {e, b1}, {2, b0}}};
                    if (along_y) // transposed: left -> bottom, right -> top edges
                        for (Window::Pt &p : t) std::swap(p.x, p.y);
                    tris.push_back(t);
                }
                const std::vector<uint8_t> g = w.draw(*ctx, tris);
                for (int k = 0; k < 256; ++k) {
                    int x = left ? 10 : 40, y = 4 * k + 1;
                    if (along_y) std::swap(x, y);
                    const bool covered = g[static_cast<size_t>(y * w.W + x)] != 0;
                    // Snapped onto the centre (k <= 128): the tie rule.
                    // Beyond it: moved right/up, a left (bottom) edge loses
                    // the centre and a right (top) one gains it; moved
                    // left/down, nothing changes.
                    bool expect = left;
                    if (k > 128 && sign > 0) expect = !left;
                    ASSERT_EQ(covered, expect)
                        << (along_y ? (left ? "bottom" : "top") : (left ? "left" : "right"))
                        << " edge moved by " << sign * k << "/65536 pixel";
                }
            }
    }
}

// The tie at -1/512 (which the sweep above cannot see: moving a left edge
// left, or a right one, changes nothing) seen on a diagonal left edge
// whose interior is below it: moved down by 1/512 it still holds the
// centre (snapped back onto it), by 3/1024 it loses it.
TEST(FillRule, NegativeHalfwayRoundsOntoTheCentre) {
    const Window w{64, 64};
    SV_MESA_CONTEXT(ctx, w.W, w.H);
    for (double dy : {0.0, -1.0 / 1024, -1.0 / 512, -3.0 / 1024, -1.0 / 256}) {
        const Window::Tri below{{{10.5, 10.5 + dy}, {50.5, 10.5}, {50.5, 50.5 + dy}}};
        const Window::Tri above{{{10.5, 10.5 + dy}, {50.5, 50.5 + dy}, {10.5, 50.5}}};
        const bool snapped_onto = dy >= -1.0 / 512;
        EXPECT_EQ(w.draw(*ctx, {below})[30 * 64 + 30], snapped_onto ? 1 : 0) << "dy " << dy;
        EXPECT_EQ(w.draw(*ctx, {above})[30 * 64 + 30], snapped_onto ? 0 : 1) << "dy " << dy;
    }
}

// The rule above as code: the number of times triangle T covers the centre
// of pixel (px, py), with T's vertices in 1/256 pixel units (exact).
// Counter-clockwise (y up) +1, clockwise -1 (as the stencil counts them),
// degenerate 0.
int reference_cover(const std::array<std::array<int64_t, 2>, 3> &t, int px, int py) {
    auto cross = [](int64_t ax, int64_t ay, int64_t bx, int64_t by) { return ax * by - ay * bx; };
    const int64_t area = cross(t[1][0] - t[0][0], t[1][1] - t[0][1], t[2][0] - t[0][0],
                               t[2][1] - t[0][1]);
    if (area == 0) return 0;
    const int order[2][3] = {{0, 1, 2}, {0, 2, 1}};
    const int *o = order[area > 0 ? 0 : 1]; // walk it counter-clockwise
    const int64_t cx = px * 256 + 128, cy = py * 256 + 128;
    for (int e = 0; e < 3; ++e) {
        const auto &a = t[o[e]], &b = t[o[(e + 1) % 3]];
        const int64_t dx = b[0] - a[0], dy = b[1] - a[1];
        const int64_t side = cross(dx, dy, cx - a[0], cy - a[1]); // > 0: interior side
        const bool inclusive = dy < 0 || (dy == 0 && dx > 0);
        if (side < 0 || (side == 0 && !inclusive)) return 0;
    }
    return area > 0 ? 1 : -1;
}

// Random triangles against reference_cover, every pixel, exactly: vertices
// on the half-pixel grid (edges through many centres, so many ties) and on
// the 1/256 grid (any slope), overlapping, both windings, some degenerate.
TEST(FillRule, RandomTrianglesMatchTheReferenceRuleExactly) {
    const Window w{64, 64};
    SV_MESA_CONTEXT(ctx, w.W, w.H);
    uint64_t rng = 0x5eed12u;
    auto next = [&rng](int n) {
        rng = rng * 6364136223846793005ull + 1442695040888963407ull;
        return static_cast<int>((rng >> 33) % static_cast<uint64_t>(n));
    };
    for (int round = 0; round < 24; ++round) {
        const int grid = round % 2 == 0 ? 128 : 1; // units of 1/256: half pixels, or 1/256
        std::vector<std::array<std::array<int64_t, 2>, 3>> tris;
        for (int k = 0; k < 40; ++k) {
            std::array<std::array<int64_t, 2>, 3> t;
            for (auto &v : t)
                for (auto &c : v) c = static_cast<int64_t>(next(64 * 256 / grid + 1)) * grid;
            if (k % 13 == 0) { // a degenerate one: the third vertex halfway along the first edge
                for (int c = 0; c < 2; ++c) {
                    t[1][c] -= (t[1][c] - t[0][c]) % (2 * grid); // an even number of grid steps
                    t[2][c] = (t[0][c] + t[1][c]) / 2;
                }
            }
            tris.push_back(t);
        }
        std::vector<Window::Tri> win;
        for (const auto &t : tris)
            win.push_back({{{t[0][0] / 256.0, t[0][1] / 256.0},
                            {t[1][0] / 256.0, t[1][1] / 256.0},
                            {t[2][0] / 256.0, t[2][1] / 256.0}}});
        const std::vector<uint8_t> g = w.draw(*ctx, win);
        int wrong = 0;
        for (int y = 0; y < w.H; ++y)
            for (int x = 0; x < w.W; ++x) {
                int n = 0;
                for (const auto &t : tris) n += reference_cover(t, x, y);
                const int want = ((n % 256) + 256) % 256;
                const int got = g[static_cast<size_t>(y * w.W + x)];
                if (got != want && wrong++ < 5)
                    ADD_FAILURE() << "round " << round << " (grid " << grid << "/256): pixel (" << x
                                  << ", " << y << ") y up: GL " << got << ", the rule " << want;
            }
        ASSERT_EQ(wrong, 0) << "round " << round;
    }
}

// A closed fan around a pixel centre, every edge through pixel centres:
// each centre inside is covered exactly once (no gaps, no double counts
// on shared edges), and the front-and-back pair of the same fan (a closed
// surface) sums to 0 everywhere.
TEST(FillRule, SharedEdgesCoverEachCentreOnce) {
    const Window w{64, 64};
    SV_MESA_CONTEXT(ctx, w.W, w.H);
    const Window::Pt c{32.5, 32.5};
    const Window::Pt ring[] = {{52.5, 32.5}, {47.5, 47.5}, {32.5, 55.5}, {17.5, 44.5},
                               {12.5, 32.5}, {20.5, 15.5}, {32.5, 10.5}, {49.5, 18.5}};
    std::vector<Window::Tri> fan, back;
    for (int k = 0; k < 8; ++k) {
        fan.push_back({c, ring[k], ring[(k + 1) % 8]});
        back.push_back(reversed(fan.back()));
    }
    const std::vector<uint8_t> g = w.draw(*ctx, fan);
    int ones = 0;
    for (uint8_t v : g) {
        ASSERT_LE(v, 1);
        ones += v;
    }
    EXPECT_GT(ones, 900);
    for (int k = 0; k < 8; ++k) // the spokes' centres, between their ends
        for (int s = 1; s < 4; ++s) {
            const double x = c.x + (ring[k].x - c.x) * s / 4, y = c.y + (ring[k].y - c.y) * s / 4;
            if (x == std::floor(x) + 0.5 && y == std::floor(y) + 0.5) {
                EXPECT_EQ(g[static_cast<size_t>(y) * 64 + static_cast<size_t>(x)], 1)
                    << "spoke " << k << " at (" << x << ", " << y << ")";
            }
        }
    std::vector<Window::Tri> both = fan;
    both.insert(both.end(), back.begin(), back.end());
    for (uint8_t v : w.draw(*ctx, both)) ASSERT_EQ(v, 0);
}

// The tie rule holds for large triangles too (llvmpipe bins big ones
// differently), on a 1024 x 1024 window.
TEST(FillRule, TieRuleOnLargeTriangles) {
    const Window w{1024, 1024};
    SV_MESA_CONTEXT(ctx, w.W, w.H);
    const std::vector<uint8_t> left = w.draw(*ctx, {{{{200.5, 1}, {1020, 512}, {200.5, 1020}}}});
    const std::vector<uint8_t> right = w.draw(*ctx, {{{{900.5, 1}, {900.5, 1020}, {3, 512}}}});
    const std::vector<uint8_t> bottom = w.draw(*ctx, {{{{1, 100.5}, {1020, 100.5}, {512, 1020}}}});
    const std::vector<uint8_t> top = w.draw(*ctx, {{{{1, 900.5}, {512, 3}, {1020, 900.5}}}});
    for (int k = 480; k < 540; ++k) {
        ASSERT_EQ(left[static_cast<size_t>(k * 1024 + 200)], 1) << "left edge, row " << k;
        ASSERT_EQ(left[static_cast<size_t>(k * 1024 + 199)], 0);
        ASSERT_EQ(right[static_cast<size_t>(k * 1024 + 900)], 0) << "right edge, row " << k;
        ASSERT_EQ(right[static_cast<size_t>(k * 1024 + 899)], 1);
        ASSERT_EQ(bottom[static_cast<size_t>(100 * 1024 + k)], 1) << "bottom edge, column " << k;
        ASSERT_EQ(bottom[static_cast<size_t>(99 * 1024 + k)], 0);
        ASSERT_EQ(top[static_cast<size_t>(900 * 1024 + k)], 0) << "top edge, column " << k;
        ASSERT_EQ(top[static_cast<size_t>(899 * 1024 + k)], 1);
    }
}

// Where the window coordinates come from, bit for bit, for triangles that
// llvmpipe does not clip (every vertex in front of the camera and inside
// the viewport): float steps, in this order,
//   clip[r] = ((m[r] * x + m[4 + r] * y) + m[8 + r] * z) + m[12 + r] * w
//             (each product and sum rounded: no FMA in the vertex shader),
//   inv_w = 1.0f / clip[3];  ndc = clip * inv_w  (a reciprocal, then a
//             multiply; not a division),
//   window = fmaf(ndc, W / 2, W / 2)  (fused, on a CPU with FMA),
// then snapped to 1/256 by round-to-nearest-even and rasterised by
// reference_cover's rule. Found on 1280 x 1024 with a general view matrix
// (every element non-zero): this model matched every pixel of 23k random
// triangles, while each of the other orders (FMA in the matrix, division,
// unfused viewport, double) missed 3 to 20 pixels. Triangles that cross the
// viewport's border are clipped by llvmpipe and miss a few edge pixels
// against any of these models (about 20-60 per 850k covered pixels,
// vertices up to 1.05-1.5 times outside); they are not tested here.
std::array<int64_t, 2> gl_window_fixed(const float m[16], const Vec4 &p, int W, int H,
                                       bool fused_viewport) {
    const float q[4] = {p.x, p.y, p.z, p.w};
    float clip[4];
    for (int r = 0; r < 4; ++r) {
        float a0 = m[r] * q[0], a1 = m[4 + r] * q[1], a2 = m[8 + r] * q[2], a3 = m[12 + r] * q[3];
        clip[r] = ((a0 + a1) + a2) + a3;
    }
    const float inv_w = 1.0f / clip[3];
    const float nx = clip[0] * inv_w, ny = clip[1] * inv_w;
    const float hw = static_cast<float>(W) / 2, hh = static_cast<float>(H) / 2;
    float wx, wy;
    if (fused_viewport) {
        wx = std::fmaf(nx, hw, hw);
        wy = std::fmaf(ny, hh, hh);
    } else {
        const float px = nx * hw, py = ny * hh; // rounded apart (the test has -ffp-contract=off)
        wx = px + hw;
        wy = py + hh;
    }
    return {static_cast<int64_t>(std::nearbyint(static_cast<double>(wx) * 256.0)),
            static_cast<int64_t>(std::nearbyint(static_cast<double>(wy) * 256.0))};
}

TEST(FillRule, WindowCoordinatesFollowGlFloatSteps) {
    const int W = 1280, H = 1024;
    SV_MESA_CONTEXT(ctx, W, H);
    // VP = P * (rotation about x) * (rotation about y, then a translation).
    const auto P = infinite_perspective(60, double(W) / H, 0.1);
    const double c = std::cos(0.3), s = std::sin(0.3), c2 = std::cos(0.2), s2 = std::sin(0.2);
    const double Ry[16] = {c, 0, -s, 0, 0, 1, 0, 0, s, 0, c, 0, 0.3, -0.2, -4, 1};
    const double Rx[16] = {1, 0, 0, 0, 0, c2, s2, 0, 0, -s2, c2, 0, 0, 0, 0, 1};
    auto mul = [](const double *A, const double *B, double *C) {
        for (int r = 0; r < 4; ++r)
            for (int k = 0; k < 4; ++k) {
                double t = 0;
                for (int j = 0; j < 4; ++j) t += A[j * 4 + r] * B[k * 4 + j];
                C[k * 4 + r] = t;
            }
    };
    double V[16], VP[16];
    mul(Rx, Ry, V);
    mul(P.data(), V, VP);
    float m[16];
    for (int i = 0; i < 16; ++i) m[i] = static_cast<float>(VP[i]);

    uint64_t rng = 0xf10a7u;
    auto uni = [&rng](float lo, float hi) {
        rng = rng * 6364136223846793005ull + 1442695040888963407ull;
        return lo + (hi - lo) * static_cast<float>((rng >> 40) & 0xFFFFFF) / float(1 << 24);
    };
    Scene sc(W, H);
    std::copy(VP, VP + 16, sc.vp.begin());
    std::vector<Vec4> tris;
    for (int t = 0; t < 6000; ++t) {
        const float size = t % 3 == 0 ? 0.3f : 0.05f;
        const float cx = uni(-1.5f, 1.5f), cy = uni(-1.5f, 1.5f), cz = uni(-1.5f, 1.5f);
        Vec4 v[3];
        bool inside = true;
        for (Vec4 &k : v) {
            k = {cx + uni(-size, size), cy + uni(-size, size), cz + uni(-size, size), 1};
            double clip[4];
            for (int r = 0; r < 4; ++r)
                clip[r] = VP[r] * k.x + VP[4 + r] * k.y + VP[8 + r] * k.z + VP[12 + r];
            inside = inside && clip[3] > 0.2 && std::fabs(clip[0] / clip[3]) < 0.98 &&
                     std::fabs(clip[1] / clip[3]) < 0.98;
        }
        if (inside) tris.insert(tris.end(), v, v + 3);
    }
    sc.volume(tris);
    const MesaStencilResult r = ctx->run(sc.job());

    auto mismatches = [&](bool fused) {
        std::vector<int> count(static_cast<size_t>(W * H), 0);
        for (size_t t = 0; t < tris.size(); t += 3) {
            std::array<std::array<int64_t, 2>, 3> f;
            for (int k = 0; k < 3; ++k)
                f[static_cast<size_t>(k)] = gl_window_fixed(m, tris[t + static_cast<size_t>(k)], W,
                                                            H, fused);
            int64_t x0 = W, x1 = 0, y0 = H, y1 = 0;
            for (const auto &v : f) {
                x0 = std::min<int64_t>(x0, v[0] / 256 - 1);
                x1 = std::max<int64_t>(x1, v[0] / 256 + 1);
                y0 = std::min<int64_t>(y0, v[1] / 256 - 1);
                y1 = std::max<int64_t>(y1, v[1] / 256 + 1);
            }
            for (int64_t y = std::max<int64_t>(0, y0); y <= std::min<int64_t>(H - 1, y1); ++y)
                for (int64_t x = std::max<int64_t>(0, x0); x <= std::min<int64_t>(W - 1, x1); ++x)
                    count[static_cast<size_t>(y * W + x)] += reference_cover(f, int(x), int(y));
        }
        int bad = 0;
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
                const int want = ((count[static_cast<size_t>(y * W + x)] % 256) + 256) % 256;
                bad += at(r, W, H - 1 - y, x) != want;
            }
        return bad;
    };
    const int fused = mismatches(true), unfused = mismatches(false);
    std::printf("window coordinates: %zu triangles; pixels off the float model: %d with a fused "
                "viewport multiply-add, %d unfused\n",
                tris.size() / 3, fused, unfused);
    EXPECT_GT(tris.size() / 3, 2000u);
#if defined(__x86_64__) || defined(__i386__)
    if (__builtin_cpu_supports("fma"))
        EXPECT_EQ(fused, 0) << "llvmpipe on an FMA CPU: the viewport transform is fused";
    else
#endif
        EXPECT_EQ(std::min(fused, unfused), 0) << "no float model matches llvmpipe here";
}

} // namespace
