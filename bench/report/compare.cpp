/*
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "compare.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "shadowvol_plan.h"

namespace svbench {

namespace {

using nlohmann::json;

struct DocError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

struct Row {
    std::string model, routine, variant, regime;
    long long triangles = 0;
    double median = 0, min = 0; /* ticks per element */
    bool checked = false;
};

/* One entry of "plans": the planner's choice for one model's size. */
struct PlanChoice {
    std::string model, source;
    long long triangles = 0, class_triangles = 0;
    int size_class = 0;
    std::vector<std::pair<std::string, std::string>> variants; /* routine, variant */
};

struct Doc {
    std::string path, schema, cpu, commit, timer, compiler;
    double tsc_hz = 0;
    std::vector<std::string> isa;
    std::string family; /* "family 25 model 1" from cpu.model_key; "" in older documents */
    std::vector<Row> rows;
    std::vector<std::string> variants; /* in the document's order */
    std::vector<PlanChoice> plans;     /* empty in documents written before them */
};

void order_variants(std::vector<std::string> &v);

Doc read_doc(const std::string &path) {
    std::ifstream f(path, std::ios::binary);
    if (!f) throw DocError(path + ": cannot open");
    std::stringstream ss;
    ss << f.rdbuf();
    json j;
    try {
        j = json::parse(ss.str());
    } catch (const json::exception &e) {
        throw DocError(path + ": not JSON (" + std::string(e.what()).substr(0, 200) + ")");
    }
    Doc d;
    d.path = path;
    try {
        d.schema = j.at("schema").get<std::string>();
        if (d.schema != "shadowvol-bench/1" && d.schema != "shadowvol-scaling/1") {
            throw DocError(path + ": schema " + d.schema +
                           " (expected shadowvol-bench/1 or shadowvol-scaling/1)");
        }
        d.cpu = j.at("cpu").at("model").get<std::string>();
        d.tsc_hz = j.at("cpu").value("tsc_hz", 0.0);
        d.commit = j.value("commit", std::string("?"));
        d.timer = j.value("timer", std::string("?"));
        d.compiler = j.value("compiler", std::string("?"));
        if (j.at("cpu").contains("isa"))
            d.isa = j.at("cpu").at("isa").get<std::vector<std::string>>();
        /* "AuthenticAMD 25/1/1 avx2 AMD EPYC": vendor, family/model/stepping, ... */
        unsigned fam = 0, mod = 0, step = 0;
        const std::string key = j.at("cpu").value("model_key", std::string());
        const size_t sp = key.find(' ');
        if (sp != std::string::npos &&
            std::sscanf(key.c_str() + sp + 1, "%u/%u/%u", &fam, &mod, &step) == 3) {
            d.family = "family " + std::to_string(fam) + " model " + std::to_string(mod);
        }
        if (j.contains("plans")) {
            for (const json &p : j.at("plans")) {
                PlanChoice c;
                c.model = p.at("model").get<std::string>();
                c.triangles = p.at("triangles").get<long long>();
                c.size_class = p.at("size_class").get<int>();
                c.class_triangles = p.value("class_triangles", 0LL);
                c.source = p.at("source").get<std::string>();
                /* In the planner's routine order (A, B, C-F), not the
                 * object's (alphabetical); a routine this build does not
                 * know keeps its place after them. */
                const json &vs = p.at("variants");
                for (int r = 0; r < SV_NUM_ROUTINES; r++) {
                    const char *name = sv_routine_name((sv_routine)r);
                    if (vs.contains(name))
                        c.variants.emplace_back(name, vs.at(name).get<std::string>());
                }
                for (const auto &kv : vs.items()) {
                    const bool known = std::any_of(c.variants.begin(), c.variants.end(),
                                                   [&](const auto &rv) {
                                                       return rv.first == kv.key();
                                                   });
                    if (!known) c.variants.emplace_back(kv.key(), kv.value().get<std::string>());
                }
                d.plans.push_back(c);
            }
        }
        for (const json &r : j.at("results")) {
            Row row;
            row.model = r.at("model").get<std::string>();
            row.routine = r.at("routine").get<std::string>();
            row.variant = r.at("variant").get<std::string>();
            row.regime = r.value("regime", std::string("moving"));
            row.triangles = r.value("triangles", 0LL);
            row.median = r.at("ticks_per_element_median").get<double>();
            row.min = r.value("ticks_per_element_min", row.median);
            row.checked = r.value("checked", false);
            if (std::find(d.variants.begin(), d.variants.end(), row.variant) == d.variants.end()) {
                d.variants.push_back(row.variant);
            }
            d.rows.push_back(row);
        }
    } catch (const json::exception &e) {
        throw DocError(path + ": " + std::string(e.what()).substr(0, 200));
    }
    order_variants(d.variants);
    return d;
}

