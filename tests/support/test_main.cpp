// The main of every test program: gtest's, except that a skip is a skip.
// Exit status: 1 a test failed, or no test ran (a filter that matches
// nothing proves nothing); 77 (ctest's SKIP_RETURN_CODE) the entry's
// condition is not met here, or a test skipped, or a variant of the
// entry's tier could not run, each named with its reason; 0 every test
// selected ran and passed. What an entry covers: tests/support/test_conditions.h.
//
// Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <set>
#include <string>
#include <vector>

#include "shadowvol.h"
#include "test_conditions.h"

namespace svtest {
namespace {

constexpr int kSkipped = 77;

// Calls of in_this_run() that let a variant of the entry's tier run.
int tier_variants_run = 0;

// The tests declared with SV_TIERED_TEST(_P), as Suite.Name.
std::set<std::string> &tiered_tests() {
    static std::set<std::string> s;
    return s;
}

// A test's Suite.Name: without the instantiation's prefix and the
// parameter's suffix.
std::string suite_dot_name(const char *suite, const char *name) {
    std::string s = suite, n = name;
    if (s.rfind('/') != std::string::npos) s = s.substr(s.rfind('/') + 1);
    if (n.find('/') != std::string::npos) n = n.substr(0, n.find('/'));
    return s + "." + n;
}

std::vector<std::string> &variants_not_run() {
    static std::vector<std::string> v;
    return v;
}

const char *env(const char *name) {
    const char *v = std::getenv(name);
    return v && *v ? v : nullptr;
}

// The ISA tiers, highest first: the name (a variant's name starts with it),
// the bit that puts a variant in the tier, and the bits the CPU needs for it.
struct Tier {
    const char *name;
    unsigned mark;
    unsigned needs;
};
constexpr Tier kTiers[] = {
    {"avx512vbmi", SV_ISA_AVX512_VBMI | SV_ISA_AVX512_VBMI2,
     SV_ISA_SSE2 | SV_ISA_AVX2 | SV_ISA_AVX512 | SV_ISA_AVX512_VBMI},
    {"avx512", SV_ISA_AVX512, SV_ISA_SSE2 | SV_ISA_AVX2 | SV_ISA_AVX512},
    {"avx2", SV_ISA_AVX2, SV_ISA_SSE2 | SV_ISA_AVX2},
};

const Tier *tier_named(const std::string &name) {
    for (const Tier &t : kTiers)
        if (name == t.name) return &t;
    return nullptr;
}

// A parameterised test's variant: the name after the last '/' when it names
// one (c_*, sse2*, avx2*, avx512*), and the tier and dispatch level its
// prefix names.
struct ParamVariant {
    std::string tier; // "" baseline
    unsigned level;   // SV_ISA_* bits dispatch must allow
};
bool param_variant(const std::string &test_name, ParamVariant &out) {
    const size_t slash = test_name.rfind('/');
    if (slash == std::string::npos) return false;
    const std::string p = test_name.substr(slash + 1);
    auto starts = [&](const char *s) { return p.compare(0, std::strlen(s), s) == 0; };
    for (const Tier &t : kTiers) {
        if (starts(t.name)) {
            out = {t.name, t.needs};
            return true;
        }
    }
    if (starts("sse2"))
        out = {"", SV_ISA_SSE2};
    else if (starts("c_"))
        out = {"", 0};
    else
        return false; // another parameter (a model set): every tier's entry
    return true;
}

// gtest's filter narrowed to this entry: the names of the tests it leaves
// out, as negative patterns appended to the user's filter.
void narrow_filter_to_this_entry() {
    const std::string tier = tier_of_this_run();
    const bool shared = shared_models_run();
    const unsigned allowed = sv_cpu_isa();
    const bool limited = sv_isa_limit_name() != nullptr;
    std::string out;
    ::testing::UnitTest *u = ::testing::UnitTest::GetInstance();
    for (int i = 0; i < u->total_test_suite_count(); i++) {
        const ::testing::TestSuite *s = u->GetTestSuite(i);
        for (int j = 0; j < s->total_test_count(); j++) {
            const ::testing::TestInfo *t = s->GetTestInfo(j);
            const std::string full = std::string(s->name()) + "." + t->name();
            bool keep = (full.find("SharedModels") != std::string::npos) == shared;
            ParamVariant pv;
            if (keep && param_variant(t->name(), pv)) {
                // Its tier's entry only; in an SV_ISA-limited entry, only
                // the variants dispatch may run there.
                keep = pv.tier == tier && (!limited || (pv.level & allowed) == pv.level);
            } else if (keep && !tier.empty()) {
                // A tier's entry: the tests that loop over variants alone.
                keep = tiered_tests().count(suite_dot_name(s->name(), t->name())) != 0;
            }
            if (!keep) out += ":" + full;
        }
    }
    if (out.empty()) return;
    std::string filter = GTEST_FLAG_GET(filter);
    filter += filter.find('-') == std::string::npos ? "-" + out.substr(1) : out;
    GTEST_FLAG_SET(filter, filter);
}

// Why this entry cannot run here, or "".
std::string entry_condition_unmet() {
    const char *tier = tier_of_this_run();
    if (*tier) {
        const Tier *t = tier_named(tier);
        if (!t)
            return std::string("SV_TEST_ISA=") + tier + " is no tier (avx2, avx512, avx512vbmi)";
        const unsigned need = t->needs;
        if ((sv_cpu_isa_detected() & need) != need) {
            char names[128];
            return std::string("this CPU lacks the ") + tier +
                   " tier (it has: " + sv_isa_names(sv_cpu_isa_detected(), names, sizeof names) +
                   ")";
        }
        if ((sv_cpu_isa() & need) != need)
            return std::string("the ISA limit SV_ISA=") + sv_isa_limit_name() + " holds the " +
                   tier + " tier down";
    }
    if (shared_models_run()) {
        struct stat st;
        const std::string dir = SV_SHARED_MODELS_DIR;
        if (stat(dir.c_str(), &st) != 0 || !S_ISDIR(st.st_mode))
            return "the real characters' folder " + dir + " is missing";
    }
    return "";
}

} // namespace

bool declare_tiered(const char *suite_dot_name) {
    tiered_tests().insert(suite_dot_name);
    return true;
}

const char *isa_tier(unsigned isa) {
    for (const Tier &t : kTiers)
        if (isa & t.mark) return t.name;
    return "";
}

std::string isa_missing(unsigned isa) {
    if ((isa & sv_cpu_isa()) == isa) return "";
    if ((isa & sv_cpu_isa_detected()) == isa && sv_isa_limit_name())
        return std::string("held down by the ISA limit (SV_ISA=") + sv_isa_limit_name() + ")";
    return "this CPU lacks its instruction set";
}

const char *tier_of_this_run() {
    const char *t = env("SV_TEST_ISA");
    return t ? t : "";
}

bool in_this_run(unsigned isa, const char *name) {
    // A loop over variants outside a test declared SV_TIERED_TEST would
    // never run in the tier entries: say so (a test of one variant, named
    // by it, is tier-filtered by its name instead).
    const ::testing::TestInfo *cur = ::testing::UnitTest::GetInstance()->current_test_info();
    ParamVariant own;
    if (cur && !param_variant(cur->name(), own) &&
        !tiered_tests().count(suite_dot_name(cur->test_suite_name(), cur->name()))) {
        static std::set<std::string> told;
        if (told.insert(suite_dot_name(cur->test_suite_name(), cur->name())).second)
            ADD_FAILURE()
                << "this test loops over variants (in_this_run): declare it with SV_TIERED_TEST "
                   "or SV_TIERED_TEST_P (tests/support/test_conditions.h) so that the tier entries "
                   "run it";
    }
    const char *tier = isa_tier(isa);
    if (*tier && std::strcmp(tier, tier_of_this_run()) != 0) return false;
    const std::string why = isa_missing(isa);
    if (why.empty()) {
        if (*tier) tier_variants_run++;
        return true;
    }
    if ((isa & sv_cpu_isa_detected()) == isa) return false; // held down by SV_ISA: out of scope
    variants_not_run().push_back(
        std::string(name) + " in " +
        (cur ? std::string(cur->test_suite_name()) + "." + cur->name() : "?") + ": " + why);
    return false;
}

bool shared_models_run() {
    const char *s = env("SV_TEST_SHARED_MODELS");
    return s && std::strcmp(s, "0") != 0;
}

std::string shared_models_dir() {
    const ::testing::TestInfo *t = ::testing::UnitTest::GetInstance()->current_test_info();
    if (!t || (std::string(t->test_suite_name()) + "." + t->name()).find("SharedModels") ==
                  std::string::npos)
        ADD_FAILURE()
            << "only a test named *SharedModels* may read the shared models (its name puts "
               "it in the shared-models ctest entry)";
    return SV_SHARED_MODELS_DIR;
}

} // namespace svtest

