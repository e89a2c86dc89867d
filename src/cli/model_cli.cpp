/*
 * `shadowvol inspect MODEL` and `shadowvol verify MODEL`: what preparation
 * finds in a glTF model, and the 3D proof that the shadow volumes built from
 * it are right (shadowvol_verify.h). One surface per mesh instance of the
 * scene (all primitives of the mesh merged, in world space).
 *
 * Exit status: 0 done (verify: every check passed); 1 a check failed;
 * 2 bad arguments; 3 the model could not be loaded or prepared, or is
 * larger than the limits (the message on stderr names the file and the
 * problem); 4 (verify) the check could not decide (the reason is printed).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "model_cli.h"

#include <algorithm>
#include <chrono>
#include <functional>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include <unistd.h>

#include "cli_args.h"
#include "model_load.h"
#include "shadowvol_gltf.h"
#include "shadowvol_casters.h"
#include "shadowvol_mesh.h"
#include "shadowvol_verify.h"

namespace svcli {

namespace {

constexpr int kExitCheckFailed = 1;
constexpr int kExitUsage = 2;
constexpr int kExitBadModel = 3;
constexpr int kExitUndecided = 4;

/* verify's memory, estimated before it starts: per triangle of the largest
 * surface (measured: 6.6 GB for a 10M-triangle grid), and its time per
 * triangle, light and variant (77 s for that grid with 2 lights). */
constexpr double kVerifyBytesPerTriangle = 700.0;
constexpr double kVerifySecondsPerTriangleLight = 4e-6;
constexpr long long kDefaultVerifyMaxMemoryMb = 8192;

/* --max-memory SIZE: a whole number of bytes with an optional K, M or G
 * (powers of 1024); plain numbers are megabytes. */
long long memory_size(ArgReader &a) {
    const std::string v = a.value();
    std::size_t digits = 0;
    while (digits < v.size() && v[digits] >= '0' && v[digits] <= '9') digits++;
    const std::string unit = v.substr(digits);
    long long shift = unit.empty() || unit == "M" ? 20 : unit == "K" ? 10 : unit == "G" ? 30 : -1;
    if (digits == 0 || digits > 12 || shift < 0) {
        usage_error("--max-memory needs a size like 512K, 800M (or 800), 8G; not '" + quoted(v) +
                    "'");
    }
    return std::stoll(v.substr(0, digits)) << shift;
}
bool is_closed(const sv::PrepareReport &r) {
    return r.triangles > 0 && r.boundary_edges == 0 && r.non_manifold_edges == 0 &&
           r.same_direction_edges == 0;
}

void add_report(sv::PrepareReport &t, const sv::PrepareReport &r) {
    t.vertices_in += r.vertices_in;
    t.triangles_in += r.triangles_in;
    t.degenerate_dropped += r.degenerate_dropped;
    t.triangles += r.triangles;
    t.welded_vertices += r.welded_vertices;
    t.zero_normal_triangles += r.zero_normal_triangles;
    t.edges += r.edges;
    t.boundary_edges += r.boundary_edges;
    t.manifold_edges += r.manifold_edges;
    t.same_direction_edges += r.same_direction_edges;
    t.non_manifold_edges += r.non_manifold_edges;
    t.sil_edges += r.sil_edges;
    t.dangling_sil_edges += r.dangling_sil_edges;
}

/* Cut at a UTF-8 character boundary (names are valid UTF-8: the loader
 * makes them so), never inside a character. */
std::string shorten(const std::string &s, std::size_t n) {
    if (s.size() <= n) return s;
    std::size_t cut = n - 3;
    while (cut > 0 && (static_cast<unsigned char>(s[cut]) & 0xC0) == 0x80) cut--;
    return s.substr(0, cut) + "...";
}

/* JSON file output: "-" is stdout. */
struct JsonOut {
    FILE *f = nullptr;
    bool owned = false;
    bool open(const char *command, const std::string &path) {
        if (path.empty()) return true;
        if (path == "-") {
            f = stdout;
            return true;
        }
        f = std::fopen(path.c_str(), "w");
        if (!f) {
            std::fprintf(stderr, "shadowvol %s: cannot write %s\n", command, path.c_str());
            return false;
        }
        owned = true;
        return true;
    }
    ~JsonOut() {
        if (owned) std::fclose(f);
    }
};

