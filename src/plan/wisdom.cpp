/*
 * The wisdom file: the plans `shadowvol tune` measured, per CPU model.
 *
 *   shadowvol-wisdom 1
 *   cpu AuthenticAMD 23/1/2 avx2 AMD EPYC
 *   class 0 calculate_facing avx2 3421.5
 *   ...                                      (one line per class and routine)
 *   class 0 skinning avx512 2.7              (deforming surfaces: ticks per
 *   class 0 skin_planes none 6.3              triangle; "none": two passes)
 *   stencil auto 32 65.0                     (the stencil pass's method, hier's
 *                                             tile side, auto's threshold:
 *                                             sv_stencil_choice; "inf" allowed)
 *   cpu <another CPU's key>
 *   ...
 *
 * A section applies only to the CPU whose sv_cpu_model_key it carries (the
 * ISA level is part of the key, so a run under SV_ISA=sse2 keeps its own).
 * Saving rewrites this CPU's section and keeps the others. A malformed file
 * is refused whole: nothing is taken from it.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <sys/stat.h>
#ifdef _WIN32
#include <direct.h>
#define WIN32_LEAN_AND_MEAN
#include <windows.h> /* MoveFileExA */
#endif

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "plan_internal.h"

namespace {

constexpr const char *kHeader = "shadowvol-wisdom 1";

struct Entry {
    std::string variant;
    double ticks = 0;
};
/* cpu key -> class -> routine -> entry; the deform routines (skinning,
 * derive_planes, skin_planes) are numbered SV_NUM_ROUTINES + r. */
using Sections = std::map<std::string, std::map<int, std::map<int, Entry>>>;
/* cpu key -> its "stencil" line. */
struct StencilLine {
    std::string method;
    int tile = 0;
    double threshold = 0;
};
using StencilLines = std::map<std::string, StencilLine>;

constexpr int kAllRoutines = (int)SV_NUM_ROUTINES + (int)SV_NUM_DEFORM_ROUTINES;

const char *routine_name(int r) {
    return r < SV_NUM_ROUTINES ? sv_routine_name((sv_routine)r)
                               : sv_deform_routine_name((sv_deform_routine)(r - SV_NUM_ROUTINES));
}

int routine_number(const std::string &name) {
    for (int r = 0; r < kAllRoutines; r++) {
        if (name == routine_name(r)) return r;
    }
    return -1;
}

/* "stencil METHOD TILE THRESHOLD" (THRESHOLD through strtod, so "inf"
 * reads); false for anything else, or values sv_stencil_choice refuses. */
bool parse_stencil_line(const std::string &line, StencilLine &out) {
    std::istringstream ls(line);
    std::string word, threshold, extra;
    if (!(ls >> word >> out.method >> out.tile >> threshold) || word != "stencil" || (ls >> extra))
        return false;
    char *end = nullptr;
    out.threshold = std::strtod(threshold.c_str(), &end);
    if (end == threshold.c_str() || *end != 0 || !(out.threshold >= 0)) return false;
    if (!(out.tile == 4 || out.tile == 8 || out.tile == 16 || out.tile == 32)) return false;
    return out.method == "bf" || out.method == "db" || out.method == "hier" || out.method == "auto";
}

bool parse(const std::string &path, Sections &out, std::vector<std::string> &order,
           StencilLines &stencil) {
    std::ifstream in(path);
    if (!in) return false;
    std::string line;
    if (!std::getline(in, line) || line != kHeader) return false;
    std::string cpu;
    while (std::getline(in, line)) {
        if (line.empty()) continue;
        if (line.rfind("cpu ", 0) == 0) {
            cpu = line.substr(4);
            if (!out.count(cpu)) order.push_back(cpu);
            out[cpu];
            continue;
        }
        if (line.rfind("stencil ", 0) == 0) {
            StencilLine st;
            if (cpu.empty() || !parse_stencil_line(line, st)) return false;
            stencil[cpu] = st;
            continue;
        }
        std::istringstream ls(line);
        std::string word, routine, variant;
        int cls = -1;
        double ticks = -1;
        if (!(ls >> word >> cls >> routine >> variant >> ticks) || word != "class" || cpu.empty() ||
            cls < 0 || cls >= SV_NUM_SIZE_CLASSES || !(ticks >= 0)) {
            return false;
        }
        const int r = routine_number(routine);
        if (r < 0) return false;
        out[cpu][cls][r] = Entry{variant, ticks};
    }
    return true;
}

std::string this_cpu() {
    char key[256];
    return sv_cpu_model_key(key, sizeof key);
}

bool make_parent_dirs(const std::string &path) {
    for (size_t i = 1; i < path.size(); i++) {
        if (path[i] != '/') continue;
        const std::string dir = path.substr(0, i);
#ifdef _WIN32
        if (_mkdir(dir.c_str()) != 0 && errno != EEXIST) return false;
#else
        if (mkdir(dir.c_str(), 0777) != 0 && errno != EEXIST) return false;
#endif
    }
    return true;
}

} // namespace

