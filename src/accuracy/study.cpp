/*
 * The accuracy study (accuracy_study.h): lights, ground truth, the counts,
 * the contract checks and the timing.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "accuracy_study.h"

#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>

#include "accuracy_internal.h"
#include "fnv1a.h"
#include "rng.h"
#include "shadowvol_gltf.h"
#include "timer.h"

namespace sv {
namespace acc {

namespace {

/* Radii above the plane: hair about 16 float ulps of a coordinate of the
 * size of the radius, graze far below one (the light rounds to a float
 * point within an ulp or so of the plane, on either side). */
constexpr double kHairHeight = 0x1p-20;
constexpr double kGrazeHeight = 0x1p-40;
constexpr double kJitter = 1e-6; /* of the light's distance, or radians */
constexpr int kCanaryBytes = 16; /* after facing[numTriangles] */
constexpr uint8_t kCanary = 0xA5;
/* A timed region covers at least this many triangles: a few hundred TSC
 * steps at the fastest variants, so the TSC's resolution (tens of ticks
 * on some VMs) stays below a percent. */
constexpr int64_t kMinTrianglesPerRegion = 8192;
constexpr int kMinRegions = 16;
constexpr std::size_t kMaxFailures = 8;

std::string file_name(const std::string &path) {
    const std::size_t slash = path.find_last_of('/');
    return slash == std::string::npos ? path : path.substr(slash + 1);
}

/* A uniform random unit vector (rejection from the cube). */
void random_unit(svbench::Rng &rng, double u[3]) {
    for (;;) {
        double r2 = 0;
        for (int i = 0; i < 3; i++) {
            u[i] = 2.0 * rng.unit() - 1.0;
            r2 += u[i] * u[i];
        }
        if (r2 > 1e-6 && r2 <= 1.0) {
            const double r = std::sqrt(r2);
            for (int i = 0; i < 3; i++) u[i] /= r;
            return;
        }
    }
}

Vec4 point_light(const double p[3]) { return Vec4{(float)p[0], (float)p[1], (float)p[2], 1.0f}; }

/* FNV-1a of a name. The study has always started from this value, not
 * FNV's offset basis (a digit short of it): kept, so the study draws the
 * same samples it always drew. */
uint64_t name_hash(const char *s) { return sv::fnv1a64(s, std::strlen(s), 1469598103934665603ull); }

/* FNV-1a over raw bytes, continuing from H. */
uint64_t bytes_hash(uint64_t h, const void *data, std::size_t n) { return sv::fnv1a64(data, n, h); }

const float *vertex(const PreparedSurface &s, int t, int corner) {
    return &s.positions[3 * (std::size_t)s.indices[3 * (std::size_t)t + (std::size_t)corner]];
}

} // namespace

/* ---- Models ----------------------------------------------------------------- */