void json_report(FILE *f, const sv::PrepareReport &r) {
    std::fprintf(f,
                 "{\"vertices_in\": %lld, \"triangles_in\": %lld, \"degenerate_dropped\": %lld, "
                 "\"triangles\": %lld, \"welded_vertices\": %lld, \"zero_normal_triangles\": "
                 "%lld, \"edges\": %lld, \"boundary_edges\": %lld, \"manifold_edges\": %lld, "
                 "\"same_direction_edges\": %lld, \"non_manifold_edges\": %lld, \"sil_edges\": "
                 "%lld, \"dangling_sil_edges\": %lld, \"closed\": %s}",
                 (long long)r.vertices_in, (long long)r.triangles_in,
                 (long long)r.degenerate_dropped, (long long)r.triangles,
                 (long long)r.welded_vertices, (long long)r.zero_normal_triangles,
                 (long long)r.edges, (long long)r.boundary_edges, (long long)r.manifold_edges,
                 (long long)r.same_direction_edges, (long long)r.non_manifold_edges,
                 (long long)r.sil_edges, (long long)r.dangling_sil_edges,
                 is_closed(r) ? "true" : "false");
}

struct ModelArgs {
    std::string model, mesh, json_path;
    long long max_triangles = -1; /* -1: the loader's default */
};

/* The options inspect and verify share: MODEL, --mesh, --json, --help.
 * EXTRA takes the command's own options (returns true when it took one).
 * Returns -1 to go on, or the exit status to return (0 after --help, 2 for
 * a usage error, reported on stderr). */
int parse_model_args(const char *command, int argc, char **argv, void (*usage)(FILE *),
                     const std::function<bool(ArgReader &)> &extra, ModelArgs *out) {
    try {
        ArgReader a(argc, argv);
        while (a.next()) {
            if (a.is_flag("-h") || a.is_flag("--help")) {
                usage(stdout);
                return 0;
            } else if (a.is("--mesh")) {
                out->mesh = a.value();
            } else if (a.is("--json")) {
                out->json_path = a.value();
            } else if (a.is("--max-triangles")) {
                out->max_triangles = a.integer(0, (long long)1 << 40);
            } else if (extra(a)) {
                continue;
            } else if (a.arg().rfind('-', 0) == 0 && a.arg() != "-") {
                usage_error("unknown option '" + quoted(a.arg()) + "'");
            } else if (out->model.empty()) {
                out->model = a.arg();
            } else {
                usage_error("unexpected argument '" + quoted(a.arg()) + "'");
            }
        }
        if (out->model.empty()) {
            usage_error(std::string("which model? (shadowvol ") + command + " MODEL)");
        }
    } catch (const UsageError &e) {
        std::fprintf(stderr, "shadowvol %s: %s\nTry 'shadowvol %s --help'.\n", command,
                     e.message.c_str(), command);
        return kExitUsage;
    }
    return -1;
}

} // namespace

/* ---- inspect ------------------------------------------------------------ */

void inspect_usage(FILE *out) {
    std::fprintf(out,
                 "usage: shadowvol inspect MODEL [--mesh NAME] [--json FILE]\n"
                 "\n"
                 "Loads a glTF 2.0 model (.gltf or .glb) and prints, for every mesh instance\n"
                 "of its scene (one surface: the mesh's triangle primitives merged, placed in\n"
                 "world space) and in total, what shadow-volume preparation finds:\n"
                 "  prims      triangle primitives merged (strips and fans converted)\n"
                 "  mirror     the node transform mirrors the mesh (winding flipped back)\n"
                 "  tris in    triangles as stored;  verts in: vertices as stored\n"
                 "  welded     distinct positions (vertices welded by exact position)\n"
                 "  degen      triangles dropped: two corners welded together\n"
                 "  tris       triangles kept;  edges: distinct edges of those\n"
                 "  boundary   edges used by one triangle (the mesh is open there)\n"
                 "  manifold   edges used twice, in opposite directions\n"
                 "  same-dir   edges used twice in the same direction (inconsistent winding)\n"
                 "  non-mfld   edges used by more than two triangles\n"
                 "  silEdges   SilEdges built;  dangling: of those, p2 = numTriangles\n"
                 "  zero-n     kept triangles with collinear corners (plane 0,0,0,0)\n"
                 "  closed     closed 2-manifold (no boundary, non-manifold or same-dir edge)\n"
                 "\n"
                 "options:\n"
                 "  --mesh NAME   only the instances of the mesh called NAME\n"
                 "  --json FILE   also write the report as JSON (schema shadowvol-inspect/1;\n"
                 "                FILE - is stdout, and the table then goes to stderr)\n"
                 "  --max-triangles N  refuse a scene of more than N triangles (summed over\n"
                 "                its instances, estimated before loading; default 16777216,\n"
                 "                about 2 GB; 0 = no limit)\n"
                 "\n"
                 "Exit status: 0 done, 2 bad arguments, 3 the model could not be loaded\n"
                 "(or is above the limits).\n");
}