/* The table's order of variants: the reference, the paper's, then the
 * newer ISAs; any other after them, as first seen. */
void order_variants(std::vector<std::string> &v) {
    static const char *const kOrder[] = {"c_ref",  "c_branchless", "sse2_paper", "sse2",
                                         "avx2",   "avx512",       "avx512vbmi", "planned_kernels",
                                         "planned"};
    constexpr int kKnown = (int)(sizeof kOrder / sizeof kOrder[0]);
    auto rank = [](const std::string &name) {
        for (int i = 0; i < kKnown; i++) {
            if (name == kOrder[i]) return i;
        }
        return kKnown;
    };
    std::stable_sort(v.begin(), v.end(),
                     [&](const std::string &a, const std::string &b) { return rank(a) < rank(b); });
}

std::string fixed(double v, int digits) {
    char b[32];
    std::snprintf(b, sizeof b, "%.*f", digits, v);
    return b;
}

std::string header(const Doc &d) {
    return d.cpu + ", TSC " + fixed(d.tsc_hz / 1e9, 2) + " GHz, timer " + d.timer + ", " +
           d.compiler + ", commit " + d.commit;
}

int compare(const Doc &a, const Doc &b) {
    if (a.schema != b.schema) {
        throw DocError(a.path + " is " + a.schema + " but " + b.path + " is " + b.schema);
    }
    if (!(a.tsc_hz > 0) || !(b.tsc_hz > 0)) {
        throw DocError("a document without cpu.tsc_hz: ticks cannot be turned into time");
    }
    std::printf("A: %s\n   %s\nB: %s\n   %s\n\n", a.path.c_str(), header(a).c_str(), b.path.c_str(),
                header(b).c_str());
    std::printf("median per element: ticks, and ns (ticks / TSC rate); B/A is the ratio of the "
                "times (below 1: B is faster)\n\n");
    std::map<std::string, const Row *> in_b;
    auto key = [](const Row &r) {
        return r.routine + "|" + r.variant + "|" + r.regime + "|" + r.model;
    };
    for (const Row &r : b.rows) in_b[key(r)] = &r;
    std::printf("%-26s %-12s %-7s %-22s %10s %10s %9s %9s %7s\n", "routine", "variant", "regime",
                "model", "A ticks", "B ticks", "A ns", "B ns", "B/A");
    std::map<std::string, std::pair<double, int>> per_variant; /* sum of logs, count */
    int shown = 0, only_a = 0;
    std::set<std::string> matched;
    for (const Row &r : a.rows) {
        const auto it = in_b.find(key(r));
        if (it == in_b.end()) {
            only_a++;
            continue;
        }
        matched.insert(key(r));
        const Row &s = *it->second;
        const double ns_a = r.median / a.tsc_hz * 1e9, ns_b = s.median / b.tsc_hz * 1e9;
        const double ratio = ns_b / ns_a;
        std::printf("%-26s %-12s %-7s %-22s %10.3f %10.3f %9.4f %9.4f %7.2f%s\n", r.routine.c_str(),
                    r.variant.c_str(), r.regime.c_str(), r.model.substr(0, 22).c_str(), r.median,
                    s.median, ns_a, ns_b, ratio, r.checked && s.checked ? "" : "  (unchecked)");
        if (std::isfinite(ratio) && ratio > 0) {
            per_variant[r.variant].first += std::log(ratio);
            per_variant[r.variant].second++;
        }
        shown++;
    }
    std::printf("\ngeometric mean of B/A per variant:\n");
    for (const std::string &v : a.variants) {
        const auto it = per_variant.find(v);
        if (it == per_variant.end()) continue;
        std::printf("  %-12s %6.2f  (%d rows)\n", v.c_str(),
                    std::exp(it->second.first / it->second.second), it->second.second);
    }
    const int only_b = (int)b.rows.size() - (int)matched.size();
    std::printf("\n%d rows compared; %d only in A, %d only in B (other variants, models or "
                "routines)\n",
                shown, only_a, only_b);
    return 0;
}