int main(int argc, char **argv) {
    ::testing::InitGoogleTest(&argc, argv);
    if (GTEST_FLAG_GET(list_tests)) return RUN_ALL_TESTS();
    const std::string unmet = svtest::entry_condition_unmet();
    if (!unmet.empty()) {
        std::printf("[  SKIPPED ] the whole entry: %s\n", unmet.c_str());
        return svtest::kSkipped;
    }
    svtest::narrow_filter_to_this_entry();
    if (RUN_ALL_TESTS() != 0) return 1;
    ::testing::UnitTest *u = ::testing::UnitTest::GetInstance();
    if (u->test_to_run_count() == 0) {
        std::printf(
            "[  FAILED  ] no test ran (filter %s): an entry that tests nothing cannot pass\n",
            GTEST_FLAG_GET(filter).c_str());
        return 1;
    }
    int skipped = 0;
    for (int i = 0; i < u->total_test_suite_count(); i++) {
        const ::testing::TestSuite *s = u->GetTestSuite(i);
        for (int j = 0; j < s->total_test_count(); j++) {
            const ::testing::TestInfo *t = s->GetTestInfo(j);
            svtest::ParamVariant pv;
            if (t->should_run() && t->result()->Passed() && svtest::param_variant(t->name(), pv) &&
                !pv.tier.empty() && pv.tier == svtest::tier_of_this_run())
                svtest::tier_variants_run++;
            if (!t->should_run() || !t->result()->Skipped()) continue;
            std::string why;
            for (int k = 0; k < t->result()->total_part_count(); k++) {
                const ::testing::TestPartResult &p = t->result()->GetTestPartResult(k);
                if (p.skipped()) why = p.message();
            }
            std::printf("[  SKIPPED ] %s.%s: %s\n", s->name(), t->name(), why.c_str());
            skipped++;
        }
    }
    if (*svtest::tier_of_this_run() && svtest::tier_variants_run == 0) {
        std::printf(
            "[  FAILED  ] SV_TEST_ISA=%s: no test here ran a variant of that tier (this program "
            "has none: the entry tests nothing of its own)\n",
            svtest::tier_of_this_run());
        return 1;
    }
    for (const std::string &v : svtest::variants_not_run())
        std::printf("[  SKIPPED ] variant %s\n", v.c_str());
    if (skipped || !svtest::variants_not_run().empty()) {
        std::printf("%d tests skipped, %zu variants not run: the entry counts as skipped\n",
                    skipped, svtest::variants_not_run().size());
        return svtest::kSkipped;
    }
    return 0;
}