int inspect_main(int argc, char **argv) {
    ModelArgs args;
    const int status = parse_model_args(
        "inspect", argc, argv, inspect_usage, [](ArgReader &) { return false; }, &args);
    if (status >= 0) return status;
    const std::string &model = args.model;

    LoadedModel m;
    if (!load_model("inspect", model, args.mesh, args.max_triangles, &m)) return kExitBadModel;
    JsonOut json;
    if (!json.open("inspect", args.json_path)) return kExitBadModel;
    FILE *out = json.f == stdout ? stderr : stdout;

    std::fprintf(out, "%s: %zu surface%s\n\n", model.c_str(), m.surfaces.size(),
                 m.surfaces.size() == 1 ? "" : "s");
    const char *head = "%-34s %5s %6s %8s %8s %8s %5s %8s %8s %8s %8s %8s %8s %8s %8s %6s %6s\n";
    std::fprintf(out, head, "surface", "prims", "mirror", "tris in", "verts in", "welded", "degen",
                 "tris", "edges", "boundary", "manifold", "same-dir", "non-mfld", "silEdges",
                 "dangling", "zero-n", "closed");
    auto row = [&](const std::string &name, const std::string &prims, const char *mirror,
                   const sv::PrepareReport &r, const char *closed) {
        std::fprintf(out,
                     "%-34s %5s %6s %8lld %8lld %8lld %5lld %8lld %8lld %8lld %8lld %8lld %8lld "
                     "%8lld %8lld %6lld %6s\n",
                     shorten(name, 34).c_str(), prims.c_str(), mirror, (long long)r.triangles_in,
                     (long long)r.vertices_in, (long long)r.welded_vertices,
                     (long long)r.degenerate_dropped, (long long)r.triangles, (long long)r.edges,
                     (long long)r.boundary_edges, (long long)r.manifold_edges,
                     (long long)r.same_direction_edges, (long long)r.non_manifold_edges,
                     (long long)r.sil_edges, (long long)r.dangling_sil_edges,
                     (long long)r.zero_normal_triangles, closed);
    };
    sv::PrepareReport total;
    int prims = 0, closed = 0;
    for (const Surface &s : m.surfaces) {
        const sv::PrepareReport &r = s.prepared.report;
        row(s.source.name, std::to_string(s.source.primitives), s.source.mirrored ? "yes" : "no", r,
            is_closed(r) ? "yes" : "no");
        add_report(total, r);
        prims += s.source.primitives;
        closed += is_closed(r);
    }
    if (m.surfaces.size() > 1) {
        const std::string c = std::to_string(closed) + "/" + std::to_string(m.surfaces.size());
        row("total", std::to_string(prims), "", total, c.c_str());
    }
    /* Shells and the caster rule each gets under --caster-rule auto
     * (shadowvol_casters.h): closed shells the paper's volume, the others
     * the general rule. */
    std::vector<sv::ShellMap> shell_maps;
    shell_maps.reserve(m.surfaces.size());
    for (const Surface &s : m.surfaces) shell_maps.push_back(sv::find_shells(s.prepared));
    std::fprintf(out, "\nshells (the caster rule under --caster-rule auto):\n");
    constexpr std::size_t kShellsShown = 12;
    for (std::size_t i = 0; i < m.surfaces.size(); i++) {
        const sv::ShellMap &sm = shell_maps[i];
        std::fprintf(out, "%s: %zu shell%s, %lld closed\n",
                     shorten(m.surfaces[i].source.name, 60).c_str(), sm.shells.size(),
                     sm.shells.size() == 1 ? "" : "s", (long long)sm.closed_shells());
        for (std::size_t k = 0; k < sm.shells.size() && k < kShellsShown; k++) {
            const sv::Shell &sh = sm.shells[k];
            const bool ground = m.surfaces[i].source.declared_ground;
            std::fprintf(out, "  shell %zu: %lld triangles, %s rule: %s\n", k,
                         (long long)sh.triangles,
                         sv::shell_uses_general_rule(sh, sv::CasterRule::automatic, ground)
                             ? "general"
                             : "paper's",
                         sv::shell_rule_reason(sh, ground).c_str());
        }
        if (sm.shells.size() > kShellsShown)
            std::fprintf(out, "  ... %zu more shells (all in --json)\n",
                         sm.shells.size() - kShellsShown);
    }
    for (const std::string &n : m.notes) std::fprintf(out, "note: %s\n", n.c_str());

    if (json.f) {
        std::fprintf(json.f,
                     "{\"schema\": \"shadowvol-inspect/1\", \"model\": %s,\n \"surfaces\": [",
                     json_string(model).c_str());
        for (std::size_t i = 0; i < m.surfaces.size(); i++) {
            const Surface &s = m.surfaces[i];
            std::fprintf(json.f,
                         "%s\n  {\"name\": %s, \"mesh\": %d, \"node\": %d, \"primitives\": %d, "
                         "\"mirrored\": %s, \"skinned\": %s, \"report\": ",
                         i ? "," : "", json_string(s.source.name).c_str(), s.source.mesh_index,
                         s.source.node_index, s.source.primitives,
                         s.source.mirrored ? "true" : "false", s.source.skinned ? "true" : "false");
            json_report(json.f, s.prepared.report);
            std::fprintf(json.f, ", \"shells\": [");
            const sv::ShellMap &sm = shell_maps[i];
            for (std::size_t k = 0; k < sm.shells.size(); k++) {
                const sv::Shell &sh = sm.shells[k];
                std::fprintf(
                    json.f,
                    "%s{\"triangles\": %lld, \"closed\": %s, \"rule\": \"%s\", "
                    "\"reason\": %s}",
                    k ? ", " : "", (long long)sh.triangles, sh.closed() ? "true" : "false",
                    sv::shell_uses_general_rule(sh, sv::CasterRule::automatic,
                                                s.source.declared_ground)
                        ? "general"
                        : "closed",
                    json_string(sv::shell_rule_reason(sh, s.source.declared_ground)).c_str());
            }
            std::fprintf(json.f, "]}");
        }
        std::fprintf(json.f, "],\n \"total\": ");
        json_report(json.f, total);
        std::fprintf(json.f, ",\n \"notes\": [");
        for (std::size_t i = 0; i < m.notes.size(); i++) {
            std::fprintf(json.f, "%s%s", i ? ", " : "", json_string(m.notes[i]).c_str());
        }
        std::fprintf(json.f, "]}\n");
    }
    return 0;
}

