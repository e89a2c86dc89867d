/*
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "bench_cli.h"

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>

#include "cycle_table.h"
#include "timer.h"

namespace svbench {

namespace {

/* Full table (6 routines x 3 variants x 2 regimes) in a few seconds on a
 * small VM whose cpuid traps; --quick in about one. */
constexpr int kDefaultRuns = 4000;
constexpr int kQuickRuns = 256;
constexpr int kMaxRuns = 1000000;
constexpr int kPatterns = 64;

struct UsageError {
    std::string message;
};

[[noreturn]] void bad(const std::string &message) {
    throw UsageError{message};
}

long long parse_int(const std::string &opt, const std::string &s, long long lo, long long hi) {
    errno = 0;
    char *end = nullptr;
    const bool digits = !s.empty() && s.find_first_not_of("0123456789") == std::string::npos;
    long long v = digits ? std::strtoll(s.c_str(), &end, 10) : 0;
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
    unsigned long long v = digits ? std::strtoull(s.c_str(), &end, 10) : 0;
    if (!digits || errno == ERANGE || *end) {
        bad("--seed needs a whole number from 0 to 18446744073709551615, not '" + s + "'");
    }
    return v;
}

std::string routine_list() {
    std::string s;
    for (int i = 0; i < kNumRoutines; i++) {
        s += (i ? ", " : "");
        s += routine_name((Routine)i);
    }
    return s;
}

std::string variant_list() {
    int n = 0;
    const sv_variant *v = sv_variants(&n);
    std::string s;
    for (int i = 0; i < n; i++) {
        s += (i ? ", " : "");
        s += v[i].name;
    }
    return s;
}

/* Breaks a ", "-separated list into lines of at most WIDTH characters. */
std::string wrap(const std::string &list, size_t width, const char *newline) {
    std::string out, line;
    size_t pos = 0;
    while (pos < list.size()) {
        size_t comma = list.find(", ", pos);
        std::string item =
            list.substr(pos, comma == std::string::npos ? std::string::npos : comma + 1 - pos);
        pos = comma == std::string::npos ? list.size() : comma + 2;
        if (!line.empty() && line.size() + 1 + item.size() > width) {
            out += line + newline;
            line.clear();
        }
        line += (line.empty() ? "" : " ") + item;
    }
    return out + line;
}

} // namespace

void bench_usage(FILE *out) {
    std::fprintf(
        out,
        "usage: shadowvol bench [options]\n"
        "\n"
        "The cycle table of the paper's section 8: every routine of every variant this\n"
        "CPU runs, timed call by call with the serialised TSC on a synthetic mesh of the\n"
        "paper's size (1344 triangles, 2016 SilEdges, 50%% facing, 20%% silhouette), with\n"
        "a moving light (a different facing pattern every call; the headline) and a fixed\n"
        "one (the paper's hot-cache setup), beside the paper's Pentium 4 figures. Every\n"
        "call is checked against the paper's C (c_ref); a row that differs prints FAILED\n"
        "and the exit status is 1.\n"
        "\n"
        "options:\n"
        "  --runs N         timed regions (calls, or batches: --batch) per row (default\n"
        "                   %d; --quick %d), split over 4 rounds through all rows\n"
        "  --quick          a short run (about a second) with every row still checked\n"
        "  --regime R       moving, fixed or both (default both)\n"
        "  --routine NAME   only this routine (repeatable), one of:\n"
        "                     %s\n"
        "  --variant NAME   only this variant (repeatable): %s\n"
        "  --timer T        auto, rdtscp, cpuid or lfence (default auto: rdtscp where the\n"
        "                   CPU has it, else cpuid)\n"
        "  --batch N        calls per timed region: auto (the default) times a batch of\n"
        "                   back-to-back calls, as many as their input copies fit in 2/3\n"
        "                   of the L1 data cache, in a count routine's row whose call\n"
        "                   lasts under 50 TSC steps (or 50 x the empty region's jitter);\n"
        "                   1 never batches; 2 to %d batches every row (N times the\n"
        "                   calls: slower). Batched rows are marked xN and report ticks\n"
        "                   per call\n"
        "  --seed N         seed of the facing patterns (default 1)\n"
        "  -h, --help       this text\n"
        "\n"
        "Units are TSC ticks (a fixed reference clock on modern CPUs, not core cycles);\n"
        "the header prints the TSC rate. Options take their value as --opt V or --opt=V.\n",
        kDefaultRuns, kQuickRuns, wrap(routine_list(), 58, "\n                     ").c_str(),
        variant_list().c_str(), kMaxBatch);
}