/* Markdown pivot: a row per ROW_KEY value (in first-seen order), a column
 * per variant, median ticks per element. */
bool is_planned(const std::string &variant) {
    return variant == "planned" || variant == "planned_kernels";
}

void pivot(const Doc &d, const std::vector<const Row *> &rows, bool by_model,
           const char *first_column, bool speedup) {
    std::vector<std::string> keys;
    std::map<std::string, std::map<std::string, const Row *>> cell;
    std::map<std::string, long long> triangles;
    std::vector<std::string> variants;
    for (const Row *r : rows) {
        const std::string k = by_model ? r->model : r->routine;
        if (!cell.count(k)) keys.push_back(k);
        cell[k][r->variant] = r;
        triangles[k] = r->triangles;
        if (std::find(variants.begin(), variants.end(), r->variant) == variants.end()) {
            variants.push_back(r->variant);
        }
    }
    order_variants(variants);
    if (by_model) {
        std::stable_sort(keys.begin(), keys.end(), [&](const std::string &x, const std::string &y) {
            return triangles[x] < triangles[y];
        });
    }
    std::string line = std::string("| ") + first_column + (by_model ? " | triangles" : "");
    std::string rule = by_model ? "|---|---:" : "|---";
    for (const std::string &v : variants) {
        line += " | " + v;
        rule += "|---:";
    }
    if (speedup) {
        line += " | best vs c_ref";
        rule += "|---:";
    }
    /* A scaling table: how far the planner's choice is from the fastest
     * fixed variant on each mesh (issue 15's goal: within 5%). */
    const bool planned_column = by_model && std::find(variants.begin(), variants.end(),
                                                      "planned") != variants.end();
    if (planned_column) {
        line += " | fastest | planned vs fastest";
        rule += "|---|---:";
    }
    std::printf("%s |\n%s|\n", line.c_str(), rule.c_str());
    for (const std::string &k : keys) {
        std::string out = "| `" + k + "`" + (by_model ? " | " + std::to_string(triangles[k]) : "");
        double best = HUGE_VAL, ref = 0, fastest = HUGE_VAL, planned = 0;
        std::string fastest_name = "-";
        for (const std::string &v : variants) {
            const auto it = cell[k].find(v);
            if (it == cell[k].end()) {
                out += " | -";
                continue;
            }
            const double m = it->second->median;
            out += " | " + fixed(m, m < 10 ? 2 : 1) + (it->second->checked ? "" : " (unchecked)");
            if (v == "c_ref") ref = m;
            if (v == "planned") planned = m;
            best = std::min(best, m);
            if (!is_planned(v) && m < fastest) fastest = m, fastest_name = v;
        }
        if (speedup) out += " | " + (ref > 0 && best > 0 ? fixed(ref / best, 1) + "x" : "-");
        if (planned_column) {
            char pct[32];
            std::snprintf(pct, sizeof pct, "%+.1f%%", 100.0 * (planned / fastest - 1));
            out += " | " + fastest_name + " | " + (planned > 0 && fastest < HUGE_VAL ? pct : "-");
        }
        std::printf("%s |\n", out.c_str());
    }
    (void)d;
}

/* The planner's choices of a document: a row per size class the run used
 * (the meshes that fell in it), a column per routine. */