/* ---- verify ------------------------------------------------------------- */

namespace {

constexpr int kDefaultLights = 16;
constexpr int kDefaultPoints = 1000;

std::string variant_names(const std::vector<const sv_variant *> &v) {
    std::string s;
    for (const sv_variant *x : v) s += (s.empty() ? "" : ", ") + std::string(x->name);
    return s;
}

struct SurfaceVerdict {
    int lights = 0, point_lights = 0, culled_lights = 0, directional_lights = 0;
    int64_t volumes = 0, distinct_volumes = 0, volume_triangles = 0, culled_triangles = 0;
    sv::InSpaceCounts counts;
    double seconds = 0;
};

} // namespace

void verify_usage(FILE *out) {
    std::fprintf(out,
                 "usage: shadowvol verify MODEL [--lights N] [--points N] [--seed S]\n"
                 "                              [--variant NAME]... [--mesh NAME] [--json FILE]\n"
                 "\n"
                 "Proves, for every mesh instance of a glTF model (one surface each, in world\n"
                 "space), that the shadow volumes built by every variant this CPU can run are\n"
                 "right, for N lights around the surface: half point lights (every other one\n"
                 "with a light box that culls part of the mesh, appendix B), half directional.\n"
                 "For each light and variant:\n"
                 "  closure   every directed edge a->b of the index list appears as often as\n"
                 "            b->a (the volume is closed and consistently wound);\n"
                 "  in space  at N random points (half around the bounds, half just behind or\n"
                 "            in front of the mesh), the volume's winding number (the stencil\n"
                 "            count, by signed ray crossings; odd vertices pushed 1000 radii\n"
                 "            away from the light) equals the number of casting triangles the\n"
                 "            segment from the point to the light crosses. For a closed mesh\n"
                 "            and an unculled light, a point outside the mesh is also checked\n"
                 "            to be in shadow exactly when that segment crosses the mesh.\n"
                 "Variants whose index lists are equal share the in-space check. Points too\n"
                 "close to a boundary to decide are skipped and counted; when more than 2%%\n"
                 "of a light's points are, or the surface's radius is outside [1.2e-38, 1e36],\n"
                 "the result is CANNOT DECIDE (exit 4) with the reason: not a pass, not a\n"
                 "failure. Stops at the first failure and prints the variant, the light and\n"
                 "the point.\n"
                 "\n"
                 "options:\n"
                 "  --lights N      lights per surface (default %d)\n"
                 "  --points N      points per light (default %d)\n"
                 "  --seed S        seed of the lights and points (default 1)\n"
                 "  --variant NAME  only this variant (repeatable; default: all this CPU runs)\n"
                 "  --mesh NAME     only the instances of the mesh called NAME\n"
                 "  --json FILE     also write the results as JSON (schema shadowvol-verify/1;\n"
                 "                  FILE - is stdout, and the table then goes to stderr)\n"
                 "  --max-triangles N  as for inspect (default 16777216; 0 = no limit)\n"
                 "  --max-memory SIZE  refuse to start when the estimate of verify's memory\n"
                 "                  (about 700 bytes a triangle of the largest surface) is\n"
                 "                  above SIZE (512K, 800M or 800, 8G; default %lldM;\n"
                 "                  0 = no limit)\n"
                 "\n"
                 "Progress goes to stderr. Exit status: 0 every check passed, 1 a check failed,\n"
                 "2 bad arguments, 3 the model could not be loaded (or is above the limits),\n"
                 "4 the check could not decide.\n",
                 kDefaultLights, kDefaultPoints, kDefaultVerifyMaxMemoryMb);
}

