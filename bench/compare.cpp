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

struct Doc {
    std::string path, schema, cpu, commit, timer, compiler;
    double tsc_hz = 0;
    std::vector<Row> rows;
    std::vector<std::string> variants; /* in the document's order */
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
    static const char *const kOrder[] = {"c_ref", "c_branchless", "sse2_paper", "sse2",
                                         "avx2", "avx512", "avx512vbmi"};
    auto rank = [](const std::string &name) {
        for (int i = 0; i < 7; i++) {
            if (name == kOrder[i]) return i;
        }
        return 7;
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
    std::printf("A: %s\n   %s\nB: %s\n   %s\n\n", a.path.c_str(), header(a).c_str(),
                b.path.c_str(), header(b).c_str());
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
        std::printf("%-26s %-12s %-7s %-22s %10.3f %10.3f %9.4f %9.4f %7.2f%s\n",
                    r.routine.c_str(), r.variant.c_str(), r.regime.c_str(),
                    r.model.substr(0, 22).c_str(), r.median, s.median, ns_a, ns_b, ratio,
                    r.checked && s.checked ? "" : "  (unchecked)");
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
    std::printf("%s |\n%s|\n", line.c_str(), rule.c_str());
    for (const std::string &k : keys) {
        std::string out = "| `" + k + "`" + (by_model ? " | " + std::to_string(triangles[k]) : "");
        double best = HUGE_VAL, ref = 0;
        for (const std::string &v : variants) {
            const auto it = cell[k].find(v);
            if (it == cell[k].end()) {
                out += " | -";
                continue;
            }
            const double m = it->second->median;
            out += " | " + fixed(m, m < 10 ? 2 : 1) + (it->second->checked ? "" : " (unchecked)");
            if (v == "c_ref") ref = m;
            best = std::min(best, m);
        }
        if (speedup) out += " | " + (ref > 0 && best > 0 ? fixed(ref / best, 1) + "x" : "-");
        std::printf("%s |\n", out.c_str());
    }
    (void)d;
}

int report(const Doc &d, const std::string &regime) {
    std::printf("<!-- %s: %s -->\n", d.path.c_str(), d.schema.c_str());
    std::printf("*%s.*\n\n", header(d).c_str());
    if (d.schema == "shadowvol-bench/1") {
        const std::string model = d.rows.empty() ? "" : d.rows.front().model;
        std::vector<const Row *> rows;
        for (const Row &r : d.rows) {
            if (r.model == model && r.regime == regime) rows.push_back(&r);
        }
        std::printf("%s light, `%s`, median TSC ticks per element (per triangle; per SilEdge for "
                    "create_sil_triangles, per vertex for calculate_cull_bits), every row "
                    "checked against c_ref:\n\n",
                    regime == "moving" ? "Moving" : "Fixed", model.c_str());
        pivot(d, rows, false, "routine", true);
    } else {
        std::vector<std::string> routines;
        for (const Row &r : d.rows) {
            if (std::find(routines.begin(), routines.end(), r.routine) == routines.end()) {
                routines.push_back(r.routine);
            }
        }
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
    std::string regime = "moving";
    for (int i = 2; i < argc; i++) {
        const std::string a = argv[i];
        if (a == "--regime" && i + 1 < argc) {
            regime = argv[++i];
        } else if (a.rfind("--regime=", 0) == 0) {
            regime = a.substr(9);
        } else if (a.rfind("-", 0) == 0) {
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
    if (files.size() != (is_compare ? 2u : 1u)) {
        std::fprintf(stderr, "usage: shadowvol bench --compare A.json B.json\n"
                             "       shadowvol bench --report FILE.json [--regime fixed]\n");
        return 2;
    }
    try {
        if (is_compare) return compare(read_doc(files[0]), read_doc(files[1]));
        return report(read_doc(files[0]), regime);
    } catch (const DocError &e) {
        std::fprintf(stderr, "shadowvol bench: %s\n", e.what());
        return 3;
    }
}

} // namespace svbench
