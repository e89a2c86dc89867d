/*
 * `shadowvol bench --scaling --quick --plot X.svg --json Y.json`, as a user
 * and a script meet it: exit status 0, every row of every table checked
 * against c_ref, the shadowvol-scaling/1 document whole (every mesh x
 * routine x variant present, numbers finite, every row checked), and the
 * SVG well-formed XML with a panel per routine, a polyline per variant in
 * each, and a marker per cache size the CPU reports.
 *
 * Beside it, the parts the run is made of, on inputs of the test's own: the
 * working-set arithmetic the plot's cache markers stand on, sysfs cache
 * sizes, XML escaping, and the SVG writer's refusal of non-finite numbers.
 *
 * No timing is asserted (a noisy 2-core VM runs this). The extra arguments
 * of SV_SCALING_ARGS (CMake) shrink the run in sanitizer builds.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

#include "cache_info.h"
#include "routines.h"
#include "svg_plot.h"
#include "working_set.h"

#ifndef SV_SHADOWVOL_EXE
#error "SV_SHADOWVOL_EXE must name the built shadowvol program"
#endif
#ifndef SV_SCALING_ARGS
#define SV_SCALING_ARGS ""
#endif

namespace {

using nlohmann::json;

/* ---- A small XML reader: well-formedness and a tree to query ---------- */

struct XmlNode {
    std::string name;
    std::map<std::string, std::string> attrs;
    std::vector<XmlNode> children;
    std::string text;

    std::string attr(const std::string &k) const {
        auto it = attrs.find(k);
        return it == attrs.end() ? std::string() : it->second;
    }
    /* Every descendant (and this node) named NAME, depth first. */
    void find_all(const std::string &n, std::vector<const XmlNode *> &out) const {
        if (name == n) {
            out.push_back(this);
        }
        for (const XmlNode &c : children) {
            c.find_all(n, out);
        }
    }
    std::vector<const XmlNode *> all(const std::string &n) const {
        std::vector<const XmlNode *> v;
        find_all(n, v);
        return v;
    }
};

/* Throws std::runtime_error naming the first thing that is not
 * well-formed XML 1.0 (as far as an SVG writer can get it wrong: tags,
 * attributes, entities, characters). */
class XmlReader {
public:
    explicit XmlReader(const std::string &s) : s_(s) {}

