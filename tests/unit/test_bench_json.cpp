/*
 * `shadowvol bench --quick --json FILE`, as a script reads it: the
 * document of schema shadowvol-bench/1 (bench/report/json_report.h) validated
 * strictly, field by field, and every routine x variant x regime row
 * present and checked on the bundled character. The validator itself is
 * tested too: documents broken on purpose (a field missing, a wrong type, a
 * row gone, a failed check) must be rejected, or it could pass anything.
 *
 * The program under test is the built shadowvol (SV_SHADOWVOL_EXE, from
 * CMake), run as a user runs it. No timing is asserted (a noisy 2-core VM
 * runs this), only that the figures are numbers that make sense.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

#include "shadowvol.h"
#include "shadowvol_plan.h"

#ifndef SV_SHADOWVOL_EXE
#error "SV_SHADOWVOL_EXE must name the built shadowvol program"
#endif

namespace {

using nlohmann::json;

const char *const kSchema = "shadowvol-bench/1";
const std::set<std::string> kRoutines = {
    "calculate_facing",     "calculate_cull_bits",       "count_facing",
    "count_facing_cull",    "create_sil_triangles",      "create_cap_triangles",
    "create_shadow_volume", "create_shadow_volume_cull", "pipeline",
    "pipeline_cull",
};
/* The pipelines (A, B and the volume): every kernel variant, with its own
 * or the nearest facing variant's A and B (routines.h). */
const std::set<std::string> kPipelineRoutines = {"pipeline", "pipeline_cull"};
/* Routines every variant of the library's table implements; appendices A
 * and B exist as c_ref only so far. */
const std::set<std::string> kKernelRoutines = {
    "count_facing",         "count_facing_cull",    "create_sil_triangles",
    "create_cap_triangles", "create_shadow_volume", "create_shadow_volume_cull",
};
const std::set<std::string> kCalculateRoutines = {"calculate_facing", "calculate_cull_bits"};
const std::set<std::string> kRegimes = {"fixed", "moving"};
const std::set<std::string> kTimers = {"rdtscp", "cpuid", "lfence"};

/* The variant table's names, and those this CPU runs. */
std::set<std::string> variant_names(bool runnableOnly) {
    int n = 0;
    const sv_variant *v = sv_variants(&n);
    std::set<std::string> names;
    for (int i = 0; i < n; i++) {
        if (!runnableOnly || (v[i].isa & sv_cpu_isa()) == v[i].isa) {
            names.insert(v[i].name);
        }
    }
    return names;
}

/* Names of the implementations of appendices A and B (sv_facing_variants):
 * the variants of the calculate_* rows. */
std::set<std::string> facing_variant_names(bool runnableOnly) {
    int n = 0;
    const sv_facing_variant *v = sv_facing_variants(&n);
    std::set<std::string> names;
    for (int i = 0; i < n; i++) {
        if (!runnableOnly || (v[i].isa & sv_cpu_isa()) == v[i].isa) {
            names.insert(v[i].name);
        }
    }
    return names;
}

std::set<std::string> all_variant_names() {
    std::set<std::string> names = variant_names(false);
    for (const std::string &f : facing_variant_names(false)) names.insert(f);
    names.insert("planned");         /* the planner's choice (shadowvol_plan.h) */
    names.insert("planned_kernels"); /* its kernels unfused (pipelines only) */
    return names;
}

/* Collects what is wrong with a document, field by field. */
class Validator {
public:
    std::vector<std::string> errors;

    void fail(const std::string &where, const std::string &what) {
        errors.push_back(where + ": " + what);
    }