std::unique_ptr<StudyModel> load_study_model(const std::string &path) {
    GltfModel g;
    try {
        g = load_gltf(path);
    } catch (const GltfError &e) {
        throw StudyError(e.what());
    }
    auto m = std::make_unique<StudyModel>();
    m->path = path;
    m->name = file_name(path);
    double lo[3], hi[3];
    for (int i = 0; i < 3; i++) {
        lo[i] = std::numeric_limits<double>::infinity();
        hi[i] = -lo[i];
    }
    for (GltfSurface &gs : g.surfaces) {
        auto s = std::make_unique<StudySurface>();
        s->name = gs.name;
        try {
            s->prepared = prepare_surface(gs.positions.data(), gs.num_vertices(), gs.indices.data(),
                                          gs.indices.size());
        } catch (const PrepareError &e) {
            throw StudyError(path + ": surface " + gs.name + ": " + e.what());
        }
        if (s->prepared.num_triangles() == 0) continue;
        const std::vector<float> &p = s->prepared.positions;
        for (std::size_t k = 0; k < p.size(); k++) {
            lo[k % 3] = std::min(lo[k % 3], (double)p[k]);
            hi[k % 3] = std::max(hi[k % 3], (double)p[k]);
        }
        {
            const PreparedSurface &ps = s->prepared;
            uint64_t h = m->content_hash ? m->content_hash : 1469598103934665603ull;
            h = bytes_hash(h, ps.positions.data(), ps.positions.size() * sizeof(float));
            h = bytes_hash(h, ps.indices.data(), ps.indices.size() * sizeof(ps.indices[0]));
            m->content_hash = h;
        }
        m->triangles += s->prepared.num_triangles();
        m->sil_edges += s->prepared.num_sil_edges();
        m->surfaces.push_back(std::move(s));
    }
    if (m->surfaces.empty()) throw StudyError(path + ": no triangles left after preparation");
    double r2 = 0;
    for (int i = 0; i < 3; i++) {
        m->center[i] = (float)((lo[i] + hi[i]) * 0.5);
        m->extents[i] = (float)std::max(hi[i] - m->center[i], m->center[i] - lo[i]);
        r2 += (double)m->extents[i] * m->extents[i];
    }
    m->radius = std::sqrt(r2);
    if (!(m->radius > 0)) throw StudyError(path + ": the model has no extent");
    for (auto &s : m->surfaces) {
        const PreparedSurface &p = s->prepared;
        s->data = make_surface_data(p, m->center, (float)m->radius);
        const int nt = p.num_triangles();
        s->error_models.resize((std::size_t)nt);
        s->normal_length.resize((std::size_t)nt);
        for (int t = 0; t < nt; t++) {
            s->error_models[(std::size_t)t] = triangle_error_model(vertex(p, t, 0), vertex(p, t, 1),
                                                                   vertex(p, t, 2));
            s->normal_length[(std::size_t)t] =
                sv_exact_normal_length(vertex(p, t, 0), vertex(p, t, 1), vertex(p, t, 2));
        }
    }
    return m;
}

/* ---- Lights ----------------------------------------------------------------- */

const std::vector<Placement> &placements() {
    static const std::vector<Placement> p = {
        {"graze", false, 0, "point light on a random triangle's plane, to float precision"},
        {"hair", false, 0, "point light 2^-20 radii above a random triangle's plane"},
        {"inside", false, 0, "point light uniform in the bounding box"},
        {"2r", false, 2, "point light 2 radii from the center"},
        {"10r", false, 10, "point light 10 radii from the center"},
        {"100r", false, 100, "point light 100 radii from the center"},
        {"1e4r", false, 1e4, "point light 10^4 radii from the center"},
        {"1e6r", false, 1e6, "point light 10^6 radii from the center"},
        {"dir", true, 0, "directional light, uniform random direction"},
        {"axis", true, 0, "directional light along +-x, +-y, +-z"},
    };
    return p;
}

const Placement *placement_by_name(const std::string &name) {
    for (const Placement &p : placements()) {
        if (name == p.name) return &p;
    }
    return nullptr;
}