    XmlNode document() {
        if (s_.compare(0, 5, "<?xml") == 0) {
            const size_t e = s_.find("?>");
            if (e == std::string::npos) {
                fail("unterminated XML declaration");
            }
            i_ = e + 2;
        }
        skip_space();
        XmlNode root = element();
        skip_space();
        if (i_ != s_.size()) {
            fail("content after the root element");
        }
        return root;
    }

private:
    [[noreturn]] void fail(const std::string &what) {
        throw std::runtime_error("XML: " + what + " at byte " + std::to_string(i_));
    }
    void skip_space() {
        while (i_ < s_.size() && std::isspace((unsigned char)s_[i_])) {
            i_++;
        }
    }
    std::string name() {
        const size_t b = i_;
        while (i_ < s_.size() && (std::isalnum((unsigned char)s_[i_]) || s_[i_] == '-' ||
                                  s_[i_] == '_' || s_[i_] == ':' || s_[i_] == '.')) {
            i_++;
        }
        if (i_ == b || std::isdigit((unsigned char)s_[b]) || s_[b] == '-') {
            fail("a name expected");
        }
        return s_.substr(b, i_ - b);
    }
    /* Character data up to STOP, entities checked and decoded. */
    std::string chars(char stop) {
        std::string out;
        while (i_ < s_.size() && s_[i_] != stop) {
            const unsigned char c = (unsigned char)s_[i_];
            if (c == '<') {
                fail("'<' in character data or an attribute");
            }
            if (c < 0x20 && c != '\t' && c != '\n' && c != '\r') {
                fail("a control character");
            }
            if (c == '&') {
                const size_t semi = s_.find(';', i_);
                if (semi == std::string::npos || semi - i_ > 10) {
                    fail("an unterminated entity");
                }
                const std::string e = s_.substr(i_ + 1, semi - i_ - 1);
                static const std::map<std::string, char> named = {
                    {"amp", '&'}, {"lt", '<'}, {"gt", '>'}, {"quot", '"'}, {"apos", '\''}};
                if (named.count(e)) {
                    out += named.at(e);
                } else if (e.size() > 1 && e[0] == '#') {
                    out += '?'; /* a character reference; its value does not matter here */
                } else {
                    fail("unknown entity &" + e + ";");
                }
                i_ = semi + 1;
                continue;
            }
            out += (char)c;
            i_++;
        }
        return out;
    }
    XmlNode element() {
        if (i_ >= s_.size() || s_[i_] != '<') {
            fail("'<' expected");
        }
        i_++;
        XmlNode n;
        n.name = name();
        for (;;) {
            const size_t before = i_;
            skip_space();
            if (i_ >= s_.size()) {
                fail("unterminated start tag <" + n.name);
            }
            if (s_.compare(i_, 2, "/>") == 0) {
                i_ += 2;
                return n;
            }
            if (s_[i_] == '>') {
                i_++;
                break;
            }
            if (i_ == before) {
                fail("no space before an attribute");
            }
            const std::string k = name();
            if (i_ >= s_.size() || s_[i_] != '=') {
                fail("'=' expected after attribute " + k);
            }
            i_++;
            const char q = i_ < s_.size() ? s_[i_] : 0;
            if (q != '"' && q != '\'') {
                fail("attribute " + k + " not quoted");
            }
            i_++;
            const std::string v = chars(q);
            if (i_ >= s_.size()) {
                fail("unterminated attribute " + k);
            }
            i_++;
            if (!n.attrs.emplace(k, v).second) {
                fail("attribute " + k + " twice in <" + n.name + ">");
            }
        }
        for (;;) {
            n.text += chars('<');
            if (i_ >= s_.size()) {
                fail("<" + n.name + "> not closed");
            }
            if (s_.compare(i_, 2, "</") == 0) {
                i_ += 2;
                if (name() != n.name) {
                    fail("</...> does not close <" + n.name + ">");
                }
                skip_space();
                if (i_ >= s_.size() || s_[i_] != '>') {
                    fail("'>' expected");
                }
                i_++;
                return n;
            }
            if (s_.compare(i_, 4, "<!--") == 0) {
                const size_t e = s_.find("-->", i_);
                if (e == std::string::npos) {
                    fail("unterminated comment");
                }
                i_ = e + 3;
                continue;
            }
            n.children.push_back(element());
        }
    }

    const std::string &s_;
    size_t i_ = 0;
};

/* Every number in an attribute value is finite: no "nan", "inf". */
void expect_finite_numbers(const XmlNode &n) {
    for (const auto &a : n.attrs) {
        const std::string &v = a.second;
        if (a.first == "class" || a.first.rfind("data-", 0) == 0 || a.first == "xmlns" ||
            a.first == "style" || a.first == "fill" || a.first == "stroke" ||
            a.first == "text-anchor") {
            continue;
        }
        std::string lower;
        for (char c : v) {
            lower += (char)std::tolower((unsigned char)c);
        }
        EXPECT_EQ(lower.find("nan"), std::string::npos) << n.name << " " << a.first << "=" << v;
        EXPECT_EQ(lower.find("inf"), std::string::npos) << n.name << " " << a.first << "=" << v;
    }
    for (const XmlNode &c : n.children) {
        expect_finite_numbers(c);
    }
}

/* ---- Running the program ---------------------------------------------- */

std::string slurp(const std::string &path) {
    std::ifstream f(path, std::ios::binary);
    std::stringstream ss;
    ss << f.rdbuf();
    return ss.str();
}

struct Result {
    int status = -1;
    std::string out, err;
};

Result run_shadowvol(const std::string &args, const std::string &dir) {
    const std::string out = dir + "/stdout", err = dir + "/stderr";
    const std::string cmd = std::string("'") + SV_SHADOWVOL_EXE + "' " + args + " >'" + out +
                            "' 2>'" + err + "'";
    const int rc = std::system(cmd.c_str());
    Result r;
    r.status = WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
    r.out = slurp(out);
    r.err = slurp(err);
    return r;
}

/* The variants this CPU runs that implement R, by name. */
std::set<std::string> runnable_variants(svbench::Routine r) {
    std::set<std::string> names;
    for (const svbench::BenchVariant &v : svbench::bench_variants()) {
        if (svbench::implements(v, r) && (v.isa & sv_cpu_isa()) == v.isa) {
            names.insert(v.name);
        }
    }
    return names;
}