int verify_main(int argc, char **argv) {
    ModelArgs args;
    int lights = kDefaultLights, points = kDefaultPoints;
    uint64_t seed = 1;
    long long max_memory = kDefaultVerifyMaxMemoryMb << 20;
    std::vector<const sv_variant *> variants;
    auto extra = [&](ArgReader &a) {
        if (a.is("--max-memory")) {
            max_memory = memory_size(a);
        } else if (a.is("--lights")) {
            lights = (int)a.integer(1, 100000);
        } else if (a.is("--points")) {
            points = (int)a.integer(1, 10000000);
        } else if (a.is("--seed")) {
            seed = a.seed();
        } else if (a.is("--variant")) {
            const std::string v = a.value();
            const sv_variant *var = sv_variant_by_name(v.c_str());
            if (!var) {
                int n = 0;
                const sv_variant *all = sv_variants(&n);
                std::string names;
                for (int i = 0; i < n; i++) names += (i ? ", " : "") + std::string(all[i].name);
                usage_error("unknown variant '" + quoted(v) + "' (variants: " + names + ")");
            }
            if ((var->isa & sv_cpu_isa()) != var->isa) {
                usage_error("variant '" + quoted(v) + "' needs an instruction set this CPU lacks");
            }
            if (std::find(variants.begin(), variants.end(), var) == variants.end()) {
                variants.push_back(var);
            }
        } else {
            return false;
        }
        return true;
    };
    const int status = parse_model_args("verify", argc, argv, verify_usage, extra, &args);
    if (status >= 0) return status;
    const std::string &model = args.model;
    if (variants.empty()) variants = sv::supported_variants();
    /* The general rule's kernels of the same instruction sets (as the
     * volume pass pairs them). */
    std::vector<const sv_general_variant *> general_variants;
    for (const sv_variant *v : variants) {
        const sv_general_variant *g = sv_general_variant_for_isa(v->isa);
        if (std::find(general_variants.begin(), general_variants.end(), g) ==
            general_variants.end())
            general_variants.push_back(g);
    }

    LoadedModel m;
    if (!load_model("verify", model, args.mesh, args.max_triangles, &m)) return kExitBadModel;
    { /* Hostile sizes: memory and time estimated before any volume. */
        int64_t largest = 0, total = 0;
        for (const Surface &s : m.surfaces) {
            largest = std::max<int64_t>(largest, s.prepared.num_triangles());
            total += s.prepared.num_triangles();
        }
        const double mb = kVerifyBytesPerTriangle * (double)largest / (1 << 20);
        const double seconds = kVerifySecondsPerTriangleLight * (double)total * lights;
        if (max_memory > 0 && mb * (1 << 20) > (double)max_memory) {
            std::fprintf(stderr,
                         "shadowvol verify: %s: %lld triangles in the largest surface need about "
                         "%.1f MB (and %.0f s for %d lights), more than --max-memory %.1f MB\n",
                         model.c_str(), (long long)largest, mb, seconds, lights,
                         (double)max_memory / (1 << 20));
            return kExitBadModel;
        }
        if (seconds > 30) {
            std::fprintf(stderr, "shadowvol verify: %s: estimated %.0f s and %.0f MB\n",
                         model.c_str(), seconds, mb);
        }
    }
    JsonOut json;
    if (!json.open("verify", args.json_path)) return kExitBadModel;
    FILE *out = json.f == stdout ? stderr : stdout;

    std::fprintf(out,
                 "%s: %zu surface%s, %d lights each, %d points per light, seed %llu\n"
                 "variants: %s\n\n",
                 model.c_str(), m.surfaces.size(), m.surfaces.size() == 1 ? "" : "s", lights,
                 points, (unsigned long long)seed, variant_names(variants).c_str());
    const char *head = "%-34s %8s %6s %6s %7s %9s %9s %9s %9s %8s %7s %7s %7s\n";
    std::fprintf(out, head, "surface", "tris", "closed", "lights", "volumes", "vol tris", "points",
                 "shadow", "lit", "crossing", "inside", "skipped", "seconds");

    sv::VerifyOptions options;
    options.points_per_light = points;
    /* Progress (surface and light) on a terminal only: logs stay clean. */
    const bool progress = isatty(2);
    std::vector<SurfaceVerdict> verdicts;
    SurfaceVerdict general; /* the general rule's shells, all surfaces */
    int general_shells = 0;
    std::string failure, undecided;
    std::size_t failed_surface = 0, undecided_surface = 0;
    for (std::size_t si = 0; si < m.surfaces.size() && failure.empty(); si++) {
        const Surface &s = m.surfaces[si];
        SurfaceVerdict v;
        const auto t0 = std::chrono::steady_clock::now();
        const uint64_t surface_seed = seed * 0x9E3779B97F4A7C15ull + si;
        const std::vector<sv::VerifyLight> ls = sv::make_verify_lights(s.prepared, lights,
                                                                       surface_seed);
        for (std::size_t li = 0; li < ls.size(); li++) {
            if (progress) {
                std::fprintf(stderr, "\rverify: surface %zu/%zu, light %zu/%zu ", si + 1,
                             m.surfaces.size(), li + 1, ls.size());
                std::fflush(stderr);
            }
            const sv::VerifyLight &l = ls[li];
            const sv::LightResult r = sv::verify_light(s.prepared, l, variants, options,
                                                       surface_seed ^
                                                           (li + 1) * 0xD1B54A32D192ED03ull);
            v.lights++;
            (l.light.w == 0.0f ? v.directional_lights : v.point_lights)++;
            v.culled_lights += l.culled;
            v.volumes += r.variants_checked;
            v.distinct_volumes += r.distinct_volumes;
            v.volume_triangles += r.volume_triangles;
            v.culled_triangles += r.culled_triangles;
            v.counts.add(r.counts);
            if (!r.ok) {
                failure = r.failure;
                failed_surface = si;
                break;
            }
            if (r.undecided && undecided.empty()) {
                undecided = r.undecided_reason;
                undecided_surface = si;
            }
        }
        v.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        if (progress) std::fprintf(stderr, "\r%60s\r", "");
        const sv::PrepareReport &r = s.prepared.report;
        std::fprintf(out,
                     "%-34s %8lld %6s %6d %7lld %9lld %9lld %9lld %9lld %8lld %7lld %7lld %7.1f\n",
                     shorten(s.source.name, 34).c_str(), (long long)r.triangles,
                     is_closed(r) ? "yes" : "no", v.lights, (long long)v.volumes,
                     (long long)(v.volume_triangles / std::max<int64_t>(v.distinct_volumes, 1)),
                     (long long)v.counts.points, (long long)v.counts.in_shadow,
                     (long long)v.counts.lit, (long long)v.counts.crossing_checked,
                     (long long)v.counts.inside_mesh, (long long)v.counts.skipped, v.seconds);
        verdicts.push_back(v);
        /* The general rule (issue 27, docs/CASTERS.md), shell by shell:
         * each shell that auto gives it, alone, its volume built by the
         * direct kernels from its general edge table, proved closed with
         * its multiplicities and right in space: the winding number is the
         * number of the shell's triangles the segment to the light
         * crosses, the general rule's count. */
        const sv::ShellMap shells = sv::find_shells(s.prepared);
        for (std::size_t k = 0; k < shells.shells.size() && failure.empty(); k++) {
            if (!sv::shell_uses_general_rule(shells.shells[k], sv::CasterRule::automatic,
                                             s.source.declared_ground))
                continue; /* proven above: the paper's volume of the surface */
            const sv::PreparedSurface one = sv::shell_surface(s.prepared, shells, (int)k);
            const sv::GeneralEdgeTable table = sv::general_edge_table(one, sv::find_shells(one),
                                                                      sv::CasterRule::general);
            SurfaceVerdict g;
            const auto g0 = std::chrono::steady_clock::now();
            for (std::size_t li = 0; li < ls.size(); li++) {
                const sv::LightResult r =
                    sv::verify_general_light(one, table, ls[li], general_variants, options,
                                             surface_seed ^ (k + 7) * 0x9E3779B97F4A7C15ull ^
                                                 (li + 1));
                g.lights++;
                g.volumes += r.variants_checked;
                g.distinct_volumes += r.distinct_volumes;
                g.volume_triangles += r.volume_triangles;
                g.counts.add(r.counts);
                if (!r.ok) {
                    failure = "shell " + std::to_string(k) + " (general rule): " + r.failure;
                    failed_surface = si;
                    break;
                }
                if (r.undecided && undecided.empty()) {
                    undecided = "shell " + std::to_string(k) + ": " + r.undecided_reason;
                    undecided_surface = si;
                }
            }
            g.seconds =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - g0).count();
            const std::string label = "  shell " + std::to_string(k) + ", general rule";
            std::fprintf(
                out, "%-34s %8lld %6s %6d %7lld %9lld %9lld %9lld %9lld %8lld %7lld %7lld %7.1f\n",
                label.c_str(), (long long)one.report.triangles, "no", g.lights,
                (long long)g.volumes,
                (long long)(g.volume_triangles / std::max<int64_t>(g.distinct_volumes, 1)),
                (long long)g.counts.points, (long long)g.counts.in_shadow, (long long)g.counts.lit,
                (long long)g.counts.crossing_checked, (long long)g.counts.inside_mesh,
                (long long)g.counts.skipped, g.seconds);
            general_shells++;
            general.volumes += g.volumes;
            general.distinct_volumes += g.distinct_volumes;
            general.counts.add(g.counts);
            general.seconds += g.seconds;
        }
    }
    SurfaceVerdict t;
    for (const SurfaceVerdict &v : verdicts) {
        t.lights += v.lights;
        t.point_lights += v.point_lights;
        t.culled_lights += v.culled_lights;
        t.directional_lights += v.directional_lights;
        t.volumes += v.volumes;
        t.distinct_volumes += v.distinct_volumes;
        t.culled_triangles += v.culled_triangles;
        t.counts.add(v.counts);
        t.seconds += v.seconds;
    }
    t.volumes += general.volumes;
    t.distinct_volumes += general.distinct_volumes;
    t.counts.add(general.counts);
    t.seconds += general.seconds;
    std::fprintf(out,
                 "\n%d lights (%d point, %d of them culled by a light box, %d directional); "
                 "%lld volumes built and checked closed (%lld distinct index lists); %lld "
                 "triangles culled;\n%lld points checked in space (%lld in shadow, %lld lit), "
                 "%lld of them also by segment crossing, %lld inside the mesh; %lld skipped "
                 "near a boundary; %lld rays replaced; %lld crossings of edge-on casting "
                 "triangles.\n",
                 t.lights, t.point_lights, t.culled_lights, t.directional_lights,
                 (long long)t.volumes, (long long)t.distinct_volumes, (long long)t.culled_triangles,
                 (long long)t.counts.points, (long long)t.counts.in_shadow, (long long)t.counts.lit,
                 (long long)t.counts.crossing_checked, (long long)t.counts.inside_mesh,
                 (long long)t.counts.skipped, (long long)t.counts.ray_retries,
                 (long long)t.counts.inverted_prisms);
    std::fprintf(out,
                 "general rule (the direct kernels, docs/CASTERS.md): %d open or non-manifold "
                 "shell%s proved on their own, %lld volumes (in the counts above).\n",
                 general_shells, general_shells == 1 ? "" : "s", (long long)general.volumes);
    if (!failure.empty()) {
        std::fprintf(out, "FAILED: surface %s: %s\n",
                     m.surfaces[failed_surface].source.name.c_str(), failure.c_str());
        if (out != stderr) {
            std::fprintf(stderr, "shadowvol verify: %s: surface %s: %s\n", model.c_str(),
                         m.surfaces[failed_surface].source.name.c_str(), failure.c_str());
        }
    } else if (!undecided.empty()) {
        std::fprintf(out, "CANNOT DECIDE: surface %s: %s\n",
                     m.surfaces[undecided_surface].source.name.c_str(), undecided.c_str());
        if (out != stderr) {
            std::fprintf(stderr, "shadowvol verify: %s: cannot decide: surface %s: %s\n",
                         model.c_str(), m.surfaces[undecided_surface].source.name.c_str(),
                         undecided.c_str());
        }
    } else {
        std::fprintf(out, "PASSED: every volume closed and right in space.\n");
    }

    if (json.f) {
        std::fprintf(json.f,
                     "{\"schema\": \"shadowvol-verify/1\", \"model\": %s, \"lights\": %d, "
                     "\"points_per_light\": %d, \"seed\": %llu, \"variants\": [",
                     json_string(model).c_str(), lights, points, (unsigned long long)seed);
        for (std::size_t i = 0; i < variants.size(); i++) {
            std::fprintf(json.f, "%s%s", i ? ", " : "", json_string(variants[i]->name).c_str());
        }
        std::fprintf(json.f,
                     "],\n \"general_rule_shells\": %d, \"passed\": %s, \"verdict\": \"%s\", "
                     "\"failure\": %s, "
                     "\"undecided\": %s,\n \"surfaces\": [",
                     general_shells, failure.empty() && undecided.empty() ? "true" : "false",
                     !failure.empty()     ? "failed"
                     : !undecided.empty() ? "undecided"
                                          : "passed",
                     failure.empty() ? "null" : json_string(failure).c_str(),
                     failure.empty() && !undecided.empty() ? json_string(undecided).c_str()
                                                           : "null");
        for (std::size_t i = 0; i < verdicts.size(); i++) {
            const SurfaceVerdict &v = verdicts[i];
            const sv::InSpaceCounts &c = v.counts;
            std::fprintf(json.f,
                         "%s\n  {\"name\": %s, \"triangles\": %lld, \"closed\": %s, \"lights\": "
                         "%d, \"point_lights\": %d, \"culled_lights\": %d, "
                         "\"directional_lights\": %d, \"volumes\": %lld, \"distinct_volumes\": "
                         "%lld, \"culled_triangles\": %lld, \"points\": %lld, \"in_shadow\": "
                         "%lld, \"lit\": %lld, \"crossing_checked\": %lld, \"inside_mesh\": %lld, "
                         "\"skipped\": %lld, \"ray_retries\": %lld, \"inverted_prisms\": %lld, "
                         "\"seconds\": %.3f}",
                         i ? "," : "", json_string(m.surfaces[i].source.name).c_str(),
                         (long long)m.surfaces[i].prepared.report.triangles,
                         is_closed(m.surfaces[i].prepared.report) ? "true" : "false", v.lights,
                         v.point_lights, v.culled_lights, v.directional_lights,
                         (long long)v.volumes, (long long)v.distinct_volumes,
                         (long long)v.culled_triangles, (long long)c.points, (long long)c.in_shadow,
                         (long long)c.lit, (long long)c.crossing_checked, (long long)c.inside_mesh,
                         (long long)c.skipped, (long long)c.ray_retries,
                         (long long)c.inverted_prisms, v.seconds);
        }
        std::fprintf(json.f, "]}\n");
    }
    return !failure.empty() ? kExitCheckFailed : !undecided.empty() ? kExitUndecided : 0;
}

} // namespace svcli
