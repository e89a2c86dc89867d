/*
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "bench_cli.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench_run.h"
#include "shadowvol_gltf.h"
#include "shadowvol_plan.h"
#include "cycle_table.h"
#include "figure1.h"
#include "stencil_rule.h"
#include "frame_bench.h"
#include "json_report.h"
#include "machine_limits.h"
#include "lights.h"
#include "model_list.h"
#include "model_workload.h"
#include "output_file.h"
#include "extrude_bench.h"
#include "planes_bench.h"
#include "cli_args.h"
#include "render_args.h"
#include "scene_bench.h"
#include "scene_presets.h"
#include "shadowvol_casters.h"
#include "stencil_method.h"
#include "routines.h"
#include "compare.h"
#include "scaling_cli.h"
#include "seed_bench.h"
#include "synthetic_workload.h"
#include "sysinfo.h"
#include "table_report.h"
#include "timer.h"

/* Set by bench/CMakeLists.txt. */
#ifndef SV_MODELS_DIR
#define SV_MODELS_DIR "models"
#endif
#ifndef SV_SHARED_MODELS_DIR
#define SV_SHARED_MODELS_DIR "../shared/models"
#endif

namespace svbench {

namespace {

/* The full table of the bundled character (40 rows) in about 7 s on a
 * small VM whose cpuid traps; --quick in about one. */
constexpr int kDefaultRuns = 4000;
constexpr int kQuickRuns = 256;
constexpr int kMaxRuns = 1000000;
/* --rounds: each row keeps its lowest round median, so more rounds ride
 * out more of a noisy machine's slow phases; past this, a round of the
 * default runs is too short to have a median. */
constexpr int kMaxRounds = 64;
constexpr int kLights = 64;
/* Runs are given for a mesh of the paper's size; a larger one gets
 * proportionally fewer (its calls are longer and steadier), at least
 * kMinScaledRuns, so `--model all` stays within a minute or so. */
constexpr int kReferenceTriangles = 1344;
constexpr int kMinScaledRuns = 64;
/* --max-triangles: the largest a mesh index (int) can count to. */
constexpr long kMaxTriangles = 715827882; /* INT_MAX / 3 */

constexpr int kExitCheckFailed = 1;
constexpr int kExitUsage = 2;
constexpr int kExitBadModel = 3;

const char *const kBundledModel = SV_MODELS_DIR "/character_1344.glb";

/* The levels sv_set_isa_limit knows (include/shadowvol.h). */
const char *const kIsaLevels = "c, sse2, avx2, avx512";

struct UsageError {
    std::string message;
};

/* A refusal; the message quotes command-line text, so it is made printable
 * and bounded here, once for every caller (issue 17). */
[[noreturn]] void bad(const std::string &message) {
    throw UsageError{sv::printable_text(message, 4 * sv::kGltfMaxQuotedBytes)};
}

long long parse_int(const std::string &opt, const std::string &s, long long lo, long long hi) {
    errno = 0;
    char *end = nullptr;
    const bool digits = !s.empty() && s.find_first_not_of("0123456789") == std::string::npos;
    const long long v = digits ? std::strtoll(s.c_str(), &end, 10) : 0;
    if (!digits || errno == ERANGE || *end || v < lo || v > hi) {
        bad(opt + " needs a whole number from " + std::to_string(lo) + " to " + std::to_string(hi) +
            ", not '" + s + "'");
    }
    return v;
}

unsigned long long parse_seed(const std::string &s) {
    errno = 0;
    char *end = nullptr;
    const bool digits = !s.empty() && s.find_first_not_of("0123456789") == std::string::npos;
    const unsigned long long v = digits ? std::strtoull(s.c_str(), &end, 10) : 0;
    if (!digits || errno == ERANGE || *end) {
        bad("--seed needs a whole number from 0 to 18446744073709551615, not '" + s + "'");
    }
    return v;
}

/* A finite number, the whole of S; false otherwise. */
bool parse_double(const std::string &s, double *v) {
    if (s.empty() || std::isspace((unsigned char)s[0])) {
        return false;
    }
    errno = 0;
    char *end = nullptr;
    *v = std::strtod(s.c_str(), &end);
    return !*end && errno != ERANGE && std::isfinite(*v);
}

/* A ratio strictly between 0 and 1. */
double parse_ratio(const std::string &opt, const std::string &s) {
    double v;
    if (!parse_double(s, &v) || !(v > 0 && v < 1)) {
        bad(opt + " needs a number between 0 and 1 (exclusive), not '" + s + "'");
    }
    return v;
}

/* x,y,z,w: four finite floats, w 1 (a point light's position) or 0 (a
 * direction towards the light, not zero). */
Vec4 parse_light(const std::string &s) {
    const std::string want =
        "--light needs x,y,z,w: four finite numbers, w = 1 for a point light at (x,y,z) or 0 "
        "for a directional light shining from direction (x,y,z), not '" +
        s + "'";
    double c[4];
    size_t pos = 0;
    for (int k = 0; k < 4; k++) {
        const size_t comma = s.find(',', pos);
        if ((k < 3) != (comma != std::string::npos)) {
            bad(want);
        }
        const std::string part = s.substr(pos, k < 3 ? comma - pos : std::string::npos);
        if (!parse_double(part, &c[k]) || !std::isfinite((float)c[k])) {
            bad(want);
        }
        pos = comma + 1;
    }
    if (c[3] != 0 && c[3] != 1) {
        bad(want);
    }
    if (c[3] == 0 && c[0] == 0 && c[1] == 0 && c[2] == 0) {
        bad("--light: a directional light (w = 0) needs a direction other than 0,0,0");
    }
    return Vec4{(float)c[0], (float)c[1], (float)c[2], (float)c[3]};
}

/* Breaks a ", "-separated list into lines of at most WIDTH characters. */
std::string wrap(const std::string &list, size_t width, const char *newline) {
    std::string out, line;
    size_t pos = 0;
    while (pos < list.size()) {
        const size_t comma = list.find(", ", pos);
        const std::string item = list.substr(pos, comma == std::string::npos ? std::string::npos
                                                                             : comma + 1 - pos);
        pos = comma == std::string::npos ? list.size() : comma + 2;
        if (!line.empty() && line.size() + 1 + item.size() > width) {
            out += line + newline;
            line.clear();
        }
        line += (line.empty() ? "" : " ") + item;
    }
    return out + line;
}

/* Everything the command line asked for. */
struct CliOptions {
    TableOptions table;
    int runs = 0; /* 0: the default for --quick or not */
    bool quick = false;
    std::string timer = "auto";
    uint64_t seed = 1;
    std::vector<std::string> models;
    bool hasLight = false;
    Vec4 light{};
    LightTargets targets;
    std::string json;         /* --json FILE; "" none, "-" stdout */
    bool scaling = false;     /* --scaling: scaling.h instead of the cycle table */
    bool limits = false;      /* --limits: machine_limits.h after each table */
    bool silhouette = false;  /* --silhouette: seed 003's finders (silhouette_bench.cpp) */
    bool backface = false;    /* --backface: seed 001's culling (backface_bench.cpp) */
    bool planes = false;      /* --planes: per-frame planes (planes_bench.cpp) */
    bool extrude = false;     /* --extrude: seed 002's vertex program (extrude_bench.cpp) */
    bool scene = false;       /* --scene: the demo scene per frame (scene_bench.cpp) */
    bool casters = false;     /* --casters: the general rule's builders (casters_bench.cpp) */
    bool stencilRule = false; /* --stencil-rule: auto's rule measured (stencil_rule.cpp) */
    std::string casterRule;   /* --caster-rule R (with --scene); "" the default, auto */
    std::string scenePreset;  /* --preset NAME|FILE (with --scene or --frame) */
    int sceneWidth = 0, sceneHeight = 0; /* --size WxH (with --scene or --frame) */
    bool frame = false;             /* --frame: the whole frame, pass by pass (frame_bench.cpp) */
    FrameBenchOptions frameOptions; /* --threads, --frames, --no-mesa, --out (with --frame) */
    bool frameOptionGiven = false;
    bool figure1 = false;     /* --figure1: seed 004's Figure 1 (figure1.cpp), with --out */
    std::string plot;         /* --plot FILE (with --scaling) */
    long maxTriangles = 0;    /* --max-triangles N (with --scaling) */
    bool regimeGiven = false; /* options the scaling run has no use for */
    bool lightGiven = false;
    std::string isa;                            /* --isa; "" none */
    std::vector<const BenchVariant *> variants; /* --variant, as given */
    bool help = false;
};

/* "c (--isa)" or "c (SV_ISA)": the ISA limit in force and who set it. */
std::string limit_source(const CliOptions &c) {
    const char *l = sv_isa_limit_name();
    return std::string(l ? l : "none") + (c.isa.empty() ? " (SV_ISA)" : " (--isa)");
}

CliOptions parse(int argc, char **argv) {
    CliOptions c;
    for (int i = 1; i < argc; i++) {
        const std::string arg = argv[i];
        std::string opt = arg, value;
        bool hasValue = false;
        if (arg.rfind("--", 0) == 0 && arg.find('=') != std::string::npos) {
            opt = arg.substr(0, arg.find('='));
            value = arg.substr(arg.find('=') + 1);
            hasValue = true;
        }
        auto need = [&]() -> std::string {
            if (hasValue) {
                return value;
            }
            if (i + 1 >= argc) {
                bad(opt + " needs a value");
            }
            return argv[++i];
        };
        if (opt == "-h" || opt == "--help") {
            c.help = true;
            return c;
        } else if (opt == "--quick" && !hasValue) {
            c.quick = true;
        } else if (opt == "--runs") {
            c.runs = (int)parse_int(opt, need(), 1, kMaxRuns);
        } else if (opt == "--rounds") {
            c.table.rounds = (int)parse_int(opt, need(), 1, kMaxRounds);
        } else if (opt == "--regime") {
            const std::string r = need();
            if (r == "moving" || r == "fixed" || r == "both") {
                c.table.moving = r != "fixed";
                c.table.fixed = r != "moving";
                c.regimeGiven = r != "moving";
            } else {
                bad("--regime must be moving, fixed or both, not '" + r + "'");
            }
        } else if (opt == "--routine") {
            const std::string r = need();
            Routine rt;
            if (!routine_by_name(r, &rt)) {
                bad("unknown routine '" + r + "' (routines: " + routine_list() + ")");
            }
            if (std::find(c.table.routines.begin(), c.table.routines.end(), rt) ==
                c.table.routines.end()) {
                c.table.routines.push_back(rt);
            }
        } else if (opt == "--variant") {
            const std::string v = need();
            const BenchVariant *var = bench_variant_by_name(v);
            if (!var) {
                bad("unknown variant '" + v + "' (variants: " + variant_list() + ")");
            }
            c.variants.push_back(var);
        } else if (opt == "--isa") {
            /* The library's limit, for the rest of the process (the
             * shadowvol program runs one command): the variant table,
             * dispatch and this table then agree on what runs. */
            c.isa = need();
            if (sv_set_isa_limit(c.isa.c_str()) != 0) {
                bad("--isa must be one of " + std::string(kIsaLevels) + ", not '" + c.isa + "'");
            }
        } else if (opt == "--timer") {
            c.timer = need();
            if (c.timer != "auto" && c.timer != "rdtscp" && c.timer != "cpuid" &&
                c.timer != "lfence") {
                bad("--timer must be auto, rdtscp, cpuid or lfence, not '" + c.timer + "'");
            }
        } else if (opt == "--batch") {
            const std::string b = need();
            try {
                c.table.batch = b == "auto" ? 0 : (int)parse_int(opt, b, 1, kMaxBatch);
            } catch (const UsageError &) {
                bad("--batch needs auto or a whole number from 1 to " + std::to_string(kMaxBatch) +
                    ", not '" + b + "'");
            }
        } else if (opt == "--seed") {
            c.seed = parse_seed(need());
        } else if (opt == "--model") {
            const std::string m = need();
            if (m.empty()) {
                bad("--model needs a file, a folder, all or synthetic");
            }
            c.models.push_back(m);
        } else if (opt == "--light") {
            c.light = parse_light(need());
            c.hasLight = true;
            c.lightGiven = true;
        } else if (opt == "--facing-ratio") {
            c.targets.facing = parse_ratio(opt, need());
        } else if (opt == "--silhouette-ratio") {
            c.targets.silhouette = parse_ratio(opt, need());
        } else if (opt == "--json") {
            c.json = need();
            if (c.json.empty()) {
                bad("--json needs a file name, or - for standard output");
            }
        } else if (opt == "--scaling" && !hasValue) {
            c.scaling = true;
        } else if (opt == "--silhouette" && !hasValue) {
            c.silhouette = true;
        } else if (opt == "--backface" && !hasValue) {
            c.backface = true;
        } else if (opt == "--planes" && !hasValue) {
            c.planes = true;
        } else if (opt == "--extrude" && !hasValue) {
            c.extrude = true;
        } else if (opt == "--scene" && !hasValue) {
            c.scene = true;
        } else if (opt == "--casters" && !hasValue) {
            c.casters = true;
        } else if (opt == "--stencil-rule" && !hasValue) {
            c.stencilRule = true;
        } else if (opt == "--frame" && !hasValue) {
            c.frame = true;
        } else if (opt == "--figure1" && !hasValue) {
            c.figure1 = true;
        } else if (opt == "--threads") {
            c.frameOptions.threads = (int)parse_int(opt, need(), 1, 1024);
            c.frameOptionGiven = true;
        } else if (opt == "--stencil") {
            c.frameOptions.stencil = need();
            c.frameOptions.stencil_source = "option";
            sv::render::StencilMethod m;
            if (!sv::render::stencil_method_by_name(c.frameOptions.stencil, m)) {
                bad("--stencil needs " + sv::render::stencil_method_names() + ", not '" +
                    c.frameOptions.stencil + "'");
            }
            c.frameOptionGiven = true;
        } else if (opt == "--frames") {
            c.frameOptions.frames = (int)parse_int(opt, need(), 1, 1000);
            c.frameOptionGiven = true;
        } else if (opt == "--no-mesa" && !hasValue) {
            c.frameOptions.mesa = false;
            c.frameOptionGiven = true;
        } else if (opt == "--out") {
            c.frameOptions.out_dir = need();
            if (c.frameOptions.out_dir.empty()) bad("--out needs a folder");
            c.frameOptionGiven = true;
        } else if (opt == "--caster-rule") {
            c.casterRule = need();
            sv::CasterRule r;
            if (!sv::caster_rule_by_name(c.casterRule, r)) {
                bad("--caster-rule needs auto, closed or general, not '" + c.casterRule + "'");
            }
        } else if (opt == "--preset") {
            c.scenePreset = need();
            if (c.scenePreset.empty()) {
                bad(std::string("--preset needs ") + scene_preset_names() + " or a glTF file");
            }
        } else if (opt == "--size") {
            const std::string v = need();
            try {
                svcli::parse_frame_size(v, c.sceneWidth, c.sceneHeight);
            } catch (const svcli::UsageError &e) {
                bad(e.message);
            }
        } else if (opt == "--limits" && !hasValue) {
            c.limits = true;
        } else if (opt == "--plot") {
            c.plot = need();
            if (c.plot.empty()) {
                bad("--plot needs a file name, or - for standard output");
            }
        } else if (opt == "--max-triangles") {
            c.maxTriangles = (long)parse_int(opt, need(), 1, kMaxTriangles);
        } else if (hasValue && (opt == "--quick" || opt == "--scaling" || opt == "--limits" ||
                                opt == "--silhouette" || opt == "--backface" || opt == "--planes" ||
                                opt == "--extrude" || opt == "--scene" || opt == "--casters" ||
                                opt == "--frame" || opt == "--figure1" || opt == "--no-mesa" ||
                                opt == "--stencil-rule")) {
            bad(opt + " takes no value");
        } else if (arg.rfind('-', 0) == 0) {
            bad("unknown option '" + arg + "'");
        } else {
            bad("unexpected argument '" + arg + "'");
        }
    }
    if (c.figure1) {
        if (c.frame || c.silhouette || c.backface || c.planes || c.extrude || c.scene ||
            c.casters || c.scaling || c.limits || !c.plot.empty() || !c.models.empty() ||
            c.lightGiven || c.frameOptions.out_dir.empty()) {
            bad("--figure1 takes --out DIR, --preset and --size only (and needs --out)");
        }
        return c;
    }
    if (c.frame) {
        if (c.silhouette || c.backface || c.planes || c.extrude || c.scene || c.casters ||
            c.scaling || c.limits || !c.plot.empty() || !c.models.empty() || c.lightGiven ||
            c.regimeGiven || !c.table.routines.empty() || !c.variants.empty() || c.table.batch ||
            !c.casterRule.empty() || c.maxTriangles) {
            bad("--frame takes --preset, --size, --threads, --stencil, --frames, --runs, "
                "--no-mesa, --out, "
                "--quick, --json, --timer and --isa only");
        }
        if (!c.scenePreset.empty()) c.frameOptions.preset = c.scenePreset;
        if (c.sceneWidth)
            c.frameOptions.width = c.sceneWidth, c.frameOptions.height = c.sceneHeight;
        if (c.quick) {
            c.frameOptions.frames = std::min(c.frameOptions.frames, 2);
            c.frameOptions.runs = 1;
        }
        if (c.runs) c.frameOptions.runs = c.runs;
        return c;
    }
    if (c.frameOptionGiven) {
        bad("--threads, --stencil, --frames, --no-mesa and --out are options of --frame");
    }
    if (c.silhouette || c.backface || c.planes || c.extrude || c.scene || c.casters ||
        c.stencilRule) {
        /* Their own meshes, lights, rows and variants (silhouette_bench.cpp,
         * backface_bench.cpp, planes_bench.cpp, casters_bench.cpp). */
        const std::string mode = c.silhouette ? "--silhouette"
                                 : c.backface ? "--backface"
                                 : c.planes   ? "--planes"
                                 : c.extrude  ? "--extrude"
                                 : c.casters  ? "--casters"
                                 : c.scene    ? "--scene"
                                              : "--stencil-rule";
        if ((c.silhouette + c.backface + c.planes + c.extrude + c.scene + c.casters +
                 c.stencilRule >
             1) ||
            c.scaling || c.limits || !c.plot.empty() || !c.models.empty() || c.lightGiven ||
            c.regimeGiven || !c.table.routines.empty() || !c.variants.empty() || c.runs ||
            c.table.batch || c.targets.facing != LightTargets{}.facing ||
            c.targets.silhouette != LightTargets{}.silhouette) {
            bad(mode + " takes --quick, --json, --max-triangles, --seed, --timer and --isa only");
        }
        if (!c.casterRule.empty() && !c.scene) bad("--caster-rule is an option of --scene");
        if ((!c.scenePreset.empty() || c.sceneWidth) && !c.scene && !c.stencilRule)
            bad("--preset and --size are options of --scene, --stencil-rule and --frame");
        return c;
    }
    if (!c.casterRule.empty()) bad("--caster-rule is an option of --scene");
    if (!c.scenePreset.empty() || c.sceneWidth)
        bad("--preset and --size are options of --scene and --frame");
    if (!c.scaling && !c.plot.empty()) {
        bad("--plot draws the scaling run: add --scaling");
    }
    if (!c.scaling && c.maxTriangles) {
        bad("--max-triangles limits the scaling run: add --scaling");
    }
    if (c.scaling && c.limits) {
        bad("--limits prints floors after the cycle table; it does not apply to --scaling");
    }
    if (c.scaling) {
        /* The scaling run has its own meshes and the moving light only. */
        for (const std::string &m : c.models) {
            if (m == "synthetic" || m == "all") {
                bad("--scaling --model takes glTF files and folders (the generated character "
                    "and the real characters of " SV_SHARED_MODELS_DIR " always run), not " +
                    m);
            }
        }
        if (c.regimeGiven) {
            bad("--scaling measures the moving light only: --regime fixed or both does not "
                "apply");
        }
        if (c.lightGiven) {
            bad("--light sets the fixed light, which --scaling does not measure");
        }
        if (c.json == "-" && c.plot == "-") {
            bad("--json - and --plot - cannot both go to standard output");
        }
    }
    if (c.timer == "rdtscp" && !cpu_has_rdtscp()) {
        bad("--timer rdtscp: this CPU has no RDTSCP (CPUID 0x80000001 EDX bit 27); use cpuid or "
            "lfence");
    }
    for (const BenchVariant *v : c.variants) {
        if ((v->isa & sv_cpu_isa_detected()) != v->isa) {
            bad(std::string("variant '") + v->name + "' needs an instruction set this CPU lacks");
        }
        if ((v->isa & sv_cpu_isa()) != v->isa) {
            bad(std::string("variant '") + v->name + "' is above the ISA limit " + limit_source(c));
        }
    }
    return c;
}

/* The variants to time, in the table's order, and why the others are not:
 * the library's sv_cpu_isa() decides, the ISA limit (--isa, SV_ISA)
 * included, as it does for dispatch and the tests. */
void choose_variants(const CliOptions &c, std::vector<const BenchVariant *> &chosen,
                     std::vector<SkippedVariant> &skipped) {
    for (const BenchVariant &v : bench_variants()) {
        const bool asked = c.variants.empty() ||
                           std::find(c.variants.begin(), c.variants.end(), &v) != c.variants.end();
        if ((v.isa & sv_cpu_isa_detected()) != v.isa) {
            skipped.push_back({v.name, "this CPU lacks its instruction set"});
        } else if ((v.isa & sv_cpu_isa()) != v.isa) {
            skipped.push_back({v.name, "above the ISA limit " + limit_source(c)});
        } else if (asked) {
            chosen.push_back(&v);
        }
    }
}

TimerKind timer_of(const CliOptions &c) {
    return c.timer == "rdtscp"   ? TimerKind::rdtscp
           : c.timer == "cpuid"  ? TimerKind::cpuid
           : c.timer == "lfence" ? TimerKind::lfence
                                 : timer_auto();
}

/* `--scaling`: the options it takes, handed to scaling_cli.cpp. */
int scaling(const CliOptions &c) {
    ScalingCommand cmd;
    ScalingOptions &o = cmd.options;
    o.quick = c.quick;
    o.runs = c.runs;
    o.rounds = c.table.rounds;
    o.maxTriangles = c.maxTriangles;
    o.seed = c.seed;
    o.targets = c.targets;
    o.batch = c.table.batch;
    o.routines = c.table.routines.empty() ? default_scaling_routines() : c.table.routines;
    o.sharedModels = SV_SHARED_MODELS_DIR;
    o.models = c.models;
    choose_variants(c, o.variants, cmd.skipped);
    cmd.json = c.json;
    cmd.plot = c.plot;
    cmd.timer = timer_of(c);
    cmd.timerAuto = c.timer == "auto";
    if (sv_isa_limit_name()) {
        cmd.isaLimit = limit_source(c);
    }
    cmd.variantsChosen = !c.variants.empty();
    return run_scaling(cmd);
}

/* --silhouette and --backface: the options they take. */
SeedCommand seed_command(const CliOptions &c) {
    SeedCommand cmd;
    cmd.quick = c.quick;
    cmd.json = c.json;
    cmd.timer = timer_of(c);
    cmd.maxTriangles = c.maxTriangles;
    cmd.seed = c.seed;
    cmd.sharedModels = SV_SHARED_MODELS_DIR;
    if (!c.casterRule.empty()) cmd.casterRule = c.casterRule;
    cmd.scenePreset = c.scenePreset;
    cmd.sceneWidth = c.sceneWidth;
    cmd.sceneHeight = c.sceneHeight;
    return cmd;
}

/* --frame's stencil method, tile and threshold as render takes them
 * (render_cli.cpp): the wisdom file loaded, then the planner's choice
 * wherever --stencil did not say (stencil_default.cpp). */
void take_frame_stencil(FrameBenchOptions &fo) {
    char wisdom[1024];
    sv_wisdom_load(sv_wisdom_default_path(wisdom, sizeof wisdom));
    svcli::StencilArgs s;
    s.method_given = fo.stencil_source == "option";
    if (s.method_given) {
        /* Checked when parsed. */
        (void)sv::render::stencil_method_by_name(fo.stencil, s.method);
    }
    svcli::take_stencil_default(s);
    fo.stencil = sv::render::stencil_method_name(s.method);
    fo.stencil_tile = s.tile;
    fo.hier_from_area_per_piece = s.rule.hier_from_area_per_piece;
    if (!s.method_given) fo.stencil_source = s.source;
}

int runs_for(int runs, int triangles) {
    if (triangles <= kReferenceTriangles) {
        return runs;
    }
    const long scaled = (long)runs * kReferenceTriangles / triangles;
    return (int)std::max<long>(std::min(runs, kMinScaledRuns), scaled);
}

} // namespace

void bench_usage(FILE *out) {
    std::fprintf(
        out,
        "usage: shadowvol bench [options]\n"
        "\n"
        "The cycle table of the paper's section 8: every routine of every variant this\n"
        "CPU runs, timed call by call with the serialised TSC, on the project's 1344-\n"
        "triangle character (models/character_1344.glb, the paper's sizes) lit by 64\n"
        "point lights chosen so that about 50%% of the triangles face the light and\n"
        "about 20%% of the SilEdges are on the silhouette, as in the paper (the header\n"
        "prints the ratios reached). Two regimes: a moving light (a different light\n"
        "every call; the headline) and a fixed one (the paper's hot-cache setup).\n"
        "Beside the paper's Pentium 4 figures. Every call is checked against the\n"
        "paper's C (c_ref; CalculateFacing and CalculateCullBits against a second\n"
        "computation); a row that differs prints FAILED and the exit status is 1.\n"
        "\n"
        "options:\n"
        "  --model M        what to time (repeatable): a glTF FILE (all its surfaces\n"
        "                   merged into one), a DIR of them, all (the bundled character\n"
        "                   and the real characters in ../shared/models), or synthetic\n"
        "                   (a torus with generated facing patterns at the paper's exact\n"
        "                   ratios). Default: the bundled character only\n"
        "  --light x,y,z,w  the fixed light (w 1: a point at x,y,z; w 0: a directional\n"
        "                   light from direction x,y,z), in the model's world space; the\n"
        "                   moving light still rotates through the 64 searched lights\n"
        "  --facing-ratio R, --silhouette-ratio R\n"
        "                   the ratios the light search aims at (default 0.5 and 0.2)\n"
        "  --json FILE      also write the results as JSON (schema shadowvol-bench/1);\n"
        "                   FILE - writes it to standard output and the table to stderr\n"
        "  --isa LEVEL      time only the variants within LEVEL, one of %s\n"
        "                   (c: the C variants only), as SV_ISA=LEVEL in the\n"
        "                   environment does\n"
        "  --runs N         timed regions (calls, or batches: --batch) per row (default\n"
        "                   %d; --quick %d), split over the rounds through all rows;\n"
        "                   meshes above 1344 triangles get proportionally fewer (at\n"
        "                   least %d)\n"
        "  --rounds N       passes through all rows (default 4, at most 64); a row\n"
        "                   keeps its lowest round median, so on a noisy machine (a\n"
        "                   shared VM) more rounds ride out more of its slow phases\n"
        "  --quick          a short run (a second or two) with every row still checked\n"
        "  --regime R       moving, fixed or both (default both)\n"
        "  --routine NAME   only this routine (repeatable), one of:\n"
        "                     %s\n"
        "  --variant NAME   only this variant (repeatable): %s\n"
        "  --timer T        auto, rdtscp, cpuid or lfence (default auto: rdtscp where the\n"
        "                   CPU has it, else cpuid)\n"
        "  --batch N        calls per timed region: auto (the default) times a batch of\n"
        "                   back-to-back calls, as many as fit in 2/3 of the L1 data\n"
        "                   cache, in a row of a routine that writes no indices whose call\n"
        "                   lasts under 50 TSC steps (or 50 x the empty region's jitter);\n"
        "                   1 never batches; 2 to %d batches every row (N times the\n"
        "                   calls: slower). Batched rows are marked xN and report ticks\n"
        "                   per call\n"
        "  --seed N         seed of the light search and of the synthetic patterns\n"
        "                   (default 1)\n"
        "  --limits         after each model's table: this core's best loads, gather\n"
        "                   lanes and bytes per tick, and from them each routine's\n"
        "                   floor (its unavoidable memory traffic) beside the best\n"
        "                   variant and the goals (bench/machine/machine_limits.h)\n"
        "  -h, --help       this text\n"
        "\n"
        "Results read back: shadowvol bench --compare A.json B.json\n"
        "                   shadowvol bench --report FILE.json [--regime fixed] [--routine R]\n"
        "                   shadowvol bench --report A.json B.json... --routine R\n"
        "--compare: two --json results (shadowvol-bench/1, or two shadowvol-scaling/1),\n"
        "per routine, variant, regime and model: the medians per element in ticks and\n"
        "in ns (ticks / each run's TSC rate) and their ratio B/A, then the geometric\n"
        "mean per variant. --report: a result's tables as Markdown (docs/results/), and\n"
        "the planner's choices it ran; --routine R: that routine's rows only; several\n"
        "bench results: routine R's row of each, a row per CPU.\n"
        "\n"
        "Scaling: shadowvol bench --scaling [--quick] [--plot FILE.svg] [--json FILE]\n"
        "The cost per element as the mesh grows, moving light, every variant this CPU\n"
        "runs: the generated character with each quad subdivided n x n (1344 n^2\n"
        "triangles, n = 1 2 3 5 9 14 27: 1344 to 979776) and the real characters in\n"
        "  %s\n"
        "when that folder exists. Per routine (default: create_shadow_volume,\n"
        "calculate_facing and the four kernels) a table of ticks per element, min and\n"
        "median, a row per mesh, with the cache (L1D, L2, L3, DRAM) that holds the\n"
        "mesh's working set; every call checked against c_ref. Under a minute on a\n"
        "small VM; --quick (n = 1 3 9, fewer runs) a few seconds.\n"
        "  --scaling        run it instead of the cycle table\n"
        "  --plot FILE      also draw it as SVG: ticks per element against triangles (log\n"
        "                   scale), a line per variant, the L1D/L2/L3 sizes marked where\n"
        "                   the routine's working set fills them; - for standard output\n"
        "  --json FILE      with --scaling: schema shadowvol-scaling/1\n"
        "  --max-triangles N\n"
        "                   leave out the meshes above N triangles\n"
        "  --runs N         with --scaling: per row on a mesh of 1344 triangles or fewer\n"
        "                   (default %d; --quick %d), in proportion fewer above (at\n"
        "                   least %d; --quick %d)\n"
        "  --model M        also measure your own mesh: a glTF FILE or a DIR of them\n"
        "                   (repeatable; every surface merged into one)\n"
        "  --routine, --variant, --isa, --timer, --batch, --rounds, --seed,\n"
        "  --facing-ratio and --silhouette-ratio apply as above; --light and --regime\n"
        "  do not.\n"
        "\n"
        "Seed 003: shadowvol bench --silhouette [--quick] [--json FILE] [--max-triangles N]\n"
        "Routine find_silhouette: the classic candidate list, the hash table (8 to 64\n"
        "columns, 16- and 32-bit cells, scalar and SSE2) and the connectivity table\n"
        "(four kernels) beside the paper's SilEdges (siledge_<variant>), on the generated\n"
        "character at 1344, 33600 and 65856 triangles (the seed's Dino and Dragon sizes)\n"
        "and spot and koala from the real characters' folder, the light above the mesh\n"
        "and beside it (16 jittered lights each, one per call); temporary and permanent\n"
        "memory, the connectivity table's precomputation (ours O(n), the seed's O(n^2)),\n"
        "every call checked against the SilEdges, and the seed's own table beside ours.\n"
        "JSON schema shadowvol-silhouette/1. A hash table too narrow for a mesh reports\n"
        "overflow (not a failure). --quick: the two smaller generated meshes, short rows.\n"
        "\n"
        "Seed 001: shadowvol bench --backface [--quick] [--json FILE] [--max-triangles N]\n"
        "Routine backface_cull (the camera's back faces: the front-facing count and the\n"
        "vertex bit array): noncompact (32-byte triangles, float), compact (16 bytes,\n"
        "16-bit normal), compact_sse2 (four per step), compact_sse2_prefetch,\n"
        "compact_avx2, compact_avx512, in ticks per triangle from 1344 to 7 million\n"
        "triangles (L1 to beyond L3), each call checked; the 16-bit decisions compared\n"
        "with the float ones and judged by the exact predicate. JSON schema\n"
        "shadowvol-backface/1. --quick: three sizes up to 108,864 triangles.\n"
        "\n"
        "Per-frame planes: shadowvol bench --planes [--quick] [--json FILE] [--max-triangles N]\n"
        "sv_derive_planes (every variant) against facing straight from the positions\n"
        "(BFG), 1 and 4 moving lights a frame, on the bundled and real characters and a\n"
        "100,352-triangle grid; every call bit-identical to the C references (docs/PLANES.md).\n"
        "JSON schema shadowvol-planes/1. --quick: the character and a small grid.\n"
        "\n"
        "Seed 002: shadowvol bench --extrude [--quick] [--json FILE] [--max-triangles N]\n"
        "The seed's vertex program emulated on the CPU (every variant, a range and none)\n"
        "beside the paper's pipeline (sv_shadow_volume_for_light), 16 moving lights, on\n"
        "the bundled and real characters and the open one; every call checked; the\n"
        "seed's buffers against the paper's index lists (docs/EXTRUSION.md); on the skinned\n"
        "characters, each normal source of the seed's Figure 4 (skinned per vertex, face\n"
        "weights, recomputed, neighbours) a frame beside the program alone, and its bytes.\n"
        "JSON schema shadowvol-extrude/1. --quick: the bundled character, the demo's.\n"
        "\n"
        "Per frame: shadowvol bench --scene [--quick] [--caster-rule R] [--json FILE]\n"
        "           [--preset simple|knights|demo|FILE] [--size WxH]\n"
        "The demo scene's frames (8 at 640x512; --quick 4 at 320x256) with only what each\n"
        "requires and with everything, on 1 thread and every core, as ratios of one run;\n"
        "each shortcut alone switched off; the culling decision timed on both sides for\n"
        "the terrain under a headlight and the character inside the lamp. Every frame\n"
        "checked against its full frame and across thread counts (docs/SCENES.md).\n"
        "--caster-rule R (auto, closed, general; default auto) for those runs; then the\n"
        "frames under closed against auto (docs/CASTERS.md): the open terrain's cost.\n"
        "Then the stencil pass per method (bf, db, hier) on 1 thread and every core:\n"
        "ms per frame (the minimum of the same runs), pixels tested, and whether each\n"
        "light's stencil equals bf's. --preset simple|knights|demo|FILE and --size WxH:\n"
        "that table alone, for that scene (docs/RENDERING.md).\n"
        "JSON schema shadowvol-scene-bench/1.\n"
        "\n"
        "The general rule: shadowvol bench --casters [--quick] [--json FILE]\n"
        "Min TSC ticks per triangle of a whole volume build, warm, in one process: the\n"
        "closed rule (the paper's, the floor), two-sided and the direct general kernels\n"
        "(and their C), on the open character, the generated open cases and the demo\n"
        "terrain, three lights, z-pass and z-fail (docs/CASTERS.md). --quick: the point\n"
        "light only, shorter rows. JSON schema shadowvol-casters-bench/1.\n"
        "\n"
        "The whole frame: shadowvol bench --frame [--preset simple|knights|demo|FILE]\n"
        "                 [--size WxH] [--threads N] [--stencil bf|db|hier|auto] [--frames N]\n"
        "                 [--runs N] [--no-mesa]\n"
        "                 [--out DIR] [--quick] [--json FILE]\n"
        "A scene (default the demo scene at 1280x720, 8 frames, every core) with the\n"
        "camera orbiting and a light moving every frame: each pass (posing, volumes,\n"
        "depth, stencil, lighting) in ms, the minimum of --runs drawings (default 3),\n"
        "beside its floor (the bytes it must touch at the memory rate measured in the\n"
        "run) and beside Mesa's llvmpipe drawing the same frame on as many threads\n"
        "(LP_NUM_THREADS is read once per process: one process per thread count).\n"
        "Checked: the runs give the same bytes, and Mesa's picture agrees off edges\n"
        "(docs/FRAME.md). --out DIR: the last frame, ours and Mesa's, as PNG. --quick:\n"
        "2 frames, 1 run. Our stencil pass: --stencil's method, else the planner's\n"
        "choice as render takes it (the wisdom file's, else auto); the report and the\n"
        "JSON say which, from where, with hier's tile and auto's threshold.\n"
        "JSON schema shadowvol-frame-bench/1.\n"
        "\n"
        "The automatic stencil method's rule: shadowvol bench --stencil-rule [--quick]\n"
        "                 [--preset P] [--size WxH] [--json FILE]\n"
        "Every light of the simple, knights and demo presets (or P alone; 3 frames) and\n"
        "of the render table's models (tools/render_models.sh: point, spot and sun, in\n"
        "z-pass and z-fail), at 1280x1024 (--quick: 320x256, 1 frame, of the models the\n"
        "bundled character alone), drawn by bf and by hier on 1 thread, the minimum of\n"
        "3 runs (--quick 2), each light's pieces and\n"
        "their area, and the threshold of area per piece (pixels)\n"
        "above which --stencil auto takes hier that gives the least\n"
        "total time (docs/results/stencil_rule/). A light whose hier stencil differs\n"
        "from bf's fails the check. JSON schema shadowvol-stencil-rule/1.\n"
        "\n"
        "Seed 004's Figure 1: shadowvol bench --figure1 --out DIR [--preset P] [--size WxH]\n"
        "A preset's first frame and first light (default knights at 640x400) drawn\n"
        "plainly four times: the correct shadows, the low-resolution shadows (each 8x8\n"
        "tile's sample over the tile), the boundary tiles in green, and the image put\n"
        "together from both (boundary tiles darker), as DIR/P_correct.png,\n"
        "P_lowres.png, P_boundary.png, P_composed.png. Exit 1 if the composed image\n"
        "differs from the correct one or hier's stencil from bf's (docs/RENDERING.md).\n"
        "\n"
        "Units are TSC ticks (a fixed reference clock on modern CPUs, not core cycles);\n"
        "the header prints the TSC rate. Options take their value as --opt V or --opt=V.\n"
        "Exit status: 0 done, 1 a row failed its check, 2 bad arguments, 3 a model\n"
        "could not be loaded.\n",
        kIsaLevels, kDefaultRuns, kQuickRuns, kMinScaledRuns,
        wrap(routine_list(), 58, "\n                     ").c_str(), variant_list().c_str(),
        kMaxBatch, SV_SHARED_MODELS_DIR, kDefaultScalingRuns, kQuickScalingRuns, kMinScalingRuns,
        kMinQuickScalingRuns);
}

int bench_main(int argc, char **argv) {
    if (is_compare_or_report(argc, argv)) { /* bench/report/compare.h */
        return compare_main(argc, argv);
    }
    CliOptions c;
    ModelList models;
    try {
        c = parse(argc, argv);
        if (c.help) {
            bench_usage(stdout);
            return 0;
        }
        if (c.scaling) {
            return scaling(c);
        }
        if (c.silhouette) {
            return run_silhouette_bench(seed_command(c));
        }
        if (c.backface) {
            return run_backface_bench(seed_command(c));
        }
        if (c.planes) {
            return run_planes_bench(seed_command(c));
        }
        if (c.extrude) {
            return run_extrude_bench(seed_command(c));
        }
        if (c.scene) {
            return run_scene_bench(seed_command(c));
        }
        if (c.casters) {
            return run_casters_bench(seed_command(c));
        }
        if (c.stencilRule) {
            return run_stencil_rule_bench(seed_command(c));
        }
        if (c.frame) {
            take_frame_stencil(c.frameOptions);
            return run_frame_bench(seed_command(c), c.frameOptions);
        }
        if (c.figure1) {
            return run_figure1(seed_command(c), c.frameOptions.out_dir, 8);
        }
        models = resolve_models(c.models, kBundledModel, SV_SHARED_MODELS_DIR);
    } catch (const UsageError &e) {
        std::fprintf(stderr, "shadowvol bench: %s\nTry 'shadowvol bench --help'.\n",
                     e.message.c_str());
        return kExitUsage;
    } catch (const ModelListError &e) {
        std::fprintf(stderr, "shadowvol bench: %s\n", e.what());
        return kExitBadModel;
    }

    BenchRun run;
    run.seed = c.seed;
    if (sv_isa_limit_name()) {
        run.isaLimit = limit_source(c);
    }
    run.variantsChosen = !c.variants.empty();
    run.realModels = models.note;
    run.options = c.table;
    run.options.runs = c.runs ? c.runs : c.quick ? kQuickRuns : kDefaultRuns;
    if (run.options.routines.empty()) {
        run.options.routines.assign(kAllRoutines, kAllRoutines + kNumRoutines);
    }
    std::sort(run.options.routines.begin(), run.options.routines.end());
    choose_variants(c, run.options.variants, run.skipped);

    try {
        OutputFile json("--json", c.json);
        FILE *out = json.is_stdout() ? stderr : stdout;

        /* Every workload before any measurement: a model that does not load
         * fails at once. */
        for (const ModelSpec &m : models.models) {
            ModelRun mr;
            try {
                mr.workload = m.synthetic
                                  ? make_synthetic_workload(c.seed, kLights, c.targets.facing,
                                                            c.targets.silhouette)
                                  : make_model_workload(m.path, c.targets, kLights, c.seed,
                                                        c.hasLight ? &c.light : nullptr);
            } catch (const WorkloadError &e) {
                std::fprintf(stderr, "shadowvol bench: %s\n", e.what());
                return m.synthetic ? kExitUsage : kExitBadModel;
            }
            if (m.synthetic) {
                mr.workload.origin.fixedGiven = c.hasLight;
            }
            run.models.push_back(std::move(mr));
        }

        run.machine = measure_machine(timer_of(c), c.timer == "auto", c.quick ? 1000 : 5000, 0.05);
        print_run_header(out, run);
        if (c.limits) {
            run.limits = measure_machine_limits();
            run.limitsMeasured = true;
        }
        for (ModelRun &m : run.models) {
            TableOptions o = run.options;
            o.runs = runs_for(o.runs, m.workload.numTriangles);
            const int perRound = (o.runs + o.rounds - 1) / o.rounds;
            o.warmup = std::min(m.workload.numMoving, perRound); /* up to one turn of lights */
            m.table = run_cycle_table(o, run.machine, m.workload);
            print_model(out, run, m);
            if (c.limits) {
                print_limits(out, run.limits, m.workload, m.table);
            }
        }
        print_notes(out, run);

        if (json.wanted() && !json.write(bench_json(run))) {
            std::fprintf(stderr, "shadowvol bench: --json: cannot write %s: %s\n",
                         json.name().c_str(), std::strerror(errno));
            return kExitCheckFailed;
        }
    } catch (const OutputFileError &e) {
        std::fprintf(stderr, "shadowvol bench: %s\nTry 'shadowvol bench --help'.\n", e.what());
        return kExitUsage;
    } catch (const std::exception &e) {
        std::fprintf(stderr, "shadowvol bench: internal error: %s\n", e.what());
        return kExitCheckFailed;
    }

    return check_failed_status(run);
}

} // namespace svbench
