/*
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "scaling.h"

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <new>
#include <system_error>

#include "model_gen.h"
#include "model_list.h"
#include "model_workload.h"
#include "shadowvol_mesh.h"
#include "timer.h"

namespace svbench {

namespace fs = std::filesystem;

namespace {

/* The workload's arrays, dropped once its table is measured: the reports
 * read only its counts and the lights' counts. */
void release_arrays(Workload &w) {
    w.positions = AlignedArray<Vec4>();
    w.planes = AlignedArray<Plane>();
    w.indices = AlignedArray<int>();
    w.silEdges = AlignedArray<SilEdge>();
    for (Light &l : w.lights) {
        l.facing = AlignedArray<uint8_t>();
        l.cullBits = AlignedArray<uint8_t>();
    }
}

} // namespace

Workload generated_surface(const MeshSpec &s) {
    try {
        const svgen::TriMesh mesh = svgen::build_character(s.subdivision);
        const sv::PreparedSurface prepared = sv::prepare_surface(mesh.positions.data(),
                                                                 mesh.num_vertices(),
                                                                 mesh.indices.data(),
                                                                 mesh.indices.size());
        Workload w = workload_from_surface(
            prepared, s.name,
            "the generated character (tools/generate_models), each quad subdivided " +
                std::to_string(s.subdivision) + " x " + std::to_string(s.subdivision));
        w.surfaces = 1;
        return w;
    } catch (const sv::PrepareError &e) {
        throw WorkloadError(s.name + ": " + e.what());
    } catch (const std::bad_alloc &) {
        throw WorkloadError(s.name + ": out of memory");
    }
}

const std::vector<Routine> &default_scaling_routines() {
    static const std::vector<Routine> r = {
        Routine::create_shadow_volume, Routine::calculate_facing,     Routine::count_facing,
        Routine::count_facing_cull,    Routine::create_sil_triangles, Routine::create_cap_triangles,
    };
    return r;
}

int scaling_lights(long triangles) {
    if (triangles <= kFullLightTriangles) {
        return kScalingLights;
    }
    return (int)std::max<long>(kMinScalingLights,
                               (long)kScalingLights * kFullLightTriangles / triangles);
}

int scaling_warmup(int runs, int rounds, const Workload &w) {
    const int perRound = (runs + rounds - 1) / rounds;
    const long cap = std::max<long>(kMinScalingWarmup, kWarmupTriangles / w.numTriangles);
    return (int)std::min<long>({w.numMoving, perRound, cap});
}

int scaling_runs(const ScalingOptions &o, long triangles) {
    const int base = o.runs ? o.runs : o.quick ? kQuickScalingRuns : kDefaultScalingRuns;
    const int least = std::min(base, o.quick ? kMinQuickScalingRuns : kMinScalingRuns);
    if (triangles <= kScalingReferenceTriangles) {
        return base;
    }
    return (int)std::max<long>(least, (long)base * kScalingReferenceTriangles / triangles);
}

std::vector<MeshSpec> scaling_meshes(const ScalingOptions &o, std::string *note) {
    std::vector<MeshSpec> specs;
    const int *first = o.quick ? std::begin(kQuickScalingSubdivisions)
                               : std::begin(kScalingSubdivisions);
    const int *last = o.quick ? std::end(kQuickScalingSubdivisions)
                              : std::end(kScalingSubdivisions);
    for (const int *n = first; n != last; n++) {
        MeshSpec s;
        s.generated = true;
        s.subdivision = *n;
        s.name = "character_" + std::to_string(kScalingReferenceTriangles * *n * *n);
        specs.push_back(s);
    }

    /* The user's --model files and folders (issue 17), after the generated
     * meshes; the run orders every mesh by its triangles. */
    std::vector<std::string> own;
    if (!o.models.empty()) {
        for (const ModelSpec &m : resolve_models(o.models, std::string(), std::string()).models) {
            MeshSpec s;
            s.path = m.path;
            s.name = fs::path(m.path).filename().string();
            own.push_back(m.path);
            specs.push_back(s);
        }
    }
    const std::string own_note = own.empty() ? std::string()
                                             : "; --model: " + std::to_string(own.size()) +
                                                   " file" + (own.size() == 1 ? "" : "s");

    std::error_code ec;
    const std::string &dir = o.sharedModels;
    if (dir.empty() || !fs::is_directory(dir, ec)) {
        *note = "real characters: none (" + (dir.empty() ? std::string("no folder given") : dir) +
                " does not exist; it holds the third-party glTF characters)" + own_note;
        return specs;
    }
    /* resolve_models lists a folder's glTF files, by name, and throws
     * ModelListError when it has none. */
    const ModelList real = resolve_models({dir}, std::string(), std::string());
    for (const ModelSpec &m : real.models) {
        if (std::find(own.begin(), own.end(), m.path) != own.end()) continue;
        MeshSpec s;
        s.path = m.path;
        s.name = fs::path(m.path).filename().string();
        specs.push_back(s);
    }
    const fs::path canon = fs::weakly_canonical(dir, ec);
    *note = "real characters: the " + std::to_string(real.models.size()) + " glTF files in " +
            (ec ? dir : canon.string()) + own_note;
    return specs;
}

Workload scaling_surface(const MeshSpec &s) {
    return s.generated ? generated_surface(s) : load_model_surface(s.path);
}

void light_scaling_workload(Workload &w, const ScalingOptions &o) {
    place_lights(w, o.targets, scaling_lights(w.numTriangles), o.seed, nullptr);
}

void measure_scaling_mesh(const ScalingRun &run, ScalingMesh &m) {
    const double t0 = monotonic_seconds();
    const ScalingOptions &so = run.options;
    TableOptions o;
    o.runs = m.runs = scaling_runs(so, m.workload.numTriangles);
    o.rounds = so.rounds;
    o.moving = true;
    o.fixed = false;
    o.batch = so.batch;
    o.routines = so.routines;
    o.variants = so.variants;
    o.progress = so.progress;
    o.warmup = scaling_warmup(o.runs, o.rounds, m.workload);
    m.table = run_cycle_table(o, run.machine, m.workload);
    release_arrays(m.workload);
    m.seconds += monotonic_seconds() - t0;
}

int failed_scaling_rows(const ScalingRun &run) {
    int n = 0;
    for (const ScalingMesh &m : run.meshes) {
        for (const Row &r : m.table.rows) {
            n += !r.ok;
        }
    }
    return n;
}

const Row *scaling_row(const ScalingMesh &m, Routine routine, const BenchVariant *variant) {
    for (const Row &r : m.table.rows) {
        if (r.routine == routine && (r.variant == variant || r.variant->origin == variant)) {
            return &r;
        }
    }
    return nullptr;
}

} // namespace svbench