int bench_main(int argc, char **argv) {
    TableOptions o;
    int runs = 0;
    bool quick = false;
    std::string timer = "auto";
    try {
        for (int i = 1; i < argc; i++) {
            std::string arg = argv[i], opt = arg, value;
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
                bench_usage(stdout);
                return 0;
            } else if (opt == "--quick" && !hasValue) {
                quick = true;
            } else if (opt == "--runs") {
                runs = (int)parse_int(opt, need(), 1, kMaxRuns);
            } else if (opt == "--regime") {
                std::string r = need();
                if (r == "moving" || r == "fixed" || r == "both") {
                    o.moving = r != "fixed";
                    o.fixed = r != "moving";
                } else {
                    bad("--regime must be moving, fixed or both, not '" + r + "'");
                }
            } else if (opt == "--routine") {
                std::string r = need();
                Routine rt;
                if (!routine_by_name(r, &rt)) {
                    bad("unknown routine '" + r + "' (routines: " + routine_list() + ")");
                }
                if (std::find(o.routines.begin(), o.routines.end(), rt) == o.routines.end()) {
                    o.routines.push_back(rt);
                }
            } else if (opt == "--variant") {
                std::string v = need();
                const sv_variant *var = sv_variant_by_name(v.c_str());
                if (!var) {
                    bad("unknown variant '" + v + "' (variants: " + variant_list() + ")");
                }
                if ((var->isa & sv_cpu_isa()) != var->isa) {
                    bad("variant '" + v + "' needs an instruction set this CPU lacks");
                }
                if (std::find(o.variants.begin(), o.variants.end(), var) == o.variants.end()) {
                    o.variants.push_back(var);
                }
            } else if (opt == "--timer") {
                timer = need();
                if (timer != "auto" && timer != "rdtscp" && timer != "cpuid" && timer != "lfence") {
                    bad("--timer must be auto, rdtscp, cpuid or lfence, not '" + timer + "'");
                }
            } else if (opt == "--batch") {
                const std::string b = need();
                try {
                    o.batch = b == "auto" ? 0 : (int)parse_int(opt, b, 1, kMaxBatch);
                } catch (const UsageError &) {
                    bad("--batch needs auto or a whole number from 1 to " +
                        std::to_string(kMaxBatch) + ", not '" + b + "'");
                }
            } else if (opt == "--seed") {
                o.seed = parse_seed(need());
            } else if (hasValue && opt == "--quick") {
                bad("--quick takes no value");
            } else if (arg.rfind("-", 0) == 0) {
                bad("unknown option '" + arg + "'");
            } else {
                bad("unexpected argument '" + arg + "'");
            }
        }
        if (timer == "rdtscp" && !cpu_has_rdtscp()) {
            bad("--timer rdtscp: this CPU has no RDTSCP (CPUID 0x80000001 EDX bit 27); use "
                "cpuid or lfence");
        }
    } catch (const UsageError &e) {
        std::fprintf(stderr, "shadowvol bench: %s\nTry 'shadowvol bench --help'.\n",
                     e.message.c_str());
        return 2;
    }

    o.timerAuto = timer == "auto";
    o.timer = timer == "rdtscp"   ? TimerKind::rdtscp
              : timer == "cpuid"  ? TimerKind::cpuid
              : timer == "lfence" ? TimerKind::lfence
                                  : timer_auto();
    o.runs = runs ? runs : quick ? kQuickRuns : kDefaultRuns;
    o.patterns = kPatterns;
    o.warmup = kPatterns; /* one turn through the patterns */
    o.overheadTries = quick ? 1000 : 5000;
    o.tscSeconds = 0.05;
    try {
        return run_cycle_table(o, stdout);
    } catch (const std::exception &e) {
        std::fprintf(stderr, "shadowvol bench: internal error: %s\n", e.what());
        return 1;
    }
}

} // namespace svbench