LightSet make_lights(const StudyModel &m, const Placement &p, int count, uint64_t seed) {
    LightSet ls;
    ls.placement = &p;
    svbench::Rng rng{seed ^ name_hash(p.name) ^ (m.content_hash << 1)};
    const double r = m.radius;
    const double c[3] = {m.center[0], m.center[1], m.center[2]};
    const std::string name = p.name;
    if (name == "axis") count = 6;
    for (int i = 0; i < count; i++) {
        double u[3], q[3];
        Vec4 l;
        if (name == "axis") {
            l = Vec4{0, 0, 0, 0};
            (&l.x)[i / 2] = i % 2 ? -1.0f : 1.0f;
        } else if (p.directional) {
            random_unit(rng, u);
            l = Vec4{(float)u[0], (float)u[1], (float)u[2], 0.0f};
        } else if (name == "hair" || name == "graze") {
            /* A random triangle with a normal (zero-area ones have none). */
            const TriangleErrorModel *em = nullptr;
            for (int tries = 0; tries < 1000 && !em; tries++) {
                int64_t t = (int64_t)(rng.unit() * (double)m.triangles);
                for (const auto &s : m.surfaces) {
                    const int64_t n = s->prepared.num_triangles();
                    if (t < n) {
                        const TriangleErrorModel &cand = s->error_models[(std::size_t)t];
                        if (cand.plane_d.a != 0 || cand.plane_d.b != 0 || cand.plane_d.c != 0) {
                            em = &cand;
                        }
                        break;
                    }
                    t -= n;
                }
            }
            if (!em) em = &m.surfaces[0]->error_models[0];
            const double n[3] = {em->plane_d.a, em->plane_d.b, em->plane_d.c};
            const double h = name == "hair" ? kHairHeight : kGrazeHeight;
            for (int k = 0; k < 3; k++) q[k] = em->c[k] + h * r * n[k];
            l = point_light(q);
            ls.height_radii = h;
        } else if (name == "inside") {
            for (int k = 0; k < 3; k++) q[k] = c[k] + (2.0 * rng.unit() - 1.0) * m.extents[k];
            l = point_light(q);
        } else {
            random_unit(rng, u);
            for (int k = 0; k < 3; k++) q[k] = c[k] + p.radii * r * u[k];
            l = point_light(q);
        }
        /* The jittered twin: 1e-6 of the distance (or radians) aside. */
        random_unit(rng, u);
        Vec4 j = l;
        if (l.w == 0.0f) {
            for (int k = 0; k < 3; k++) (&j.x)[k] = (float)((&l.x)[k] + kJitter * u[k]);
        } else {
            const double dist = std::sqrt(((double)l.x - c[0]) * (l.x - c[0]) +
                                          ((double)l.y - c[1]) * (l.y - c[1]) +
                                          ((double)l.z - c[2]) * (l.z - c[2]));
            const double step = kJitter * std::max(dist, r);
            for (int k = 0; k < 3; k++) (&j.x)[k] = (float)((&l.x)[k] + step * u[k]);
            ls.mean_distance_radii += dist / r / count;
        }
        ls.lights.push_back(l);
        ls.jittered.push_back(j);
    }
    return ls;
}

/* ---- The study -------------------------------------------------------------- */

namespace {

/* Per (light, surface): the ground truth and the bounds. */
struct Truth {
    std::vector<uint8_t> facing; /* numTriangles + 1 */
    std::vector<double> D;
    std::vector<double> bound[4]; /* per FacingArithmetic, filled on demand */
    bool have_bound[4] = {false, false, false, false};
};

/* A facing buffer followed by canary bytes. */
struct FacingBuffer {
    std::vector<uint8_t> bytes;
    int n = 0;
    void reset(int numTriangles) {
        n = numTriangles;
        bytes.assign((std::size_t)n + 1 + kCanaryBytes, kCanary);
    }
    uint8_t *data() { return bytes.data(); }
    /* Every byte 0 or 1, the last 1, the canaries untouched. */
    bool well_formed() const {
        for (int t = 0; t < n; t++) {
            if (bytes[(std::size_t)t] > 1) return false;
        }
        if (bytes[(std::size_t)n] != 1) return false;
        for (int k = 0; k < kCanaryBytes; k++) {
            if (bytes[(std::size_t)n + 1 + (std::size_t)k] != kCanary) return false;
        }
        return true;
    }
};

std::string light_text(const Vec4 &l) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "(%.9g, %.9g, %.9g, %g)", l.x, l.y, l.z, l.w);
    return buf;
}

class Study {
public:
    Study(const StudyOptions &o, StudyResult &res) : o_(o), res_(res) {}

    void run_placement(const StudyModel &m, const Placement &p,
                       const std::vector<const Variant *> &vars);

private:
    void fail(const std::string &what) {
        res_.failure_count++;
        if (res_.failures.size() < kMaxFailures) res_.failures.push_back(what);
    }
    void compute_truth(const StudySurface &s, const Vec4 &l, Truth &t);
    const std::vector<double> &bounds(const StudySurface &s, const Vec4 &l, Truth &t,
                                      FacingArithmetic a);
    template <class Timer>
    void time_variant(const Variant &v, const StudyModel &m, const LightSet &ls, StudyRow &row);