/* One quick scaling run for all the tests that read it. */
class ScalingRun : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        char tmpl[] = "/tmp/sv_scaling_XXXXXX";
        ASSERT_NE(mkdtemp(tmpl), nullptr);
        dir_ = tmpl;
        result_ = run_shadowvol(std::string("bench --scaling --quick ") + SV_SCALING_ARGS +
                                    " --plot '" + dir_ + "/plot.svg' --json '" + dir_ +
                                    "/scaling.json'",
                                dir_);
        svg_ = slurp(dir_ + "/plot.svg");
        json_ = slurp(dir_ + "/scaling.json");
    }
    static void TearDownTestSuite() {
        for (const char *f : {"/plot.svg", "/scaling.json", "/stdout", "/stderr"}) {
            std::remove((dir_ + f).c_str());
        }
        rmdir(dir_.c_str());
    }
    static std::string dir_, svg_, json_;
    static Result result_;
};
std::string ScalingRun::dir_, ScalingRun::svg_, ScalingRun::json_;
Result ScalingRun::result_;

TEST_F(ScalingRun, ExitsZeroWithEveryTableRowChecked) {
    ASSERT_EQ(result_.status, 0) << result_.err;
    std::istringstream lines(result_.out);
    std::string line;
    int tables = 0, rows = 0, notes = 0;
    bool inTable = false;
    while (std::getline(lines, line)) {
        if (line.find(": ticks per ") != std::string::npos) {
            tables++;
            inTable = false;
        } else if (line.rfind("mesh ", 0) == 0 && line.find("checked") != std::string::npos) {
            inTable = true;
        } else if (inTable && line.empty()) {
            inTable = false;
        } else if (inTable && line.rfind("  ", 0) == 0) {
            notes++; // the goal checks under a table (scaling_report.cpp)
        } else if (inTable) {
            rows++;
            EXPECT_EQ(line.substr(line.size() - 2), "ok") << line;
        }
    }
    EXPECT_EQ(tables, 6) << "a table per default routine";
    // Under every table: the planner's 5% check and the slower-than-c_ref
    // check of issue 15, decided by this run's medians.
    EXPECT_GE(notes, 2 * 6) << result_.out;
    EXPECT_NE(result_.out.find("  planned vs the fastest variant (medians): "), std::string::npos);
    EXPECT_NE(result_.out.find("  slower than c_ref (variants other than the paper's own): "),
              std::string::npos);
    EXPECT_GE(rows, 6 * 2) << result_.out;
    // The large-mesh check claims issue 15's goal only at its size (the
    // 979776-triangle character); a --quick run's largest mesh is not it.
    for (size_t at = result_.out.find("  large mesh: "); at != std::string::npos;
         at = result_.out.find("  large mesh: ", at + 1)) {
        const std::string l = result_.out.substr(at, result_.out.find('\n', at) - at);
        EXPECT_TRUE(l.find(" at 979776 triangles (") != std::string::npos ||
                    l.find("not decided here") != std::string::npos)
            << l;
    }
    EXPECT_EQ(result_.out.find("FAILED"), std::string::npos);
    for (const char *field :
         {"\ncpu ", "\ncaches    L1D", "\ntsc ", "\ntimer ", "\nmeshes ", "\nlights ", "\nruns "}) {
        EXPECT_NE(result_.out.find(field), std::string::npos) << "no '" << field << "'";
    }
}