    /* OBJ[KEY] exists and is a string (non-empty); returns it or "". */
    std::string string(const json &obj, const char *key, const std::string &where) {
        if (!obj.contains(key)) {
            fail(where, std::string("no \"") + key + "\"");
            return "";
        }
        const json &v = obj.at(key);
        if (!v.is_string() || v.get<std::string>().empty()) {
            fail(where, std::string("\"") + key + "\" is not a non-empty string");
            return "";
        }
        return v.get<std::string>();
    }
    /* OBJ[KEY] is a string from ALLOWED. */
    std::string one_of(const json &obj, const char *key, const std::set<std::string> &allowed,
                       const std::string &where) {
        const std::string s = string(obj, key, where);
        if (!s.empty() && !allowed.count(s)) {
            fail(where, std::string("\"") + key + "\" is \"" + s + "\", not an allowed name");
        }
        return s;
    }
    /* OBJ[KEY] is a whole number >= LO; returns it or -1. */
    long long integer(const json &obj, const char *key, long long lo, const std::string &where) {
        if (!obj.contains(key)) {
            fail(where, std::string("no \"") + key + "\"");
            return -1;
        }
        const json &v = obj.at(key);
        if (!v.is_number_integer() || v.get<long long>() < lo) {
            fail(where,
                 std::string("\"") + key + "\" is not a whole number >= " + std::to_string(lo));
            return -1;
        }
        return v.get<long long>();
    }
    /* OBJ[KEY] is a finite number >= 0; returns it or -1. */
    double number(const json &obj, const char *key, const std::string &where) {
        if (!obj.contains(key)) {
            fail(where, std::string("no \"") + key + "\"");
            return -1;
        }
        const json &v = obj.at(key);
        if (!v.is_number() || !std::isfinite(v.get<double>()) || v.get<double>() < 0) {
            fail(where, std::string("\"") + key + "\" is not a finite number >= 0");
            return -1;
        }
        return v.get<double>();
    }
    bool boolean(const json &obj, const char *key, const std::string &where) {
        if (!obj.contains(key) || !obj.at(key).is_boolean()) {
            fail(where, std::string("\"") + key + "\" is missing or not true/false");
            return false;
        }
        return obj.at(key).get<bool>();
    }

    void document(const json &doc) {
        if (!doc.is_object()) {
            fail("document", "not an object");
            return;
        }
        if (string(doc, "schema", "document") != kSchema && doc.contains("schema")) {
            fail("document", std::string("schema is not \"") + kSchema + "\"");
        }
        cpu(doc);
        string(doc, "compiler", "document");
        string(doc, "commit", "document");
        one_of(doc, "timer", kTimers, "document");
        if (!doc.contains("results") || !doc.at("results").is_array() ||
            doc.at("results").empty()) {
            fail("document", "\"results\" is missing, not an array, or empty");
            return;
        }
        const json &results = doc.at("results");
        for (size_t i = 0; i < results.size(); i++) {
            row(results[i], "results[" + std::to_string(i) + "]");
        }
    }

    void cpu(const json &doc) {
        if (!doc.contains("cpu") || !doc.at("cpu").is_object()) {
            fail("document", "\"cpu\" is missing or not an object");
            return;
        }
        const json &c = doc.at("cpu");
        string(c, "model", "cpu");
        if (!c.contains("isa") || !c.at("isa").is_array()) {
            fail("cpu", "\"isa\" is missing or not an array");
        } else {
            bool sse2 = false;
            for (const json &f : c.at("isa")) {
                if (!f.is_string() || f.get<std::string>().empty()) {
                    fail("cpu", "an \"isa\" entry is not a non-empty string");
                } else {
                    sse2 = sse2 || f.get<std::string>() == "sse2";
                }
            }
            if (!sse2) { /* architectural on x86-64, where the bench runs */
                fail("cpu", "\"isa\" lacks sse2");
            }
        }
        if (number(c, "tsc_hz", "cpu") == 0) {
            fail("cpu", "\"tsc_hz\" is 0");
        }
    }

    void row(const json &r, const std::string &where) {
        if (!r.is_object()) {
            fail(where, "not an object");
            return;
        }
        string(r, "model", where);
        const long long tris = integer(r, "triangles", 1, where);
        const long long edges = integer(r, "edges", 0, where);
        const std::string routine = one_of(r, "routine", kRoutines, where);
        one_of(r, "variant", all_variant_names(), where);
        one_of(r, "regime", kRegimes, where);
        const long long elements = integer(r, "elements", 1, where);
        integer(r, "runs", 1, where);
        const bool checked = boolean(r, "checked", where);
        if (r.contains("checked") && r.at("checked").is_boolean() && !checked) {
            fail(where, "\"checked\" is false: the row failed its correctness check");
        }
        const double mn = number(r, "ticks_min", where);
        const double md = number(r, "ticks_median", where);
        const double emn = number(r, "ticks_per_element_min", where);
        const double emd = number(r, "ticks_per_element_median", where);
        if (mn >= 0 && md >= 0 && md < mn) {
            fail(where, "ticks_median is below ticks_min");
        }
        if (emn >= 0 && emd >= 0 && emd < emn) {
            fail(where, "ticks_per_element_median is below ticks_per_element_min");
        }
        if (elements > 0 && mn >= 0 && emn >= 0 &&
            std::fabs(emn * (double)elements - mn) > 1e-6 * std::max(1.0, mn)) {
            fail(where, "ticks_per_element_min is not ticks_min / elements");
        }
        if (elements > 0 && md >= 0 && emd >= 0 &&
            std::fabs(emd * (double)elements - md) > 1e-6 * std::max(1.0, md)) {
            fail(where, "ticks_per_element_median is not ticks_median / elements");
        }
        /* Per SilEdge for CreateSilTriangles, per vertex for
         * CalculateCullBits, per triangle otherwise. */
        if (routine == "create_sil_triangles") {
            if (edges >= 0 && elements >= 0 && elements != edges) {
                fail(where, "elements is not the model's edges");
            }
        } else if (routine == "calculate_cull_bits") {
            const long long verts = integer(r, "vertices", 1, where);
            if (verts >= 0 && elements >= 0 && elements != verts) {
                fail(where, "elements is not the model's vertices");
            }
        } else if (!routine.empty() && tris >= 0 && elements >= 0 && elements != tris) {
            fail(where, "elements is not the model's triangles");
        }
    }