    const StudyOptions &o_;
    StudyResult &res_;
};

void Study::compute_truth(const StudySurface &s, const Vec4 &l, Truth &t) {
    const PreparedSurface &p = s.prepared;
    const int nt = p.num_triangles();
    t.facing.assign((std::size_t)nt + 1, 1);
    t.D.assign((std::size_t)nt, 0.0);
    for (int k = 0; k < 4; k++) t.have_bound[k] = false;
    for (int i = 0; i < nt; i++) {
        const float *a = vertex(p, i, 0), *b = vertex(p, i, 1), *c = vertex(p, i, 2);
        int sign = 0;
        const double det = sv_exact_det_estimate(a, b, c, &l, &sign);
        t.facing[(std::size_t)i] = sign > 0;
        t.D[(std::size_t)i] = sign == 0 ? 0.0 : det / s.normal_length[(std::size_t)i];
    }
}

const std::vector<double> &Study::bounds(const StudySurface &s, const Vec4 &l, Truth &t,
                                         FacingArithmetic a) {
    const int k = (int)a;
    if (!t.have_bound[k]) {
        const std::size_t nt = s.error_models.size();
        t.bound[k].resize(nt);
        for (std::size_t i = 0; i < nt; i++) {
            t.bound[k][i] = facing_error_bound(a, s.error_models[i], l);
        }
        t.have_bound[k] = true;
    }
    return t.bound[k];
}

template <class Timer>
void Study::time_variant(const Variant &v, const StudyModel &m, const LightSet &ls, StudyRow &row) {
    std::vector<FacingBuffer> bufs(m.surfaces.size());
    for (std::size_t s = 0; s < m.surfaces.size(); s++) {
        bufs[s].reset(m.surfaces[s]->prepared.num_triangles());
    }
    const int nl = (int)ls.lights.size();
    const int batch = (int)std::max<int64_t>(1, (kMinTrianglesPerRegion + m.triangles - 1) /
                                                    m.triangles);
    const int regions = std::max(kMinRegions, (nl * o_.timing_rounds + batch - 1) / batch);
    auto call = [&](const Vec4 &l) {
        for (std::size_t s = 0; s < m.surfaces.size(); s++) {
            v.run(m.surfaces[s]->data, l, nullptr, bufs[s].data());
        }
    };
    for (const Vec4 &l : ls.lights) call(l); /* warm caches and predictors */
    std::vector<uint64_t> ticks((std::size_t)regions), empty((std::size_t)regions);
    int k = 0;
    for (int r = 0; r < regions; r++) {
        const uint64_t e0 = Timer::begin();
        const uint64_t e1 = Timer::end();
        empty[(std::size_t)r] = e1 - e0;
        const uint64_t t0 = Timer::begin();
        for (int b = 0; b < batch; b++) call(ls.lights[(std::size_t)(k++ % nl)]);
        const uint64_t t1 = Timer::end();
        ticks[(std::size_t)r] = t1 - t0;
    }
    for (std::size_t s = 0; s < bufs.size(); s++) {
        if (!bufs[s].well_formed()) {
            fail(std::string(v.name) + ": wrote a byte other than 0/1 or past facing[n] (timed)");
        }
    }
    std::sort(ticks.begin(), ticks.end());
    std::sort(empty.begin(), empty.end());
    const double per = (double)batch * (double)m.triangles;
    const double med = (double)ticks[ticks.size() / 2] - (double)empty[empty.size() / 2];
    const double mn = (double)ticks[0] - (double)empty[0];
    row.ticks_median = std::max(med, 0.0) / per;
    row.ticks_min = std::max(mn, 0.0) / per;
    row.timed = true;
}