TEST_F(ScalingRun, JsonHasEveryRowChecked) {
    ASSERT_EQ(result_.status, 0) << result_.err;
    const json doc = json::parse(json_);
    ASSERT_TRUE(doc.is_object());
    EXPECT_EQ(doc.at("schema"), "shadowvol-scaling/1");
    EXPECT_TRUE(doc.at("cpu").at("model").is_string());
    EXPECT_GT(doc.at("cpu").at("tsc_hz").get<double>(), 0);
    for (const char *k : {"l1d_bytes", "l2_bytes", "l3_bytes"}) {
        const json &c = doc.at("caches").at(k);
        EXPECT_TRUE(c.is_null() || (c.is_number_integer() && c.get<long long>() > 0)) << k;
    }
    for (const char *k : {"compiler", "commit", "timer"}) {
        EXPECT_TRUE(doc.at(k).is_string()) << k;
    }

    /* The routines of the run, from working_set. */
    std::vector<std::string> routines;
    for (const json &ws : doc.at("working_set")) {
        routines.push_back(ws.at("routine"));
        EXPECT_GT(ws.at("bytes_per_triangle").get<double>(), 0);
        EXPECT_TRUE(ws.at("formula").is_string());
    }
    ASSERT_EQ(routines.size(), 6u);
    EXPECT_EQ(routines[0], "create_shadow_volume") << "the volume first";

    /* Meshes: sorted by size, generated ones 1344 n^2. */
    std::map<std::string, long long> triangles;
    long long last = 0;
    int generated = 0;
    for (const json &m : doc.at("models")) {
        const long long t = m.at("triangles");
        EXPECT_GE(t, last) << "models in order of size";
        last = t;
        triangles[m.at("model")] = t;
        if (m.at("generated").get<bool>()) {
            generated++;
            const long long n = m.at("subdivision");
            EXPECT_EQ(t, 1344 * n * n);
        }
        EXPECT_GT(m.at("lights").get<int>(), 0);
        EXPECT_GT(m.at("working_set_bytes").get<double>(), 0);
    }
    EXPECT_GE(generated, 2);

    /* Results: every mesh x routine x runnable variant once, checked. */
    std::set<std::string> seen;
    for (const json &r : doc.at("results")) {
        const std::string key = r.at("model").get<std::string>() + " " +
                                r.at("routine").get<std::string>() + " " +
                                r.at("variant").get<std::string>();
        EXPECT_TRUE(seen.insert(key).second) << "twice: " << key;
        EXPECT_EQ(r.at("regime"), "moving");
        EXPECT_TRUE(r.at("checked").get<bool>()) << key << ": " << r.dump();
        ASSERT_TRUE(triangles.count(r.at("model"))) << key;
        EXPECT_EQ(r.at("triangles").get<long long>(), triangles[r.at("model")]);
        for (const char *k : {"ticks_per_element_min", "ticks_per_element_median"}) {
            ASSERT_TRUE(r.at(k).is_number()) << key << " " << k;
            const double v = r.at(k);
            EXPECT_TRUE(std::isfinite(v) && v >= 0) << key << " " << k;
        }
        EXPECT_LE(r.at("ticks_per_element_min").get<double>(),
                  r.at("ticks_per_element_median").get<double>())
            << key;
        const std::set<std::string> fits = {"L1D", "L2", "L3", "DRAM", "?"};
        EXPECT_TRUE(fits.count(r.at("fits"))) << key;
    }
    for (const auto &m : triangles) {
        for (const std::string &rn : routines) {
            svbench::Routine r;
            ASSERT_TRUE(svbench::routine_by_name(rn, &r));
            for (const std::string &v : runnable_variants(r)) {
                EXPECT_TRUE(seen.count(m.first + " " + rn + " " + v))
                    << "missing " << m.first << " " << rn << " " << v;
            }
        }
    }
}