    /* Every routine x variant x regime row of MODEL once: the kernel
     * routines for every variant this CPU runs, appendices A and B for
     * c_ref; and the model's sizes. */
    void coverage(const json &doc, const std::string &model, long long triangles, long long edges) {
        if (!doc.is_object() || !doc.contains("results") || !doc.at("results").is_array()) {
            return; /* reported by document() */
        }
        std::set<std::tuple<std::string, std::string, std::string>> seen;
        for (const json &r : doc.at("results")) {
            if (!r.is_object() || r.value("model", "") != model) {
                continue;
            }
            const auto key = std::make_tuple(r.value("routine", ""), r.value("variant", ""),
                                             r.value("regime", ""));
            if (!seen.insert(key).second) {
                fail(model, "row " + std::get<0>(key) + " " + std::get<1>(key) + " " +
                                std::get<2>(key) + " appears twice");
            }
            if (r.value("triangles", -1LL) != triangles || r.value("edges", -1LL) != edges) {
                fail(model, "a row gives other sizes than " + std::to_string(triangles) +
                                " triangles and " + std::to_string(edges) + " edges");
            }
        }
        for (const std::string &regime : kRegimes) {
            for (const std::string &routine : kKernelRoutines) {
                for (const std::string &variant : variant_names(true)) {
                    if (!seen.count(std::make_tuple(routine, variant, regime))) {
                        fail(model, "no row " + routine + " " + variant + " " + regime);
                    }
                }
            }
            for (const std::string &routine : kCalculateRoutines) {
                for (const std::string &variant : facing_variant_names(true)) {
                    if (!seen.count(std::make_tuple(routine, variant, regime))) {
                        fail(model, "no row " + routine + " " + variant + " " + regime);
                    }
                }
            }
            for (const std::string &routine : kPipelineRoutines) {
                for (const std::string &variant : variant_names(true)) {
                    if (!seen.count(std::make_tuple(routine, variant, regime))) {
                        fail(model, "no row " + routine + " " + variant + " " + regime);
                    }
                }
            }
            for (const std::string &routine : kRoutines) {
                if (!seen.count(std::make_tuple(routine, std::string("planned"), regime))) {
                    fail(model, "no row " + routine + " planned " + regime);
                }
            }
        }
    }
};

std::vector<std::string> validate(const json &doc) {
    Validator v;
    v.document(doc);
    v.coverage(doc, "character_1344.glb", 1344, 2016);
    return v.errors;
}

std::string join(const std::vector<std::string> &lines) {
    std::string s;
    for (const std::string &l : lines) {
        s += l + "\n";
    }
    return s;
}

bool mentions(const std::vector<std::string> &errors, const std::string &what) {
    for (const std::string &e : errors) {
        if (e.find(what) != std::string::npos) {
            return true;
        }
    }
    return false;
}

std::string slurp(const std::string &path) {
    std::ifstream f(path, std::ios::binary);
    std::ostringstream s;
    s << f.rdbuf();
    return s.str();
}