void print_plans(const Doc &d) {
    if (d.plans.empty()) return;
    std::vector<std::string> routines;
    for (const auto &rv : d.plans.front().variants) routines.push_back(rv.first);
    std::printf("The planner's choices (`planned`; a class is measured on the generated "
                "character of the size given):\n\n| size class | measured on | meshes (triangles) "
                "| source");
    std::string rule = "|---:|---:|---|---";
    for (const std::string &r : routines) {
        std::printf(" | %s", r.c_str());
        rule += "|---";
    }
    std::printf(" |\n%s|\n", rule.c_str());
    std::vector<int> seen;
    for (const PlanChoice &p : d.plans) {
        if (std::find(seen.begin(), seen.end(), p.size_class) != seen.end()) continue;
        seen.push_back(p.size_class);
        std::string meshes;
        for (const PlanChoice &q : d.plans) {
            if (q.size_class == p.size_class) {
                meshes += (meshes.empty() ? "" : ", ") + std::to_string(q.triangles);
            }
        }
        std::printf("| %d | %lld | %s | %s", p.size_class, p.class_triangles, meshes.c_str(),
                    p.source.c_str());
        for (const auto &rv : p.variants) std::printf(" | %s", rv.second.c_str());
        std::printf(" |\n");
    }
    std::printf("\n");
}

int report(const Doc &d, const std::string &regime, const std::string &routine_only) {
    std::printf("<!-- %s: %s -->\n", d.path.c_str(), d.schema.c_str());
    std::printf("*%s.*\n\n", header(d).c_str());
    if (d.schema == "shadowvol-bench/1") {
        const std::string model = d.rows.empty() ? "" : d.rows.front().model;
        std::vector<const Row *> rows;
        for (const Row &r : d.rows) {
            if (r.model == model && r.regime == regime &&
                (routine_only.empty() || r.routine == routine_only)) {
                rows.push_back(&r);
            }
        }
        if (rows.empty()) throw DocError(d.path + ": no rows of " + routine_only);
        std::printf("%s light, `%s`, median TSC ticks per element (per triangle; per SilEdge for "
                    "create_sil_triangles, per vertex for calculate_cull_bits), every row "
                    "checked against c_ref:\n\n",
                    regime == "moving" ? "Moving" : "Fixed", model.c_str());
        pivot(d, rows, false, "routine", true);
        if (routine_only.empty() && !d.plans.empty()) {
            std::printf("\n");
            print_plans(d);
        }
    } else {
        std::vector<std::string> routines;
        for (const Row &r : d.rows) {
            if (std::find(routines.begin(), routines.end(), r.routine) == routines.end() &&
                (routine_only.empty() || r.routine == routine_only)) {
                routines.push_back(r.routine);
            }
        }
        if (routines.empty()) throw DocError(d.path + ": no rows of " + routine_only);
        for (const std::string &routine : routines) {
            std::vector<const Row *> rows;
            for (const Row &r : d.rows) {
                if (r.routine == routine) rows.push_back(&r);
            }
            std::printf("`%s`, moving light, median TSC ticks per element, by mesh:\n\n",
                        routine.c_str());
            pivot(d, rows, true, "mesh", false);
            std::printf("\n");
        }
        print_plans(d);
    }
    return 0;
}

/* --report A.json B.json ... --routine R: one routine's moving-light row
 * of each bench document's first model, a row per CPU, against the
 * faithful SSE2 port (issue 15's goal for the pipeline: 3x). A document
 * without rows of R (written before the routine existed) is named below
 * the table. */