TEST_F(ScalingRun, SvgIsWellFormedWithAPolylinePerVariantAndTheCacheMarkers) {
    ASSERT_EQ(result_.status, 0) << result_.err;
    XmlNode root;
    try {
        root = XmlReader(svg_).document();
    } catch (const std::exception &e) {
        FAIL() << e.what();
    }
    EXPECT_EQ(root.name, "svg");
    EXPECT_EQ(root.attr("xmlns"), "http://www.w3.org/2000/svg");
    expect_finite_numbers(root);

    const json doc = json::parse(json_);
    int caches = 0;
    for (const char *k : {"l1d_bytes", "l2_bytes", "l3_bytes"}) {
        caches += !doc.at("caches").at(k).is_null();
    }

    std::vector<const XmlNode *> panels;
    for (const XmlNode *g : root.all("g")) {
        if (g->attr("class") == "panel") {
            panels.push_back(g);
        }
    }
    ASSERT_EQ(panels.size(), doc.at("working_set").size());
    for (const XmlNode *p : panels) {
        svbench::Routine r;
        ASSERT_TRUE(svbench::routine_by_name(p->attr("data-id"), &r)) << p->attr("data-id");
        std::multiset<std::string> lines;
        for (const XmlNode *pl : p->all("polyline")) {
            lines.insert(pl->attr("data-series"));
            /* "x,y x,y ...": pairs of numbers. */
            std::istringstream pts(pl->attr("points"));
            std::string pair;
            int n = 0;
            while (pts >> pair) {
                double x, y;
                char comma;
                std::istringstream xy(pair);
                EXPECT_TRUE((xy >> x >> comma >> y) && comma == ',') << pair;
                n++;
            }
            EXPECT_GE(n, 2) << p->attr("data-id") << " " << pl->attr("data-series")
                            << ": a line needs the generated meshes";
        }
        const std::set<std::string> want = runnable_variants(r);
        EXPECT_EQ(std::set<std::string>(lines.begin(), lines.end()), want) << p->attr("data-id");
        EXPECT_EQ(lines.size(), want.size()) << "one polyline per variant";

        std::set<std::string> markers;
        for (const XmlNode *g : p->all("g")) {
            if (g->attr("class") == "vmarker") {
                markers.insert(g->attr("data-label").substr(0, 3));
                const double x = std::strtod(g->attr("data-x").c_str(), nullptr);
                EXPECT_TRUE(std::isfinite(x) && x > 0) << g->attr("data-x");
            }
        }
        EXPECT_EQ((int)markers.size(), caches) << p->attr("data-id");
        if (!doc.at("caches").at("l2_bytes").is_null()) {
            EXPECT_TRUE(markers.count("L2 ")) << p->attr("data-id");
        }
    }
}

/* ---- The parts ---------------------------------------------------------- */

// Issue 17: `bench --scaling --model FILE` measures the user's own mesh
// beside the generated ones (it was refused: a user could not add a mesh).
TEST(ScalingModel, UsersOwnMeshIsMeasured) {
    char tmpl[] = "/tmp/sv_scaling_model_XXXXXX";
    ASSERT_NE(mkdtemp(tmpl), nullptr);
    const std::string dir = tmpl;
    const std::string mine = dir + "/my_own_mesh.glb";
    {
        std::ifstream in(std::string(SV_MODELS_DIR) + "/character_1344.glb", std::ios::binary);
        std::ofstream out(mine, std::ios::binary);
        out << in.rdbuf();
    }
    const Result r = run_shadowvol("bench --scaling --quick --max-triangles 1344 --routine "
                                   "count_facing --rounds 3 --model '" +
                                       mine + "' --json '" + dir + "/s.json'",
                                   dir);
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("my_own_mesh.glb"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("in 3 rounds;"), std::string::npos) << "--rounds not taken:\n" << r.out;
    const json doc = json::parse(slurp(dir + "/s.json"));
    EXPECT_EQ(doc.at("options").value("rounds", 0), 3);
    bool found = false;
    for (const json &m : doc.at("models")) found = found || m.at("model") == "my_own_mesh.glb";
    EXPECT_TRUE(found) << doc.at("models").dump();
    const Result bad = run_shadowvol("bench --scaling --quick --model synthetic", dir);
    EXPECT_EQ(bad.status, 2) << bad.err;
    for (const char *f : {"/my_own_mesh.glb", "/s.json", "/stdout", "/stderr"}) {
        std::remove((dir + f).c_str());
    }
    rmdir(dir.c_str());
}

TEST(WorkingSet, VolumeAtThePapersRatios) {
    using svbench::Routine;
    const svbench::WorkingSet ws = svbench::working_set(Routine::create_shadow_volume,
                                                        svbench::paper_shape());
    /* 1 facing + 12 indices + 1.5 x 16 SilEdges + 1.5 x 0.2 x 24 + 0.5 x 24 */
    EXPECT_NEAR(ws.total, 56.2, 1e-9);
    EXPECT_EQ(svbench::working_set_formula(ws),
              "1 facing + 12 indices + 24 SilEdges + 7.2 silhouette + 12 caps = 56.2 bytes per "
              "triangle");
    EXPECT_NEAR(svbench::working_set(Routine::count_facing, svbench::paper_shape()).total, 1, 0);
    EXPECT_EQ(svbench::working_set_formula(
                  svbench::working_set(Routine::count_facing, svbench::paper_shape())),
              "1 facing byte per triangle");
    EXPECT_NEAR(svbench::working_set(Routine::calculate_facing, svbench::paper_shape()).total, 17,
                1e-9);
    EXPECT_NEAR(svbench::working_set(Routine::create_sil_triangles, svbench::paper_shape()).total,
                32.2, 1e-9);
    EXPECT_NEAR(svbench::working_set(Routine::create_cap_triangles, svbench::paper_shape()).total,
                25, 1e-9);
    /* Culling turns triangles facing: fewer caps. */
    svbench::MeshShape culled = svbench::paper_shape();
    culled.culled = 0.25;
    EXPECT_NEAR(svbench::working_set(Routine::create_shadow_volume_cull, culled).total,
                56.2 + 0.5 - 0.25 * 24, 1e-9);
}

