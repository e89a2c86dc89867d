/*
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "scaling_cli.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "machine_limits.h"
#include "model_list.h"
#include "output_file.h"
#include "scaling_json.h"
#include "scaling_plot.h"
#include "scaling_report.h"
#include "working_set.h"

namespace svbench {

namespace {

constexpr int kExitCheckFailed = 1;
constexpr int kExitUsage = 2;
constexpr int kExitBadModel = 3;

/* Overhead measurements at start-up, as the cycle table takes them. */
constexpr int kOverheadTries = 5000;
constexpr int kQuickOverheadTries = 1000;
constexpr double kTscSeconds = 0.05;

/* A mesh before it is measured: a real character is loaded at once (so a
 * broken file fails before any timing, and its size is known for the
 * order); a generated one is built when its turn comes. */
struct Pending {
    MeshSpec spec;
    long triangles = 0;
    Workload surface; /* real characters only */
};

bool write_document(OutputFile &f, const std::string &doc, const char *option) {
    if (!f.wanted() || f.write(doc)) {
        return true;
    }
    std::fprintf(stderr, "shadowvol bench: %s: cannot write %s: %s\n", option, f.name().c_str(),
                 std::strerror(errno));
    return false;
}

} // namespace

int run_scaling(const ScalingCommand &cmd) {
    ScalingRun run;
    run.options = cmd.options;
    run.isaLimit = cmd.isaLimit;
    run.variantsChosen = cmd.variantsChosen;
    run.skipped = cmd.skipped;
    const ScalingOptions &o = run.options;

    try {
        OutputFile json("--json", cmd.json);
        OutputFile plot("--plot", cmd.plot);
        FILE *out = json.is_stdout() || plot.is_stdout() ? stderr : stdout;

        std::vector<Pending> pending;
        for (const MeshSpec &s : scaling_meshes(o, &run.realModels)) {
            Pending p;
            p.spec = s;
            if (s.generated) {
                p.triangles = (long)kScalingReferenceTriangles * s.subdivision * s.subdivision;
            } else {
                p.surface = scaling_surface(s);
                p.triangles = p.surface.numTriangles;
            }
            if (o.maxTriangles && p.triangles > o.maxTriangles) {
                run.leftOut.push_back(s.name + ": " + std::to_string(p.triangles) +
                                      " triangles, above --max-triangles " +
                                      std::to_string(o.maxTriangles));
                continue;
            }
            pending.push_back(std::move(p));
        }
        std::stable_sort(pending.begin(), pending.end(), [](const Pending &a, const Pending &b) {
            return a.triangles < b.triangles;
        });
        for (const Pending &p : pending) {
            ScalingMesh m;
            m.spec = p.spec;
            m.triangles = p.triangles;
            run.meshes.push_back(std::move(m));
        }

        run.machine = measure_machine(cmd.timer, cmd.timerAuto,
                                      o.quick ? kQuickOverheadTries : kOverheadTries, kTscSeconds);
        print_scaling_header(out, run);
        for (size_t i = 0; i < run.meshes.size(); i++) {
            ScalingMesh &m = run.meshes[i];
            const double t0 = monotonic_seconds();
            m.workload = m.spec.generated ? scaling_surface(m.spec) : std::move(pending[i].surface);
            if (m.workload.numTriangles != m.triangles) {
                throw std::logic_error(
                    m.spec.name + " has " + std::to_string(m.workload.numTriangles) +
                    " triangles, not the " + std::to_string(m.triangles) + " expected");
            }
            light_scaling_workload(m.workload, o);
            m.seconds = monotonic_seconds() - t0;
            measure_scaling_mesh(run, m);
            print_scaling_mesh(out, m, i == 0);
        }
        if (!run.meshes.empty() &&
            working_set_bytes(Routine::pipeline, run.meshes.back().workload) > 32.0 * 1048576) {
            run.memoryLoadBytes = measure_memory_load_rate();
        }
        print_scaling_tables(out, run);

        const bool written = write_document(json, scaling_json(run), "--json") &&
                             write_document(plot, scaling_svg(run), "--plot");
        if (!written) {
            return kExitCheckFailed;
        }
        if (plot.wanted() && !plot.is_stdout()) {
            std::fprintf(out, "\nplot      %s\n", plot.name().c_str());
        }
        if (json.wanted() && !json.is_stdout()) {
            std::fprintf(out, "%sjson      %s\n", plot.wanted() && !plot.is_stdout() ? "" : "\n",
                         json.name().c_str());
        }
    } catch (const OutputFileError &e) {
        std::fprintf(stderr, "shadowvol bench: %s\nTry 'shadowvol bench --help'.\n", e.what());
        return kExitUsage;
    } catch (const ModelListError &e) {
        std::fprintf(stderr, "shadowvol bench: %s\n", e.what());
        return kExitBadModel;
    } catch (const WorkloadError &e) {
        std::fprintf(stderr, "shadowvol bench: %s\n", e.what());
        return kExitBadModel;
    } catch (const std::exception &e) {
        std::fprintf(stderr, "shadowvol bench: internal error: %s\n", e.what());
        return kExitCheckFailed;
    }

    const int failed = failed_scaling_rows(run);
    if (failed) {
        std::fprintf(stderr, "shadowvol bench: %d row%s failed the check against the reference\n",
                     failed, failed == 1 ? "" : "s");
        return kExitCheckFailed;
    }
    return 0;
}

} // namespace svbench
