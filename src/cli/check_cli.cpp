/*
 * shadowvol check: one line per routine and variant (ok, FAILED with the
 * first failing case, or skipped with the reason), a summary line, and
 * the seed, so that a failure is replayed with --seed (the inputs of a
 * routine depend on the seed and the routine only, not on which variants
 * or routines run). The checks are src/check/routine_checks.h's.
 *
 * Exit status: 0 every line ok or skipped; 1 a check failed; 2 bad
 * arguments.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "check_cli.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "cli_args.h"
#include "shadowvol_plan.h"
#include "routine_bench.h"
#include "routine_checks.h"

namespace svcli {

namespace {

std::string joined(const std::vector<std::string> &names) {
    std::string s;
    for (const std::string &n : names) s += (s.empty() ? "" : " ") + n;
    return s;
}

std::vector<std::string> variant_names(const std::vector<svcheck::Variant> &table) {
    std::vector<std::string> n;
    n.reserve(table.size());
    for (const svcheck::Variant &v : table) n.push_back(v.name);
    return n;
}

std::vector<std::string> routine_names() {
    std::vector<std::string> n;
    for (svcheck::Routine r : svcheck::all_routines()) n.push_back(svcheck::routine_name(r));
    return n;
}

// The default seed: the clock, so every run draws new inputs (printed, so
// any run can be replayed).
uint64_t clock_seed() {
    const auto t = std::chrono::system_clock::now().time_since_epoch();
    return (uint64_t)std::chrono::duration_cast<std::chrono::microseconds>(t).count();
}

} // namespace

void check_usage(FILE *out) {
    const std::vector<svcheck::Variant> table = svcheck::library_variants();
    std::fprintf(out,
                 "usage: shadowvol check [--variant V]... [--function F]... [--seed S] [--bench]\n"
                 "  Runs every routine of every variant this CPU runs against the paper's C\n"
                 "  (c_ref) on seeded random inputs: every length 0..80 and a few thousand,\n"
                 "  every offset the variant's alignment allows, none / all / half / random\n"
                 "  facing, cull bits on every plane. Each call goes through the ABI checker\n"
                 "  where this build has one; outputs must equal c_ref's byte for byte and\n"
                 "  nothing past the documented bound may change. One line per routine and\n"
                 "  variant: ok, FAILED (the first failing case), or skipped (the reason).\n"
                 "  --variant V    check variant V only (repeatable):\n"
                 "                 %s\n"
                 "  --function F   check routine F only (repeatable):\n"
                 "                 %s\n"
                 "  --seed S       the inputs' seed (default: from the clock; printed, so a\n"
                 "                 failure is replayed with --seed S)\n"
                 "  --bench        also median TSC ticks per call on a 1344-triangle input\n"
                 "                 (the bundled character's size) and the speed-up over c_ref;\n"
                 "                 a quick look: 'shadowvol bench' is the measurement\n"
                 "exit status: 0 all ok (or skipped), 1 a check failed, 2 bad arguments\n",
                 joined(variant_names(table)).c_str(), joined(routine_names()).c_str());
}

namespace {

// What "planned" is: each size class's plan source ("built-in",
// "wisdom"), as sv_plan_for gives them now.
std::string plan_sources() {
    std::string s;
    for (int c = 0; c < SV_NUM_SIZE_CLASSES; c++) {
        const sv_plan *p = sv_plan_for(sv_size_class_triangles(c), SV_PLAN_ESTIMATE);
        s += (c ? ", " : "") + std::string("class ") + std::to_string(c) + " " + p->source;
    }
    return s;
}

} // namespace

int check_main(int argc, char **argv) {
    // "planned" checks the plans a program of this user gets: the wisdom
    // file's for this CPU where it has them (as `shadowvol bench` reads it),
    // else the built-in ones. Nothing is measured.
    char wisdom[1024];
    sv_wisdom_load(sv_wisdom_default_path(wisdom, sizeof wisdom));
    const std::vector<svcheck::Variant> table = svcheck::library_variants();
    std::vector<std::string> want_variants;
    std::vector<svcheck::Routine> routines;
    uint64_t seed = 0;
    bool seeded = false, bench = false;
    try {
        ArgReader a(argc, argv);
        while (a.next()) {
            if (a.is_flag("--help") || a.is_flag("-h")) {
                check_usage(stdout);
                return 0;
            } else if (a.is("--variant")) {
                const std::string v = a.value();
                bool known = false;
                for (const svcheck::Variant &t : table) known = known || t.name == v;
                if (!known) {
                    usage_error("unknown variant '" + quoted(v) +
                                "' (known: " + joined(variant_names(table)) + ")");
                }
                want_variants.push_back(v);
            } else if (a.is("--function")) {
                const std::string f = a.value();
                svcheck::Routine r;
                if (!svcheck::routine_by_name(f, &r)) {
                    usage_error("unknown function '" + quoted(f) +
                                "' (known: " + joined(routine_names()) + ")");
                }
                // (named twice: checked once)
                if (std::find(routines.begin(), routines.end(), r) == routines.end())
                    routines.push_back(r);
            } else if (a.is("--seed")) {
                seed = a.seed();
                seeded = true;
            } else if (a.is_flag("--bench")) {
                bench = true;
            } else {
                usage_error("unknown argument '" + quoted(a.arg()) + "'");
            }
        }
    } catch (const UsageError &e) {
        std::fprintf(stderr, "shadowvol check: %s\nTry 'shadowvol check --help'.\n",
                     e.message.c_str());
        return 2;
    }
    if (routines.empty()) routines = svcheck::all_routines();
    std::vector<svcheck::Variant> chosen;
    for (const svcheck::Variant &v : table) {
        bool take = want_variants.empty();
        for (const std::string &w : want_variants) take = take || w == v.name;
        if (take) chosen.push_back(v);
    }
    if (!seeded) seed = clock_seed();

    char isa[160];
    std::printf("seed      %llu (replay: --seed %llu)\n", (unsigned long long)seed,
                (unsigned long long)seed);
    std::printf("cpu       %s (%s)\n", sv_isa_level_name(),
                sv_isa_names(sv_cpu_isa(), isa, sizeof isa));
    std::printf("abi       %s\n", svcheck::abi_checker_summary().c_str());
    std::printf("planned   %s\n", plan_sources().c_str());
    if (bench) {
        std::printf("bench     median TSC ticks per call, %d triangles; speed-up over c_ref\n",
                    svcheck::BenchWorkload::kTriangles);
    }

    std::unique_ptr<svcheck::BenchWorkload> work;
    svcheck::Variant ref;
    if (bench) {
        work.reset(new svcheck::BenchWorkload(seed));
        ref = svcheck::make_variant("c_ref", sv_facing_variant_by_name("c_ref"),
                                    sv_variant_by_name("c_ref"));
    }
    int ok = 0, failed = 0, skipped = 0;
    std::string first_failed;
    for (svcheck::Routine r : routines) {
        const std::vector<svcheck::Result> results = svcheck::check_routine(r, chosen, seed);
        const double ref_ticks =
            bench ? work->ticks(r, ref.for_triangles(svcheck::BenchWorkload::kTriangles)) : 0;
        for (size_t i = 0; i < results.size(); i++) {
            const svcheck::Result &res = results[i];
            std::string status;
            if (res.status == svcheck::Result::ok) {
                ok++;
                status = "ok (" + std::to_string(res.cases) + " cases)";
            } else if (res.status == svcheck::Result::skipped) {
                skipped++;
                status = "skipped (" + res.detail + ")";
            } else {
                failed++;
                status = "FAILED (" + std::to_string(res.failures) + " of " +
                         std::to_string(res.cases) + " cases) first: " + res.detail;
                if (first_failed.empty()) {
                    first_failed = std::string("--variant ") + res.variant + " --function " +
                                   svcheck::routine_name(r);
                }
            }
            std::string timing;
            if (bench && res.status != svcheck::Result::skipped) {
                const svcheck::Variant *v = nullptr;
                for (const svcheck::Variant &c : chosen) v = c.name == res.variant ? &c : v;
                // c_ref's row is the reference's own timing (one measurement,
                // so its ratio is 1.00 and not the noise of two).
                const double t =
                    res.variant == "c_ref"
                        ? ref_ticks
                        : work->ticks(r, v->for_triangles(svcheck::BenchWorkload::kTriangles));
                char buf[64];
                std::snprintf(buf, sizeof buf, "%10.0f ticks %6.2fx  ", t,
                              t > 0 ? ref_ticks / t : 0.0);
                timing = buf;
            } else if (bench) {
                timing = std::string(33, ' ');
            }
            std::printf("%-24s %-13s %s%s\n", svcheck::routine_name(r), res.variant.c_str(),
                        timing.c_str(), status.c_str());
            std::fflush(stdout);
        }
    }
    std::printf("summary   %d ok, %d failed, %d skipped\n", ok, failed, skipped);
    if (ok + failed == 0 && skipped == 0) {
        std::fprintf(stderr,
                     "shadowvol check: the named variants have none of the named routines\n");
        return 2;
    }
    if (failed) {
        std::printf("replay    shadowvol check --seed %llu %s\n", (unsigned long long)seed,
                    first_failed.c_str());
        return 1;
    }
    return 0;
}

} // namespace svcli