TEST(CacheInfo, SysfsSizes) {
    EXPECT_EQ(svbench::parse_sysfs_size("48K"), 48u * 1024);
    EXPECT_EQ(svbench::parse_sysfs_size("1024K"), 1024u * 1024);
    EXPECT_EQ(svbench::parse_sysfs_size("32M"), 32u << 20);
    EXPECT_EQ(svbench::parse_sysfs_size("512"), 512u);
    for (const char *bad : {"", "K", "48KB", "4 8K", "-1K", "48k", "99999999999999999999K"}) {
        EXPECT_EQ(svbench::parse_sysfs_size(bad), 0u) << bad;
    }
    EXPECT_EQ(svbench::format_bytes(48 * 1024), "48 KiB");
    EXPECT_EQ(svbench::format_bytes(1.5 * 1024 * 1024), "1.5 MiB");
    EXPECT_EQ(svbench::format_bytes(0), "unknown");
    /* Whatever this machine reports, the summary names every level. */
    const std::string s = svbench::cache_summary(svbench::cache_sizes());
    for (const char *l : {"L1D ", "L2 ", "L3 "}) {
        EXPECT_NE(s.find(l), std::string::npos) << s;
    }
}

TEST(SvgPlot, EscapesTextAndReplacesWhatXmlForbids) {
    EXPECT_EQ(svplot::xml_escape("a<b & \"c\" 'd'>"),
              "a&lt;b &amp; &quot;c&quot; &apos;d&apos;&gt;");
    EXPECT_EQ(svplot::xml_escape("x\x01y"), "x\xef\xbf\xbdy");             /* control character */
    EXPECT_EQ(svplot::xml_escape("\xff"), "\xef\xbf\xbd");                 /* not UTF-8 */
    EXPECT_EQ(svplot::xml_escape("\xc0\xaf"), "\xef\xbf\xbd\xef\xbf\xbd"); /* overlong '/' */
    EXPECT_EQ(svplot::xml_escape("\xed\xa0\x80"),
              "\xef\xbf\xbd\xef\xbf\xbd\xef\xbf\xbd"); /* a surrogate */
    EXPECT_EQ(svplot::xml_escape("caf\xc3\xa9 \xe2\x86\x92"), "caf\xc3\xa9 \xe2\x86\x92");
}

TEST(SvgPlot, RefusesNonFiniteNumbersAndDrawsOddNames) {
    svplot::Document d;
    d.title = "t";
    d.lineKey = "line";
    svplot::Panel p;
    p.id = "p<&>";
    p.series.push_back({"a\x02\xff", 0, {{1000, 1.5, "m"}, {10000, 2.5, ""}}, {{500, 3, "r"}}});
    p.markers.push_back({"L1D 48 KiB", 875});
    p.markers.push_back({"L3 1 GiB", 1e9}); /* beyond the axis: under the legend */
    d.panels.push_back(p);
    const std::string svg = svplot::render(d);
    XmlNode root;
    ASSERT_NO_THROW(root = XmlReader(svg).document()) << svg;
    EXPECT_EQ(root.all("polyline").size(), 1u);
    int markers = 0;
    for (const XmlNode *g : root.all("g")) {
        markers += g->attr("class") == "vmarker";
    }
    EXPECT_EQ(markers, 2);

    for (double bad : {(double)NAN, (double)INFINITY, -1.0, 0.0}) {
        svplot::Document e = d;
        e.panels[0].series[0].line[0].x = bad;
        EXPECT_THROW(svplot::render(e), std::logic_error) << bad;
    }
    svplot::Document e = d;
    e.panels[0].series[0].line[0].y = NAN;
    EXPECT_THROW(svplot::render(e), std::logic_error);
}

} // namespace