/* Runs the shell command, returns its exit status (-1 if it did not exit). */
int run(const std::string &command) {
    const int st = std::system(command.c_str());
    return st != -1 && WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

/* One `bench --quick --json FILE` run for the whole suite (a second or a
 * few under the sanitizers), and a short one with --json - . */
class BenchJson : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        char tmpl[] = "/tmp/sv_bench_json_XXXXXX";
        const char *d = mkdtemp(tmpl);
        ASSERT_NE(d, nullptr);
        dir_ = d;
        const std::string exe = SV_SHADOWVOL_EXE;
        status_ = run("'" + exe + "' bench --quick --json '" + dir_ + "/bench.json' > '" + dir_ +
                      "/table.txt' 2> '" + dir_ + "/stderr.txt'");
        table_ = slurp(dir_ + "/table.txt");
        text_ = slurp(dir_ + "/bench.json");
        stdoutStatus_ = run("'" + exe +
                            "' bench --quick --routine count_facing --regime fixed --json - > '" +
                            dir_ + "/stdout.json' 2> '" + dir_ + "/stderr_table.txt'");
        stdoutJson_ = slurp(dir_ + "/stdout.json");
        stderrTable_ = slurp(dir_ + "/stderr_table.txt");
        limitsStatus_ = run("'" + exe +
                            "' bench --quick --limits --regime moving --routine count_facing "
                            "--routine create_shadow_volume --json '" +
                            dir_ + "/limits.json' > /dev/null 2> '" + dir_ + "/stderr_limits.txt'");
        limitsJson_ = slurp(dir_ + "/limits.json");
    }
    static void TearDownTestSuite() {
        if (!dir_.empty()) {
            run("rm -rf '" + dir_ + "'");
        }
    }
    /* The document, or a failed assertion. */
    static json document() {
        json doc = json::parse(text_, nullptr, false);
        EXPECT_FALSE(doc.is_discarded()) << "not JSON:\n" << text_.substr(0, 2000);
        return doc;
    }

    static std::string dir_, table_, text_, stdoutJson_, stderrTable_, limitsJson_;
    static int status_, stdoutStatus_, limitsStatus_;
};
std::string BenchJson::dir_, BenchJson::table_, BenchJson::text_, BenchJson::stdoutJson_,
    BenchJson::stderrTable_, BenchJson::limitsJson_;
int BenchJson::status_ = -1, BenchJson::stdoutStatus_ = -1, BenchJson::limitsStatus_ = -1;

TEST_F(BenchJson, QuickRunExitsZeroAndPrintsTheTable) {
    EXPECT_EQ(status_, 0) << slurp(dir_ + "/stderr.txt");
    EXPECT_NE(table_.find("regime: moving light"), std::string::npos);
    EXPECT_NE(table_.find("regime: fixed light"), std::string::npos);
}

TEST_F(BenchJson, DocumentMatchesTheSchemaAndCoversEveryRow) {
    const json doc = document();
    const std::vector<std::string> errors = validate(doc);
    EXPECT_TRUE(errors.empty()) << join(errors);
    /* 6 kernel routines and 2 pipelines x the runnable kernel variants + 2
     * calculate_* routines x the runnable A/B variants + the planned
     * variant on all 10 + planned_kernels on the 2 pipelines, in 2
     * regimes. */
    const size_t want = 2 * (8 * variant_names(true).size() +
                             2 * facing_variant_names(true).size() + 10 + 2);
    EXPECT_EQ(doc.at("results").size(), want);
}

/* "plans": the plan the planned rows ran, one per model, naming a variant
 * the table has for every routine of the planner. */
/* cpu.model_key: the wisdom file's key of this CPU (vendor, family/model/
 * stepping, ISA level, brand), which tells CPU generations apart where
 * the brand string does not. */
TEST_F(BenchJson, CpuCarriesItsModelKey) {
    const json doc = document();
    char key[256];
    EXPECT_EQ(doc.at("cpu").value("model_key", ""), std::string(sv_cpu_model_key(key, sizeof key)));
    unsigned f = 0, m = 0, st = 0;
    const std::string k = doc.at("cpu").value("model_key", "");
    ASSERT_NE(k.find(' '), std::string::npos) << k;
    EXPECT_EQ(std::sscanf(k.c_str() + k.find(' ') + 1, "%u/%u/%u", &f, &m, &st), 3) << k;
}

