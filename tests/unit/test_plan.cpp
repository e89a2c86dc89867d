// Dispatch by measurement (include/shadowvol_plan.h, issue 15): size
// classes, the built-in plan, a measured plan (its choices are the fastest
// of its own timings, its kernels compute c_ref's volume), SV_PLAN_MEASURE,
// the wisdom file (round trip, other CPUs' sections kept, a malformed file
// refused whole), and the ISA limit.
//
// Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
#include "test_support.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "shadowvol_mesh.h"
#include "shadowvol_plan.h"

using namespace svtest;

namespace {

constexpr double kPi = 3.14159265358979323846;

std::string temp_path(const char *name) {
    const char *dir = std::getenv("TMPDIR");
    return std::string(dir && *dir ? dir : "/tmp") + "/sv_plan_test_" + std::to_string(getpid()) +
           "_" + name;
}

std::string read_all(const std::string &path) {
    std::ifstream in(path);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

// A closed mesh for the volume check: a UV sphere (the poles' copies weld,
// their degenerate triangles are dropped).
sv::PreparedSurface test_surface() {
    std::vector<float> p;
    std::vector<uint32_t> idx;
    const int n = 24; // a UV sphere, n x n
    for (int i = 0; i <= n; i++) {
        for (int j = 0; j < n; j++) {
            const double th = kPi * i / n, ph = 2 * kPi * j / n;
            p.push_back((float)(std::sin(th) * std::cos(ph)));
            p.push_back((float)(std::sin(th) * std::sin(ph)));
            p.push_back((float)std::cos(th));
        }
    }
    for (int i = 0; i < n; i++) {
        for (int j = 0; j < n; j++) {
            const uint32_t a = (uint32_t)(i * n + j), b = (uint32_t)(i * n + (j + 1) % n),
                           c = a + (uint32_t)n, d = b + (uint32_t)n;
            idx.insert(idx.end(), {a, c, d, a, d, b});
        }
    }
    return sv::prepare_surface(p.data(), p.size() / 3, idx.data(), idx.size());
}

void expect_plan_computes_c_ref(const sv_plan &plan) {
    const sv::PreparedSurface s = test_surface();
    const Vec4 light = {1.7f, 0.4f, 0.9f, 1};
    sv::AlignedVector<uint8_t> facing(s.num_triangles() + 1), ref_facing(s.num_triangles() + 1);
    plan.calculate_facing(s.planes.data(), s.num_triangles(), &light, facing.data());
    sv_calculate_facing_c_ref(s.planes.data(), s.num_triangles(), &light, ref_facing.data());
    ASSERT_EQ(facing, ref_facing) << "calculate_facing "
                                  << plan.variant[SV_ROUTINE_CALCULATE_FACING];
    sv::AlignedVector<int> out(sv_shadow_volume_capacity(s.num_indices(), s.num_sil_edges()));
    sv::AlignedVector<int> ref(out.size());
    const int n = sv_create_shadow_volume_checked(&plan.kernels, out.data(), out.size(),
                                                  s.indices.data(), s.num_indices(),
                                                  s.num_triangles(), s.sil_edges.data(),
                                                  s.num_sil_edges(), facing.data(), nullptr);
    const int e = sv_create_shadow_volume(sv_variant_by_name("c_ref"), ref.data(), s.indices.data(),
                                          s.num_indices(), s.sil_edges.data(), s.num_sil_edges(),
                                          ref_facing.data(), nullptr);
    ASSERT_GT(e, 0);
    ASSERT_EQ(n, e) << (n < 0 ? sv_status_string(n) : "count");
    EXPECT_EQ(0, std::memcmp(out.data(), ref.data(), sizeof(int) * (size_t)n));
}

class PlanTest : public ::testing::Test {
protected:
    void SetUp() override { sv_plan_reset(); }
    void TearDown() override { sv_plan_reset(); }
};

} // namespace

TEST_F(PlanTest, SizeClasses) {
    EXPECT_EQ(sv_size_class(0), 0);
    EXPECT_EQ(sv_size_class(-5), 0);
    EXPECT_EQ(sv_size_class(4095), 0);
    EXPECT_EQ(sv_size_class(4096), 1);
    EXPECT_EQ(sv_size_class(65535), 1);
    EXPECT_EQ(sv_size_class(65536), 2);
    EXPECT_EQ(sv_size_class(524288), 3);
    EXPECT_EQ(sv_size_class(INT32_MAX), 3);
    for (int c = 0; c < SV_NUM_SIZE_CLASSES; c++) {
        EXPECT_EQ(sv_size_class(sv_size_class_triangles(c)), c);
    }
    EXPECT_STREQ(sv_static_variant_name(SV_ROUTINE_CALCULATE_FACING),
                 sv_best_facing_variant()->name);
    EXPECT_STREQ(sv_static_variant_name(SV_ROUTINE_CREATE_SIL_TRIANGLES), sv_best_variant()->name);
    EXPECT_EQ(sv_static_variant_name(SV_NUM_ROUTINES), nullptr);
    EXPECT_EQ(sv_size_class_triangles(-1), 0);
    EXPECT_EQ(sv_size_class_triangles(SV_NUM_SIZE_CLASSES), 0);
    EXPECT_STREQ(sv_routine_name(SV_ROUTINE_CREATE_CAP_TRIANGLES), "create_cap_triangles");
    EXPECT_EQ(sv_routine_name(SV_NUM_ROUTINES), nullptr);
}

TEST_F(PlanTest, BuiltInPlanRunsHereAndComputesCRef) {
    for (int c = 0; c < SV_NUM_SIZE_CLASSES; c++) {
        const sv_plan *p = sv_plan_for(sv_size_class_triangles(c), SV_PLAN_ESTIMATE);
        ASSERT_NE(p, nullptr);
        EXPECT_EQ(p->size_class, c);
        EXPECT_STREQ(p->source, "built-in");
        EXPECT_EQ(p->kernels.isa & sv_cpu_isa(), p->kernels.isa) << "needs what this CPU lacks";
        for (int r = 0; r < SV_NUM_ROUTINES; r++) EXPECT_NE(p->variant[r], nullptr);
        expect_plan_computes_c_ref(*p);
    }
}

TEST_F(PlanTest, MeasuredPlanTakesTheFastestOfItsTimingsAndComputesCRef) {
    std::vector<sv_plan_timing> t(64);
    const int n = sv_plan_measure(0, t.data(), (int)t.size());
    ASSERT_GT(n, 0);
    ASSERT_LE(n, (int)t.size());
    t.resize((size_t)n);
    const sv_plan *p = sv_plan_for(100, SV_PLAN_ESTIMATE);
    EXPECT_STREQ(p->source, "measured");
    for (int r = 0; r < SV_NUM_ROUTINES; r++) {
        double best = -1;
        int timed = 0;
        for (const sv_plan_timing &x : t) {
            if (x.routine != r) continue;
            timed++;
            EXPECT_GT(x.ticks, 0) << sv_routine_name((sv_routine)r) << " " << x.variant;
            if (best < 0 || x.ticks < best) best = x.ticks;
        }
        EXPECT_GE(timed, 1) << sv_routine_name((sv_routine)r);
        // The fastest, or the static choice (kept unless another variant
        // beats it by the 3% margin overall and round by round: the
        // rounds are not visible here), with its own timing.
        const char *stat = sv_static_variant_name((sv_routine)r);
        double stat_ticks = -1;
        for (const sv_plan_timing &x : t) {
            if (x.routine == r && std::strcmp(x.variant, stat) == 0) stat_ticks = x.ticks;
        }
        if (std::strcmp(p->variant[r], stat) == 0 && p->ticks[r] != best) {
            EXPECT_EQ(p->ticks[r], stat_ticks) << sv_routine_name((sv_routine)r);
        } else {
            EXPECT_EQ(p->ticks[r], best)
                << sv_routine_name((sv_routine)r) << ": the plan is not the fastest";
            if (std::strcmp(p->variant[r], stat) != 0 && stat_ticks > 0) {
                EXPECT_GT(stat_ticks, best * 1.03)
                    << sv_routine_name((sv_routine)r)
                    << ": replaced the static choice within the margin";
            }
        }
    }
    expect_plan_computes_c_ref(*p);
    // Other classes were not measured.
    EXPECT_STREQ(sv_plan_for(sv_size_class_triangles(1), SV_PLAN_ESTIMATE)->source, "built-in");
}

// The caller's own surface: measured on it (a copy, so no alignment is
// asked: here every array starts 4 bytes past an aligned address), the
// plan of its class only, and it computes c_ref.
TEST_F(PlanTest, MeasuringTheCallersSurfacePlansItsClass) {
    const sv::PreparedSurface s = test_surface();
    std::vector<Vec4> pos((size_t)s.num_vertices());
    for (int i = 0; i < s.num_vertices(); i++) {
        pos[(size_t)i] = {s.positions[3 * (size_t)i], s.positions[3 * (size_t)i + 1],
                          s.positions[3 * (size_t)i + 2], 1};
    }
    // Misaligned copies: planes and indices 4 bytes past their alignment.
    std::vector<char> planeBytes(sizeof(Plane) * (size_t)s.num_triangles() + 64);
    std::vector<char> indexBytes(sizeof(int) * (size_t)s.num_indices() + 64);
    char *pa = planeBytes.data() +
               (64 - (reinterpret_cast<uintptr_t>(planeBytes.data()) % 64)) % 64 + 4;
    char *ia = indexBytes.data() +
               (64 - (reinterpret_cast<uintptr_t>(indexBytes.data()) % 64)) % 64 + 4;
    std::memcpy(pa, s.planes.data(), sizeof(Plane) * (size_t)s.num_triangles());
    std::memcpy(ia, s.indices.data(), sizeof(int) * (size_t)s.num_indices());
    sv_surface v{reinterpret_cast<const Plane *>(pa),
                 reinterpret_cast<const int *>(ia),
                 s.num_indices(),
                 s.sil_edges.data(),
                 s.num_sil_edges(),
                 pos.data(),
                 s.num_vertices(),
                 Bounds{}};
    std::vector<sv_plan_timing> t(64);
    const int n = sv_plan_measure_surface(&v, t.data(), (int)t.size());
    ASSERT_GT(n, 0);
    for (int i = 0; i < std::min(n, (int)t.size()); i++) {
        EXPECT_EQ(t[(size_t)i].size_class, sv_size_class(s.num_triangles()));
        EXPECT_GT(t[(size_t)i].ticks, 0);
    }
    const sv_plan *p = sv_plan_for(s.num_triangles(), SV_PLAN_ESTIMATE);
    EXPECT_STREQ(p->source, "measured");
    expect_plan_computes_c_ref(*p);
    EXPECT_STREQ(sv_plan_for(sv_size_class_triangles(2), SV_PLAN_ESTIMATE)->source, "built-in");
}

// A surface that breaks a contract is refused (-2) before anything is
// measured, and plans nothing.
TEST_F(PlanTest, MeasuringABadSurfaceIsRefused) {
    const sv::PreparedSurface s = test_surface();
    std::vector<Vec4> pos((size_t)s.num_vertices(), Vec4{0, 0, 0, 1});
    for (int i = 0; i < s.num_vertices(); i++) {
        pos[(size_t)i] = {s.positions[3 * (size_t)i], s.positions[3 * (size_t)i + 1],
                          s.positions[3 * (size_t)i + 2], 1};
    }
    const sv_surface good{s.planes.data(),   s.indices.data(), s.num_indices(),  s.sil_edges.data(),
                          s.num_sil_edges(), pos.data(),       s.num_vertices(), Bounds{}};
    EXPECT_EQ(sv_plan_measure_surface(nullptr, nullptr, 0), -2);
    sv_surface v = good;
    v.numIndices = 0;
    EXPECT_EQ(sv_plan_measure_surface(&v, nullptr, 0), -2) << "no triangle";
    v = good;
    v.numIndices -= 1;
    EXPECT_EQ(sv_plan_measure_surface(&v, nullptr, 0), -2) << "not a multiple of 3";
    v = good;
    v.planes = nullptr;
    EXPECT_EQ(sv_plan_measure_surface(&v, nullptr, 0), -2) << "NULL planes";
    v = good;
    v.numVerts -= 1; // the last vertex is used: an index out of range
    EXPECT_EQ(sv_plan_measure_surface(&v, nullptr, 0), -2) << "index out of range";
    std::vector<SilEdge> edges(s.sil_edges.begin(), s.sil_edges.end());
    edges.back().v2 |= 1;
    v = good;
    v.silEdges = edges.data();
    EXPECT_EQ(sv_plan_measure_surface(&v, nullptr, 0), -2) << "odd SilEdge vertex";
    edges = std::vector<SilEdge>(s.sil_edges.begin(), s.sil_edges.end());
    edges.front().p2 = s.num_triangles() + 1;
    v.silEdges = edges.data();
    EXPECT_EQ(sv_plan_measure_surface(&v, nullptr, 0), -2) << "SilEdge triangle out of range";
    std::vector<Plane> planes(s.planes.begin(), s.planes.end());
    planes[7].b = std::nanf("");
    v = good;
    v.planes = planes.data();
    EXPECT_EQ(sv_plan_measure_surface(&v, nullptr, 0), -2) << "NaN plane";
    std::vector<Vec4> inf = pos;
    inf[3].z = INFINITY;
    v = good;
    v.positions = inf.data();
    EXPECT_EQ(sv_plan_measure_surface(&v, nullptr, 0), -2) << "infinite position";
    EXPECT_STREQ(sv_plan_for(s.num_triangles(), SV_PLAN_ESTIMATE)->source, "built-in");
}

TEST_F(PlanTest, MeasureFlagMeasuresOnFirstUse) {
    const sv_plan *p = sv_plan_for(1000, SV_PLAN_MEASURE);
    EXPECT_STREQ(p->source, "measured");
    EXPECT_EQ(sv_plan_for(2000, SV_PLAN_MEASURE), p) << "measured again";
}

TEST_F(PlanTest, WisdomRoundTripKeepsOtherCpusAndRefusesMalformedFiles) {
    const std::string path = temp_path("wisdom/dir/file");
    char key[256];
    sv_cpu_model_key(key, sizeof key);
    ASSERT_GT(std::strlen(key), 5u);
    // A file with another CPU's section first.
    std::remove(path.c_str());
    ASSERT_EQ(sv_wisdom_save(path.c_str()), 0) << "creates the folders";
    {
        std::ofstream out(path);
        out << "shadowvol-wisdom 1\ncpu OtherVendor 1/2/3 sse2 A CPU that is not this one\n"
            << "class 0 count_facing c_ref 10.0\n";
    }
    EXPECT_EQ(sv_wisdom_load(path.c_str()), 0) << "no section for this CPU";
    EXPECT_STREQ(sv_plan_for(1, SV_PLAN_ESTIMATE)->source, "built-in");

    ASSERT_GT(sv_plan_measure(0, nullptr, 0), 0);
    const sv_plan measured = *sv_plan_for(1, SV_PLAN_ESTIMATE);
    ASSERT_EQ(sv_wisdom_save(path.c_str()), 0);
    const std::string text = read_all(path);
    EXPECT_NE(text.find("cpu OtherVendor 1/2/3 sse2 A CPU that is not this one\nclass 0 "
                        "count_facing c_ref 10.0\n"),
              std::string::npos)
        << text;
    EXPECT_NE(text.find(std::string("cpu ") + key + "\n"), std::string::npos) << text;

    sv_plan_reset();
    EXPECT_EQ(sv_wisdom_load(path.c_str()), 1);
    const sv_plan *w = sv_plan_for(1, SV_PLAN_ESTIMATE);
    EXPECT_STREQ(w->source, "wisdom");
    for (int r = 0; r < SV_NUM_ROUTINES; r++) {
        EXPECT_STREQ(w->variant[r], measured.variant[r]) << sv_routine_name((sv_routine)r);
    }
    expect_plan_computes_c_ref(*w);
    // SV_PLAN_MEASURE does not re-measure a class the wisdom has.
    EXPECT_STREQ(sv_plan_for(1, SV_PLAN_MEASURE)->source, "wisdom");

    // Malformed: nothing is taken.
    for (const char *bad : {"not wisdom\n", "shadowvol-wisdom 1\nclass 0 count_facing c_ref 1\n",
                            "shadowvol-wisdom 1\ncpu X\nclass 9 count_facing c_ref 1\n",
                            "shadowvol-wisdom 1\ncpu X\nclass 0 no_such_routine c_ref 1\n",
                            "shadowvol-wisdom 1\ncpu X\nclass 0 count_facing c_ref\n"}) {
        sv_plan_reset();
        {
            std::ofstream out(path);
            out << bad << "cpu " << key << "\nclass 0 count_facing c_ref 1.0\n";
        }
        EXPECT_EQ(sv_wisdom_load(path.c_str()), -1) << bad;
        EXPECT_STREQ(sv_plan_for(1, SV_PLAN_ESTIMATE)->source, "built-in") << bad;
        EXPECT_EQ(sv_wisdom_save(path.c_str()), -1) << "overwrote a file it cannot read: " << bad;
    }
    EXPECT_EQ(sv_wisdom_load((path + ".missing").c_str()), -1);
    std::remove(path.c_str());
}

// The stencil pass's method (issue 28): a measurement is saved as this
// CPU's "stencil" line and read back as the wisdom's choice; the wisdom
// never overrides a measurement; "inf" reads; a line with a method, tile
// or threshold that is not one refuses the file.
TEST_F(PlanTest, WisdomCarriesTheStencilChoice) {
    const std::string path = temp_path("stencil");
    std::remove(path.c_str());
    char key[256];
    sv_cpu_model_key(key, sizeof key);
    sv_stencil_choice c;
    EXPECT_EQ(sv_stencil_choice_for(&c), 0) << "none before a measurement";
    EXPECT_EQ(sv_stencil_choice_for(nullptr), -1);
    for (const char *bad : {"fast", "", "bf "}) EXPECT_EQ(sv_stencil_choice_set(bad, 32, 1), -1);
    EXPECT_EQ(sv_stencil_choice_set("auto", 12, 1), -1) << "no such tile";
    EXPECT_EQ(sv_stencil_choice_set("auto", 32, -1), -1) << "negative threshold";
    EXPECT_EQ(sv_stencil_choice_set("auto", 32, NAN), -1) << "NaN threshold";
    ASSERT_EQ(sv_stencil_choice_set("auto", 16, 71.25), 0);
    ASSERT_EQ(sv_stencil_choice_for(&c), 1);
    EXPECT_STREQ(c.method, "auto");
    EXPECT_STREQ(c.source, "measured");
    ASSERT_EQ(sv_wisdom_save(path.c_str()), 0);
    const std::string text = read_all(path);
    EXPECT_NE(text.find(std::string("cpu ") + key + "\nstencil auto 16 71.2\n"), std::string::npos)
        << text;

    sv_plan_reset();
    EXPECT_EQ(sv_stencil_choice_for(&c), 0) << "reset forgets it";
    EXPECT_EQ(sv_wisdom_load(path.c_str()), 0) << "no class in the file";
    ASSERT_EQ(sv_stencil_choice_for(&c), 1);
    EXPECT_STREQ(c.method, "auto");
    EXPECT_EQ(c.tile, 16);
    EXPECT_NEAR(c.hier_from_area_per_piece, 71.2, 1e-9);
    EXPECT_STREQ(c.source, "wisdom");

    // A measurement outranks the file, and the file does not come back over it.
    ASSERT_EQ(sv_stencil_choice_set("hier", 8, 0), 0);
    EXPECT_EQ(sv_wisdom_load(path.c_str()), 0);
    ASSERT_EQ(sv_stencil_choice_for(&c), 1);
    EXPECT_STREQ(c.method, "hier");

    sv_plan_reset();
    {
        std::ofstream out(path);
        out << "shadowvol-wisdom 1\ncpu " << key << "\nstencil bf 32 inf\n";
    }
    EXPECT_EQ(sv_wisdom_load(path.c_str()), 0);
    ASSERT_EQ(sv_stencil_choice_for(&c), 1);
    EXPECT_STREQ(c.method, "bf");
    EXPECT_TRUE(std::isinf(c.hier_from_area_per_piece));
    ASSERT_EQ(sv_wisdom_save(path.c_str()), 0) << "rewrites what it read";
    EXPECT_NE(read_all(path).find("\nstencil bf 32 inf\n"), std::string::npos) << read_all(path);

    for (const char *bad :
         {"stencil fast 32 1", "stencil auto 12 1", "stencil auto 32 -1", "stencil auto 32 nan",
          "stencil auto 32", "stencil auto 32 1 x", "stencil auto 32 1x"}) {
        sv_plan_reset();
        {
            std::ofstream out(path);
            out << "shadowvol-wisdom 1\ncpu " << key << "\n" << bad << "\n";
        }
        EXPECT_EQ(sv_wisdom_load(path.c_str()), -1) << bad;
        EXPECT_EQ(sv_stencil_choice_for(&c), 0) << bad;
    }
    sv_plan_reset();
    std::remove(path.c_str());
}

TEST_F(PlanTest, WisdomNamingAVariantThisCpuLacksFallsBack) {
    const std::string path = temp_path("lacks");
    char key[256];
    sv_cpu_model_key(key, sizeof key);
    {
        std::ofstream out(path);
        out << "shadowvol-wisdom 1\ncpu " << key
            << "\nclass 0 create_sil_triangles no_such_variant 5\n"
            << "class 0 count_facing c_ref 7\n";
    }
    ASSERT_EQ(sv_wisdom_load(path.c_str()), 1);
    const sv_plan *p = sv_plan_for(1, SV_PLAN_ESTIMATE);
    EXPECT_STREQ(p->variant[SV_ROUTINE_COUNT_FACING], "c_ref");
    EXPECT_STREQ(p->variant[SV_ROUTINE_CREATE_SIL_TRIANGLES], sv_best_variant()->name);
    expect_plan_computes_c_ref(*p);
    std::remove(path.c_str());
}

TEST_F(PlanTest, UnderAnIsaLimitThePlanUsesOnlyWhatTheLimitAllows) {
    const char *saved = sv_isa_limit_name();
    const std::string keep = saved ? saved : "";
    ASSERT_EQ(sv_set_isa_limit("c"), 0);
    char key[256];
    sv_cpu_model_key(key, sizeof key);
    EXPECT_NE(std::string(key).find(" c "), std::string::npos) << key;
    ASSERT_GT(sv_plan_measure(0, nullptr, 0), 0);
    const sv_plan *p = sv_plan_for(1, SV_PLAN_ESTIMATE);
    EXPECT_EQ(p->kernels.isa, 0u);
    expect_plan_computes_c_ref(*p);
    sv_set_isa_limit(keep.empty() ? nullptr : keep.c_str());
    // Measured with the limit lifted, then the limit lowered: the plan is
    // made again within the limit.
    sv_plan_reset();
    ASSERT_GT(sv_plan_measure(0, nullptr, 0), 0);
    ASSERT_EQ(sv_set_isa_limit("c"), 0);
    const sv_plan *q = sv_plan_for(1, SV_PLAN_ESTIMATE);
    EXPECT_EQ(q->kernels.isa, 0u) << q->source;
    for (int r = 0; r <= SV_ROUTINE_CALCULATE_CULL_BITS; r++) EXPECT_STREQ(q->variant[r], "c_ref");
    sv_set_isa_limit(keep.empty() ? nullptr : keep.c_str());
}