void Study::run_placement(const StudyModel &m, const Placement &p,
                          const std::vector<const Variant *> &vars) {
    const LightSet ls = make_lights(m, p, o_.lights,
                                    o_.seed * 0x9E3779B97F4A7C15ull + m.content_hash);
    const std::size_t nv = vars.size();
    std::vector<StudyRow> rows(nv);
    for (std::size_t vi = 0; vi < nv; vi++) {
        StudyRow &r = rows[vi];
        r.variant = vars[vi];
        r.model = &m;
        r.placement = &p;
        r.mean_distance_radii = ls.mean_distance_radii;
        r.height_radii = ls.height_radii;
        r.lights = (int)ls.lights.size();
        r.triangles = m.triangles;
    }
    Truth truth;
    std::vector<FacingBuffer> out(nv), jit(nv), back(nv);
    for (std::size_t li = 0; li < ls.lights.size(); li++) {
        const Vec4 &l = ls.lights[li], &lj = ls.jittered[li];
        for (const auto &sp : m.surfaces) {
            const StudySurface &s = *sp;
            const PreparedSurface &ps = s.prepared;
            const int nt = ps.num_triangles();
            compute_truth(s, l, truth);
            int64_t sil_exact = 0;
            for (const SilEdge &e : ps.sil_edges) {
                sil_exact += truth.facing[(std::size_t)e.p1] != truth.facing[(std::size_t)e.p2];
            }
            auto where = [&](const Variant &v, int t) {
                return std::string(v.name) + ", " + m.name + " surface " + s.name + ", " + p.name +
                       " light " + light_text(l) + ", triangle " + std::to_string(t);
            };
            for (std::size_t vi = 0; vi < nv; vi++) {
                const Variant &v = *vars[vi];
                StudyRow &row = rows[vi];
                FacingBuffer &f = out[vi];
                f.reset(nt);
                row.exact_stage += v.run(s.data, l, nullptr, f.data());
                if (!f.well_formed()) {
                    fail(where(v, -1) + ": a byte other than 0/1, facing[n] != 1, or a write "
                                        "past facing[n]");
                    row.violations++;
                }
                row.tests += nt;
                /* The contract. */
                if (v.contract == Contract::same_as) {
                    const Variant *def = variant_by_name(v.same_as);
                    FacingBuffer ref;
                    const FacingBuffer *refp = nullptr;
                    for (std::size_t k = 0; k < vi; k++) {
                        if (vars[k] == def) refp = &out[k];
                    }
                    if (!refp) {
                        ref.reset(nt);
                        def->run(s.data, l, nullptr, ref.data());
                        refp = &ref;
                    }
                    for (int t = 0; t < nt; t++) {
                        if (f.bytes[(std::size_t)t] != refp->bytes[(std::size_t)t]) {
                            fail(where(v, t) + ": differs from " + def->name);
                            row.violations++;
                            break;
                        }
                    }
                }
                const Contract c = v.contract == Contract::same_as
                                       ? variant_by_name(v.same_as)->contract
                                       : v.contract;
                int64_t mis = 0;
                for (int t = 0; t < nt; t++)
                    mis += f.bytes[(std::size_t)t] != truth.facing[(std::size_t)t];
                row.misclassified += mis;
                if (c == Contract::exact) {
                    if (mis) {
                        fail(where(v, -1) + ": " + std::to_string(mis) +
                             " bytes differ from the exact facing");
                        row.violations += mis;
                    }
                } else if (c == Contract::bounded) {
                    const std::vector<double> &B = bounds(s, l, truth, v.arithmetic);
                    for (int t = 0; t < nt; t++) {
                        const double D = truth.D[(std::size_t)t], b = B[(std::size_t)t];
                        if (std::fabs(D) <= b) {
                            row.uncertain++;
                        } else if (f.bytes[(std::size_t)t] != truth.facing[(std::size_t)t]) {
                            char buf[160];
                            std::snprintf(buf, sizeof buf,
                                          ": facing %d, exact %d, D %.6g > bound %.6g",
                                          f.bytes[(std::size_t)t], truth.facing[(std::size_t)t], D,
                                          b);
                            fail(where(v, t) + buf);
                            row.violations++;
                        }
                    }
                } else { /* biased: eps_bias's threshold, stateless here */
                    const std::vector<double> &B = bounds(s, l, truth, v.arithmetic);
                    const double tau = sv_eps_bias_threshold(s.data.eps_distance, s.data.eps_angle,
                                                             s.data.center, &l);
                    for (int t = 0; t < nt; t++) {
                        const double D = truth.D[(std::size_t)t], b = B[(std::size_t)t];
                        if (std::fabs(D - tau) <= b) {
                            row.uncertain++;
                        } else if (f.bytes[(std::size_t)t] != (D > tau)) {
                            char buf[160];
                            std::snprintf(buf, sizeof buf,
                                          ": facing %d, D %.6g, threshold %.6g, bound %.6g",
                                          f.bytes[(std::size_t)t], D, tau, b);
                            fail(where(v, t) + buf);
                            row.violations++;
                        }
                    }
                }
                /* Silhouette edges: compared only where some byte differs. */
                row.silhouette_exact += sil_exact;
                if (mis) {
                    for (const SilEdge &e : ps.sil_edges) {
                        const std::size_t a = (std::size_t)e.p1, b = (std::size_t)e.p2;
                        row.silhouette_changed += (truth.facing[a] != truth.facing[b]) !=
                                                  (f.bytes[a] != f.bytes[b]);
                    }
                }
                /* Flicker: frames L, L', L; counted on the step L' -> L.
                 * eps_bias runs with hysteresis from the second frame on,
                 * each frame's previous bytes the frame before's; the
                 * stateless variants' third frame is their first. */
                const bool hysteresis = v.contract == Contract::biased;
                FacingBuffer &fj = jit[vi];
                fj.reset(nt);
                v.run(s.data, lj, hysteresis ? f.data() : nullptr, fj.data());
                const FacingBuffer *third = &f;
                if (hysteresis) {
                    FacingBuffer &fb = back[vi];
                    fb.reset(nt);
                    v.run(s.data, l, fj.data(), fb.data());
                    third = &fb;
                }
                for (int t = 0; t < nt; t++) {
                    row.flicker += fj.bytes[(std::size_t)t] != third->bytes[(std::size_t)t];
                }
            }
        }
    }
    if (o_.timing) {
        for (std::size_t vi = 0; vi < nv; vi++) {
            if (o_.progress) {
                o_.progress(m.name + ": " + p.name + ": timing " + vars[vi]->name);
            }
            switch (svbench::timer_auto()) {
            case svbench::TimerKind::rdtscp:
                time_variant<svbench::TscRdtscp>(*vars[vi], m, ls, rows[vi]);
                break;
            default: time_variant<svbench::TscCpuid>(*vars[vi], m, ls, rows[vi]); break;
            }
        }
    }
    for (StudyRow &r : rows) res_.rows.push_back(r);
}

} // namespace

StudyResult run_study(const std::vector<const StudyModel *> &models, const StudyOptions &o) {
    StudyResult res;
    std::vector<const Variant *> vars = o.variants;
    if (vars.empty()) {
        for (const Variant &v : variants()) {
            if (runnable(v)) vars.push_back(&v);
        }
    }
    std::vector<const Placement *> places = o.placements;
    if (places.empty()) {
        for (const Placement &p : placements()) places.push_back(&p);
    }
    if (o.timing) {
        res.pinned_cpu = svbench::pin_to_current_cpu();
        const svbench::TimerKind k = svbench::timer_auto();
        res.timer = std::string(svbench::timer_name(k)) + " (" + svbench::timer_sequence(k) + ")";
        res.tsc_hz = svbench::estimate_tsc_hz(0.05);
    }
    Study study(o, res);
    for (const StudyModel *m : models) {
        for (const Placement *p : places) {
            if (o.progress) o.progress(m->name + ": " + p->name);
            study.run_placement(*m, *p, vars);
        }
    }
    return res;
}

} // namespace acc
} // namespace sv