TEST_F(BenchJson, PlansNameThePlannedRowsKernels) {
    const json doc = document();
    ASSERT_TRUE(doc.contains("plans") && doc.at("plans").is_array());
    ASSERT_EQ(doc.at("plans").size(), 1u);
    const json &p = doc.at("plans")[0];
    EXPECT_EQ(p.value("model", ""), "character_1344.glb");
    EXPECT_EQ(p.value("triangles", 0), 1344);
    EXPECT_EQ(p.value("size_class", -1), sv_size_class(1344));
    EXPECT_EQ(p.value("class_triangles", 0), sv_size_class_triangles(sv_size_class(1344)));
    const std::string source = p.value("source", "");
    EXPECT_TRUE(source == "measured" || source == "wisdom" || source == "built-in") << source;
    const std::set<std::string> names = all_variant_names();
    ASSERT_TRUE(p.contains("variants") && p.at("variants").is_object());
    EXPECT_EQ(p.at("variants").size(), (size_t)SV_NUM_ROUTINES);
    for (int r = 0; r < SV_NUM_ROUTINES; r++) {
        const char *routine = sv_routine_name((sv_routine)r);
        ASSERT_TRUE(p.at("variants").contains(routine)) << routine;
        EXPECT_TRUE(names.count(p.at("variants").at(routine).get<std::string>())) << routine;
    }
}

TEST_F(BenchJson, ModelsReportTheLightsActualRatios) {
    const json doc = document();
    ASSERT_TRUE(doc.contains("models") && doc.at("models").is_array());
    ASSERT_EQ(doc.at("models").size(), 1u);
    const json &m = doc.at("models")[0];
    EXPECT_EQ(m.value("model", ""), "character_1344.glb");
    EXPECT_EQ(m.value("vertices", 0), 674);
    EXPECT_EQ(m.value("lights", 0), 64);
    for (const char *ratio : {"facing_ratio", "silhouette_ratio", "culled_ratio"}) {
        ASSERT_TRUE(m.contains(ratio) && m.at(ratio).is_object()) << ratio;
        const json &r = m.at(ratio);
        const double lo = r.value("min", -1.0), mean = r.value("mean", -1.0),
                     hi = r.value("max", -1.0);
        EXPECT_TRUE(0 < lo && lo <= mean && mean <= hi && hi < 1) << ratio << ": " << r.dump();
    }
    /* The search aims at 50% facing: every light it keeps is near it. */
    EXPECT_NEAR(m.at("facing_ratio").value("mean", 0.0), 0.5, 0.05);
    EXPECT_NEAR(m.at("culled_ratio").value("mean", 0.0), 0.25, 0.02);
}

TEST_F(BenchJson, DashWritesTheDocumentToStdoutAndTheTableToStderr) {
    EXPECT_EQ(stdoutStatus_, 0) << stderrTable_;
    const json doc = json::parse(stdoutJson_, nullptr, false);
    ASSERT_FALSE(doc.is_discarded()) << "stdout is not JSON:\n" << stdoutJson_.substr(0, 2000);
    EXPECT_EQ(doc.value("schema", ""), kSchema);
    ASSERT_TRUE(doc.contains("results") && doc.at("results").is_array());
    EXPECT_EQ(doc.at("results").size(), variant_names(true).size() + 1) << "and planned";
    Validator v;
    v.document(doc);
    EXPECT_TRUE(v.errors.empty()) << join(v.errors);
    EXPECT_NE(stderrTable_.find("regime: fixed light"), std::string::npos);
}

/* --limits adds "limits": the machine's rates and a floor per routine
 * measured with the moving light (machine_limits.h); without it there is
 * no such field. Nothing about the figures but their sense is asserted. */