extern "C" {

const char *sv_wisdom_default_path(char *buf, size_t size) {
    if (!buf || size == 0) return buf;
    buf[0] = 0;
    const char *env = std::getenv("SV_WISDOM");
    const char *xdg = std::getenv("XDG_CACHE_HOME");
    const char *home = std::getenv("HOME");
    if (env && *env) {
        std::snprintf(buf, size, "%s", env);
    } else if (xdg && *xdg) {
        std::snprintf(buf, size, "%s/shadowvol/wisdom", xdg);
    } else if (home && *home) {
        std::snprintf(buf, size, "%s/.cache/shadowvol/wisdom", home);
    }
    return buf;
}

int sv_wisdom_load(const char *path) {
    if (!path || !*path) return -1;
    Sections all;
    std::vector<std::string> order;
    StencilLines stencil;
    if (!parse(path, all, order, stencil)) return -1;
    const auto st = stencil.find(this_cpu());
    if (st != stencil.end()) {
        const StencilLine &l = st->second;
        svplan::set_stencil_choice(l.method.c_str(), l.tile, l.threshold, 2);
    }
    const auto it = all.find(this_cpu());
    if (it == all.end()) return 0;
    int classes = 0;
    for (const auto &[cls, routines] : it->second) {
        const char *names[SV_NUM_ROUTINES] = {};
        double ticks[SV_NUM_ROUTINES] = {};
        bool volume = false;
        for (const auto &[r, e] : routines) {
            if (r >= SV_NUM_ROUTINES) {
                /* Names the animation layer checks against its tables. */
                svplan::set_deform_choice(cls, r - SV_NUM_ROUTINES, e.variant.c_str(), e.ticks, 2);
                continue;
            }
            names[r] = e.variant.c_str();
            ticks[r] = e.ticks;
            volume = true;
        }
        /* make_plan copies the static names, so e.variant may go. */
        if (volume) svplan::install(cls, svplan::make_plan(cls, "wisdom", names, ticks), 2);
        classes++;
    }
    return classes;
}

int sv_wisdom_save(const char *path) {
    if (!path || !*path || !make_parent_dirs(path)) return -1;
    Sections all;
    std::vector<std::string> order;
    StencilLines stencil;
    struct stat st;
    if (stat(path, &st) == 0 && !parse(path, all, order, stencil))
        return -1; /* never clobber a file we cannot read */
    const std::string cpu = this_cpu();
    if (!all.count(cpu)) order.push_back(cpu);
    auto &mine = all[cpu];
    for (int c = 0; c < SV_NUM_SIZE_CLASSES; c++) {
        sv_plan p;
        if (!svplan::measured(c, &p)) continue;
        for (int r = 0; r < SV_NUM_ROUTINES; r++) mine[c][r] = Entry{p.variant[r], p.ticks[r]};
    }
    for (int c = 0; c < SV_NUM_SIZE_CLASSES; c++) {
        for (int r = 0; r < SV_NUM_DEFORM_ROUTINES; r++) {
            sv_deform_choice d;
            if (svplan::measured_deform_choice(c, r, &d)) {
                mine[c][SV_NUM_ROUTINES + r] = Entry{d.variant, d.ticks};
            }
        }
    }
    sv_stencil_choice sc;
    if (svplan::measured_stencil_choice(&sc))
        stencil[cpu] = StencilLine{sc.method, sc.tile, sc.hier_from_area_per_piece};
    const std::string tmp = std::string(path) + ".tmp";
    {
        std::ofstream out(tmp);
        if (!out) return -1;
        out << kHeader << "\n";
        for (const std::string &key : order) {
            out << "cpu " << key << "\n";
            const auto sl = stencil.find(key);
            if (sl != stencil.end()) {
                char t[64];
                std::snprintf(t, sizeof t, "%.1f", sl->second.threshold); /* "inf" as such */
                out << "stencil " << sl->second.method << " " << sl->second.tile << " " << t
                    << "\n";
            }
            for (const auto &[cls, routines] : all[key]) {
                for (const auto &[r, e] : routines) {
                    char t[64];
                    std::snprintf(t, sizeof t, r < SV_NUM_ROUTINES ? "%.1f" : "%.3f", e.ticks);
                    out << "class " << cls << " " << routine_name(r) << " " << e.variant << " " << t
                        << "\n";
                }
            }
        }
        if (!out.flush()) return -1;
    }
#ifdef _WIN32
    /* Windows' rename() refuses an existing target: every save after the
     * first would fail. MoveFileEx replaces it (found by the wine run of
     * the suite, docs/PLATFORMS.md). */
    return MoveFileExA(tmp.c_str(), path, MOVEFILE_REPLACE_EXISTING) ? 0 : -1;
#else
    return std::rename(tmp.c_str(), path) == 0 ? 0 : -1;
#endif
}

} // extern "C"