int report_many(const std::vector<Doc> &docs, const std::string &routine) {
    std::vector<std::string> variants;
    for (const Doc &d : docs) {
        if (d.schema != "shadowvol-bench/1") {
            throw DocError(d.path + ": several files are reported only as bench documents");
        }
        for (const Row &r : d.rows) {
            if (r.routine == routine && r.regime == "moving" &&
                std::find(variants.begin(), variants.end(), r.variant) == variants.end()) {
                variants.push_back(r.variant);
            }
        }
    }
    order_variants(variants);
    std::printf("<!-- %s of each file, moving light -->\n", routine.c_str());
    std::printf("`%s`, moving light, median TSC ticks per triangle (ns per triangle in the last "
                "column), every row checked against c_ref:\n\n| CPU | ISA | commit",
                routine.c_str());
    std::string rule = "|---|---|---";
    for (const std::string &v : variants) {
        std::printf(" | %s", v.c_str());
        rule += "|---:";
    }
    std::printf(" | best vs sse2_paper | best, ns |\n%s|---:|---:|\n", rule.c_str());
    std::string without;
    for (const Doc &d : docs) {
        std::map<std::string, const Row *> cell;
        const std::string model = d.rows.empty() ? "" : d.rows.front().model;
        for (const Row &r : d.rows) {
            if (r.routine == routine && r.regime == "moving" && r.model == model)
                cell[r.variant] = &r;
        }
        if (cell.empty()) {
            without += (without.empty() ? "" : ", ") + ("`" + d.path + "`");
            continue;
        }
        const bool has512 = std::find(d.isa.begin(), d.isa.end(), "avx512f") != d.isa.end();
        const bool vbmi = std::find(d.isa.begin(), d.isa.end(), "avx512vbmi") != d.isa.end();
        std::string out = "| " + d.cpu + (d.family.empty() ? "" : " (" + d.family + ")") +
                          ", TSC " + fixed(d.tsc_hz / 1e9, 2) + " GHz | " +
                          (vbmi     ? "AVX-512 VBMI"
                           : has512 ? "AVX-512"
                                    : "AVX2") +
                          " | " + d.commit;
        double best = HUGE_VAL, paper = 0;
        for (const std::string &v : variants) {
            const auto it = cell.find(v);
            if (it == cell.end()) {
                out += " | -";
                continue;
            }
            const double m = it->second->median;
            out += " | " + fixed(m, m < 10 ? 2 : 1) + (it->second->checked ? "" : " (unchecked)");
            if (v == "sse2_paper") paper = m;
            best = std::min(best, m);
        }
        out += " | " + (paper > 0 ? fixed(paper / best, 2) + "x" : std::string("-"));
        out += " | " + (d.tsc_hz > 0 ? fixed(best / d.tsc_hz * 1e9, 2) : std::string("-"));
        std::printf("%s |\n", out.c_str());
    }
    if (!without.empty()) {
        std::printf("\nNo `%s` rows (measured before the routine existed): %s.\n", routine.c_str(),
                    without.c_str());
    }
    return 0;
}

} // namespace

bool is_compare_or_report(int argc, char **argv) {
    return argc >= 2 && (!std::strcmp(argv[1], "--compare") || !std::strcmp(argv[1], "--report"));
}

int compare_main(int argc, char **argv) {
    const bool is_compare = !std::strcmp(argv[1], "--compare");
    std::vector<std::string> files;
    std::string regime = "moving", routine;
    for (int i = 2; i < argc; i++) {
        const std::string a = argv[i];
        if (!is_compare && a == "--routine" && i + 1 < argc) {
            routine = argv[++i];
        } else if (a == "--regime" && i + 1 < argc) {
            regime = argv[++i];
        } else if (a.rfind("--regime=", 0) == 0) {
            regime = a.substr(9);
        } else if (a.rfind('-', 0) == 0) {
            std::fprintf(stderr, "shadowvol bench: %s: unknown option '%s'\n", argv[1], a.c_str());
            return 2;
        } else {
            files.push_back(a);
        }
    }
    if (regime != "moving" && regime != "fixed") {
        std::fprintf(stderr, "shadowvol bench: --regime is moving or fixed, not '%s'\n",
                     regime.c_str());
        return 2;
    }
    const bool many = !is_compare && files.size() > 1;
    if (is_compare ? files.size() != 2
                   : files.empty() || (many && (routine.empty() || regime != "moving"))) {
        std::fprintf(stderr,
                     "usage: shadowvol bench --compare A.json B.json\n"
                     "       shadowvol bench --report FILE.json [--regime fixed] [--routine R]\n"
                     "       shadowvol bench --report A.json B.json... --routine R\n");
        return 2;
    }
    try {
        if (is_compare) return compare(read_doc(files[0]), read_doc(files[1]));
        if (many) {
            std::vector<Doc> docs;
            docs.reserve(files.size());
            for (const std::string &f : files) docs.push_back(read_doc(f));
            return report_many(docs, routine);
        }
        return report(read_doc(files[0]), regime, routine);
    } catch (const DocError &e) {
        std::fprintf(stderr, "shadowvol bench: %s\n", e.what());
        return 3;
    }
}

} // namespace svbench