TEST_F(BenchJson, LimitsReportTheRatesAndAFloorPerRoutine) {
    EXPECT_FALSE(document().contains("limits")) << "a run without --limits has \"limits\"";
    ASSERT_EQ(limitsStatus_, 0) << slurp(dir_ + "/stderr_limits.txt");
    const json doc = json::parse(limitsJson_, nullptr, false);
    ASSERT_FALSE(doc.is_discarded()) << "not JSON:\n" << limitsJson_.substr(0, 2000);
    Validator v;
    v.document(doc);
    EXPECT_TRUE(v.errors.empty()) << join(v.errors);
    ASSERT_TRUE(doc.contains("limits") && doc.at("limits").is_object());
    const json &l = doc.at("limits");
    const std::string vec = l.value("vector", "");
    ASSERT_TRUE(vec == "zmm" || vec == "ymm" || vec == "none") << l.dump();
    EXPECT_GT(l.value("scalar_loads_per_tick", 0.0), 0.0) << l.dump();
    /* The core's clock over the TSC's: a core between a tenth and ten
     * times its TSC's rate (a dependent add is one cycle on every x86
     * core; a chain measured as free would read as infinite). */
    const double cyclesPerTick = l.value("core_cycles_per_tick", 0.0);
    EXPECT_GT(cyclesPerTick, 0.1) << l.dump();
    EXPECT_LT(cyclesPerTick, 10.0) << l.dump();
    ASSERT_TRUE(l.contains("floors") && l.at("floors").is_array()) << l.dump();
    if (vec == "none") {
        EXPECT_TRUE(l.at("floors").empty()) << "floors without the vector rates";
        return;
    }
    for (const char *rate : {"gather_lanes_per_tick", "l1_load_bytes_per_tick",
                             "l2_load_bytes_per_tick", "store_bytes_per_tick"}) {
        EXPECT_GT(l.value(rate, 0.0), 0.0) << rate;
    }
    EXPECT_GE(l.value("l2_buffer_bytes", 0ull), 65536ull);
    std::set<std::string> routines;
    for (const json &f : l.at("floors")) {
        EXPECT_EQ(f.value("model", ""), "character_1344.glb");
        routines.insert(f.value("routine", ""));
        const double floor = f.value("floor_ticks", -1.0), load = f.value("load_port_ticks", -1.0),
                     lookup = f.value("lookup_ticks", -1.0),
                     store = f.value("store_port_ticks", -1.0);
        EXPECT_GT(floor, 0.0) << f.dump();
        EXPECT_TRUE(lookup >= 0 && lookup <= load) << f.dump();
        EXPECT_TRUE(store >= 0 && floor == std::max(load, store)) << f.dump();
        const double streaming = f.value("streaming_floor_ticks", -1.0);
        EXPECT_TRUE(streaming > 0 && streaming <= floor) << f.dump();
    }
    EXPECT_EQ(routines, (std::set<std::string>{"count_facing", "create_shadow_volume"}));
}

/* The validator can fail: each broken copy of a good document is
 * rejected, for the reason broken into it. */
TEST_F(BenchJson, ValidatorRejectsBrokenDocuments) {
    const json good = document();
    ASSERT_TRUE(validate(good).empty());
    struct Breakage {
        const char *what;
        void (*breakIt)(json &);
        const char *reason;
    };
    const Breakage cases[] = {
        {"a row without checked", [](json &d) { d["results"][0].erase("checked"); },
         "\"checked\" is missing"},
        {"ticks as a string",
         [](json &d) { d["results"][0]["ticks_min"] = d["results"][0]["ticks_min"].dump(); },
         "\"ticks_min\" is not a finite number"},
        {"a row that failed its check", [](json &d) { d["results"][3]["checked"] = false; },
         "\"checked\" is false"},
        {"another schema", [](json &d) { d["schema"] = "shadowvol-bench/2"; }, "schema is not"},
        {"no schema", [](json &d) { d.erase("schema"); }, "no \"schema\""},
        {"isa as a string", [](json &d) { d["cpu"]["isa"] = "sse2 avx2"; },
         "\"isa\" is missing or not an array"},
        {"tsc_hz as null", [](json &d) { d["cpu"]["tsc_hz"] = nullptr; },
         "\"tsc_hz\" is not a finite number"},
        {"an unknown routine", [](json &d) { d["results"][0]["routine"] = "count_faces"; },
         "not an allowed name"},
        {"an unknown regime", [](json &d) { d["results"][0]["regime"] = "hot"; },
         "not an allowed name"},
        {"median below min",
         [](json &d) {
             json &r = d["results"][0];
             r["ticks_median"] = r["ticks_min"].get<double>() - 1;
         },
         "ticks_median is below ticks_min"},
        {"negative ticks", [](json &d) { d["results"][1]["ticks_min"] = -5; },
         "\"ticks_min\" is not a finite number >= 0"},
        {"wrong elements", [](json &d) { d["results"][2]["elements"] = 1343; }, "elements is not"},
        {"elements as a float", [](json &d) { d["results"][2]["elements"] = 1344.5; },
         "\"elements\" is not a whole number"},
        {"a row missing", [](json &d) { d["results"].erase(d["results"].begin() + 5); }, "no row"},
        {"a row twice", [](json &d) { d["results"].push_back(d["results"][0]); }, "appears twice"},
        {"other sizes", [](json &d) { d["results"][4]["triangles"] = 1000; }, "other sizes"},
        {"results not an array", [](json &d) { d["results"] = json::object(); },
         "\"results\" is missing"},
    };
    for (const Breakage &c : cases) {
        json broken = good;
        c.breakIt(broken);
        const std::vector<std::string> errors = validate(broken);
        EXPECT_FALSE(errors.empty()) << c.what << ": accepted";
        EXPECT_TRUE(mentions(errors, c.reason))
            << c.what << ": rejected, but not for \"" << c.reason << "\":\n"
            << join(errors);
    }
}

} // namespace
