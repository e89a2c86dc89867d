/*
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "seed_bench.h"

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "header_lines.h"
#include "json_writer.h"
#include "model_workload.h"
#include "output_file.h"
#include "scene_presets.h"
#include "scaling.h"
#include "sysinfo.h"

namespace svbench {

namespace {

template <class Timer>
SeedTiming time_with(const SeedTimer &t, const std::function<void(int)> &run,
                     const std::function<std::string(int)> &check) {
    SeedTiming r;
    run(0); /* warm-up: caches, page faults of the output, the table's first touch */
    r.failure = check(0);
    if (!r.failure.empty()) {
        r.ok = false;
        return r;
    }
    std::vector<double> ticks;
    const double start = monotonic_seconds();
    for (int i = 1; i <= t.maxCalls; i++) {
        const uint64_t t0 = Timer::begin();
        run(i);
        const uint64_t t1 = Timer::end();
        const uint64_t d = t1 - t0;
        ticks.push_back(d > t.overhead ? (double)(d - t.overhead) : 0.0);
        r.failure = check(i);
        if (!r.failure.empty()) {
            r.ok = false;
            break;
        }
        if (i >= t.minCalls && monotonic_seconds() - start > t.budget) break;
    }
    r.calls = (int)ticks.size();
    if (!ticks.empty()) {
        std::sort(ticks.begin(), ticks.end());
        r.min = ticks.front();
        r.median = ticks[ticks.size() / 2];
    }
    return r;
}

} // namespace

SeedTimer make_seed_timer(TimerKind kind, bool quick) {
    SeedTimer t;
    t.kind = kind;
    t.overhead = measure_overhead(kind, quick ? 1000 : 5000).min;
    t.tscHz = estimate_tsc_hz(0.05);
    t.budget = quick ? 0.02 : 0.2;
    t.minCalls = quick ? 2 : 5;
    return t;
}

SeedTiming time_seed_row(const SeedTimer &t, const std::function<void(int)> &run,
                         const std::function<std::string(int)> &check) {
    switch (t.kind) {
    case TimerKind::rdtscp: return time_with<TscRdtscp>(t, run, check);
    case TimerKind::cpuid: return time_with<TscCpuid>(t, run, check);
    case TimerKind::lfence: return time_with<TscLfence>(t, run, check);
    }
    return SeedTiming{};
}

SeedMesh generated_seed_mesh(int n, const std::string &note) {
    MeshSpec spec;
    spec.generated = true;
    spec.subdivision = n;
    spec.name = "character_" + std::to_string(1344 * n * n);
    SeedMesh m;
    m.w = generated_surface(spec);
    m.name = spec.name + (note.empty() ? "" : " (" + note + ")");
    m.source = m.w.source;
    return m;
}

SeedMesh loaded_seed_mesh(const std::string &path) {
    SeedMesh m;
    m.w = load_model_surface(path);
    m.name = m.w.name;
    m.source = path;
    return m;
}

void print_seed_header(FILE *out, const char *title, const SeedTimer &t, int pinnedCpu,
                       const char *runs) {
    std::fprintf(out, "%s\n", title);
    print_cpu_lines(out, pinnedCpu);
    std::fprintf(out,
                 "timer     %s, overhead %llu ticks subtracted; TSC %.3f GHz (ticks, not core "
                 "cycles)\n",
                 timer_name(t.kind), (unsigned long long)t.overhead, t.tscHz * 1e-9);
    std::fprintf(out, "build     %s, commit %s\n", build_flags().c_str(), git_commit().c_str());
    if (runs) {
        std::fprintf(out, "runs      %s\n", runs);
        return;
    }
    std::fprintf(out,
                 "runs      each row %.2f s of calls (at least %d, at most %d), min and median; "
                 "every call checked\n",
                 t.budget, t.minCalls, t.maxCalls);
}

void seed_json_header(JsonWriter &j, const char *schema, const SeedTimer &t) {
    j.key("schema");
    j.value(schema);
    j.key("cpu");
    j.value(cpu_model());
    j.key("isa");
    j.value(cpu_isa_flags());
    j.key("commit");
    j.value(git_commit());
    j.key("build");
    j.value(build_flags());
    j.key("timer");
    j.value(timer_name(t.kind));
    j.key("tsc_hz");
    j.value(t.tscHz);
    j.key("overhead_ticks");
    j.value((long long)t.overhead);
}

void seed_json_row(JsonWriter &j, const char *routine, const std::string &variant,
                   const SeedTiming &t) {
    j.key("routine");
    j.value(routine);
    j.key("variant");
    j.value(variant);
    j.key("calls");
    j.value(t.calls);
    j.key("median_ticks");
    j.value(t.median);
    j.key("min_ticks");
    j.value(t.min);
}

int run_seed_frame(const SeedCommand &cmd, const char *what,
                   const std::function<int(FILE *out, std::string *doc)> &body) {
    try {
        OutputFile json("--json", cmd.json);
        std::string doc;
        const int failed = body(json.is_stdout() ? stderr : stdout, &doc);
        if (json.wanted() && !json.write(doc)) {
            std::fprintf(stderr, "shadowvol bench: --json: cannot write %s: %s\n",
                         json.name().c_str(), std::strerror(errno));
            return 1;
        }
        if (failed) {
            std::fprintf(stderr, "shadowvol bench: %d %s row%s failed the check\n", failed, what,
                         failed == 1 ? "" : "s");
            return 1;
        }
        return 0;
    } catch (const OutputFileError &e) {
        std::fprintf(stderr, "shadowvol bench: %s\n", e.what());
        return 2;
    } catch (const WorkloadError &e) {
        std::fprintf(stderr, "shadowvol bench: %s\n", e.what());
        return 3;
    } catch (const std::exception &e) {
        std::fprintf(stderr, "shadowvol bench: internal error: %s\n", e.what());
        return 1;
    }
}

std::unique_ptr<ScenePreset> open_bench_preset(const SeedCommand &cmd, const std::string &name,
                                               double aspect) {
    try {
        return make_scene_preset(name, aspect, SV_MODELS_DIR, cmd.sharedModels, SV_DEMO_SCENE);
    } catch (const std::exception &e) {
        throw WorkloadError(std::string("--preset ") + name + ": " + e.what());
    }
}

} // namespace svbench
