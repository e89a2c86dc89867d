// Box modelling of the character on a quad mesh, subdivision and
// triangulation. See model_gen.h for the part structure and the counts.
//
// Determinism: only +, -, *, / and sqrt (all correctly rounded in IEEE 754)
// are used on positions, no sin/cos, and the library is compiled with
// -ffp-contract=off, so the bytes written do not depend on the libm.

#include "model_gen.h"

#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <stdexcept>
#include <utility>

namespace svgen {
namespace {

Vec3 add(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
Vec3 sub(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Vec3 mul(Vec3 a, double s) { return {a.x * s, a.y * s, a.z * s}; }
double dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

using Quad = std::array<std::uint32_t, 4>;

// ---------------------------------------------------------------- torso --

// Torso box: x (width) [-0.21, 0.21] in 6 cells, y (height) [0.85, 1.45] in
// 8 cells, z (depth) [-0.12, 0.12] in 4 cells. +y is up, +z is the front
// (glTF conventions).
constexpr int kNx = 6, kNy = 8, kNz = 4;
constexpr double kX0 = -0.21, kX1 = 0.21;
constexpr double kY0 = 0.85, kY1 = 1.45;
constexpr double kZ0 = -0.12, kZ1 = 0.12;

QuadMesh build_torso() {
    QuadMesh m;
    const int n[3] = {kNx, kNy, kNz};
    std::map<std::array<int, 3>, std::uint32_t> index; // grid point -> vertex
    auto vertex = [&](std::array<int, 3> g) {
        auto it = index.find(g);
        if (it != index.end()) return it->second;
        const double tx = double(g[0]) / kNx, ty = double(g[1]) / kNy, tz = double(g[2]) / kNz;
        double x = kX0 + (kX1 - kX0) * tx;
        const double y = kY0 + (kY1 - kY0) * ty;
        double z = kZ0 + (kZ1 - kZ0) * tz;
        // A waist (narrower between hips and chest) and a rounded section (the
        // sides thinner than the middle): the figure is not a box.
        const double xn = x / kX1;
        x *= 1.0 - 0.6 * ty * (1.0 - ty);
        z *= 1.0 - 0.3 * xn * xn;
        const std::uint32_t i = static_cast<std::uint32_t>(m.vertices.size());
        m.vertices.push_back({x, y, z});
        index.emplace(g, i);
        return i;
    };
    // Face with outward axis a and sign s; (b, c) the other axes with
    // e_b x e_c = e_a, so (p,q) (p+1,q) (p+1,q+1) (p,q+1) is counter-clockwise
    // seen from +a.
    for (int a = 0; a < 3; ++a) {
        const int b = (a + 1) % 3, c = (a + 2) % 3;
        for (int s = 0; s < 2; ++s) {
            for (int q = 0; q < n[c]; ++q) {
                for (int p = 0; p < n[b]; ++p) {
                    std::array<std::uint32_t, 4> v;
                    const int pp[4] = {p, p + 1, p + 1, p};
                    const int qq[4] = {q, q, q + 1, q + 1};
                    for (int k = 0; k < 4; ++k) {
                        std::array<int, 3> g;
                        g[a] = s ? n[a] : 0;
                        g[b] = pp[k];
                        g[c] = qq[k];
                        v[k] = vertex(g);
                    }
                    if (s == 0)
                        m.quads.push_back({v[0], v[3], v[2], v[1]});
                    else
                        m.quads.push_back(v);
                }
            }
        }
    }
    return m;
}

// ------------------------------------------------------------ extrusion --

// One ring of an extruded limb: distance t along the limb's direction d,
// radii ra (along u) and rb (along w), and a shift (su, sw) of its centre.
struct Ring {
    double t, ra, rb, su, sw;
};

struct Limb {
    Vec3 d, u, w;            // direction and the two axes of its cross-section
    std::vector<Ring> rings; // one per segment
    double cap_bump;         // how far the patch's interior vertices bulge
};

// Extrudes the patch (the quads whose centroid satisfies `in_patch`, a disc
// whose boundary is one loop) by limb.rings.size() segments. Ring 0 is the
// patch's boundary where it is; ring j > 0 gets new vertices, placed on an
// ellipse in the (u, w) plane by the direction of each boundary vertex from
// the loop's centroid; walls (a_j, b_j, b_j+1, a_j+1) join ring j to ring j+1
// for each boundary edge a -> b of the patch; the patch itself moves to the
// last ring. Adds (boundary edges) x (segments) quads.
template <class Pred> void extrude(QuadMesh &m, Pred in_patch, const Limb &limb) {
    std::vector<std::size_t> patch;
    for (std::size_t i = 0; i < m.quads.size(); ++i) {
        Vec3 c{0, 0, 0};
        for (auto v : m.quads[i]) c = add(c, m.vertices[v]);
        if (in_patch(mul(c, 0.25))) patch.push_back(i);
    }
    if (patch.empty()) throw std::logic_error("extrude: empty patch");
    std::set<std::pair<std::uint32_t, std::uint32_t>> edges;
    for (auto i : patch)
        for (int k = 0; k < 4; ++k) edges.insert({m.quads[i][k], m.quads[i][(k + 1) % 4]});
    std::map<std::uint32_t, std::uint32_t> next; // boundary: a -> b
    std::set<std::uint32_t> patch_vertices;
    for (auto e : edges) {
        patch_vertices.insert(e.first);
        if (!edges.count({e.second, e.first})) {
            if (!next.emplace(e.first, e.second).second)
                throw std::logic_error("extrude: patch boundary is not a simple loop");
        }
    }
    std::vector<std::uint32_t> loop;
    for (std::uint32_t v = next.begin()->first;;) {
        loop.push_back(v);
        v = next.at(v);
        if (v == loop.front()) break;
        if (loop.size() > next.size()) throw std::logic_error("extrude: boundary loop");
    }
    if (loop.size() != next.size()) throw std::logic_error("extrude: boundary has several loops");

    Vec3 c0{0, 0, 0};
    for (auto v : loop) c0 = add(c0, m.vertices[v]);
    c0 = mul(c0, 1.0 / double(loop.size()));
    double ea = 0, eb = 0;
    for (auto v : loop) {
        const Vec3 r = sub(m.vertices[v], c0);
        ea = std::fmax(ea, std::fabs(dot(r, limb.u)));
        eb = std::fmax(eb, std::fabs(dot(r, limb.w)));
    }
    auto place = [&](Vec3 p, const Ring &ring, double extra_t, bool on_ellipse) {
        const Vec3 r = sub(p, c0);
        double a = dot(r, limb.u) / ea, b = dot(r, limb.w) / eb;
        if (on_ellipse) {
            const double len = std::sqrt(a * a + b * b);
            a /= len;
            b /= len;
        }
        Vec3 q = add(c0, mul(limb.d, ring.t + extra_t));
        q = add(q, mul(limb.u, ring.ra * a + ring.su));
        q = add(q, mul(limb.w, ring.rb * b + ring.sw));
        return q;
    };

    const std::size_t k = limb.rings.size();
    std::vector<std::vector<std::uint32_t>> rings(k + 1);
    rings[0] = loop;
    for (std::size_t j = 1; j <= k; ++j) {
        for (auto v : loop) {
            rings[j].push_back(static_cast<std::uint32_t>(m.vertices.size()));
            m.vertices.push_back(place(m.vertices[v], limb.rings[j - 1], 0.0, true));
        }
    }
    // The patch moves to the last ring; its interior vertices bulge out.
    std::map<std::uint32_t, std::uint32_t> moved;
    for (std::size_t i = 0; i < loop.size(); ++i) moved[loop[i]] = rings[k][i];
    for (auto v : patch_vertices) {
        if (moved.count(v)) continue;
        const Vec3 r = sub(m.vertices[v], c0);
        const double a = dot(r, limb.u) / ea, b = dot(r, limb.w) / eb;
        const double bump = limb.cap_bump * (1.0 - 0.5 * (a * a + b * b));
        m.vertices[v] = place(m.vertices[v], limb.rings[k - 1], bump, false);
    }
    for (auto i : patch)
        for (auto &v : m.quads[i]) {
            auto it = moved.find(v);
            if (it != moved.end()) v = it->second;
        }
    const std::size_t nl = loop.size();
    for (std::size_t j = 0; j < k; ++j)
        for (std::size_t i = 0; i < nl; ++i) {
            const std::size_t i1 = (i + 1) % nl;
            m.quads.push_back({rings[j][i], rings[j][i1], rings[j + 1][i1], rings[j + 1][i]});
        }
}

bool near(double a, double b) { return std::fabs(a - b) < 1e-9; }

} // namespace

QuadMesh build_character_quads() {
    QuadMesh m = build_torso();
    const double cx = (kX1 - kX0) / kNx, cy = (kY1 - kY0) / kNy;
    const Vec3 ex{1, 0, 0}, ey{0, 1, 0}, ez{0, 0, 1};

    // Neck and head: the top face's middle 2x2 cells, upward. 10 segments.
    Limb head{ey,
              ex,
              ez,
              {{0.020, 0.055, 0.050, 0, 0.000}, // neck
               {0.070, 0.045, 0.045, 0, 0.005},
               {0.110, 0.050, 0.052, 0, 0.010},
               {0.140, 0.070, 0.080, 0, 0.015}, // jaw
               {0.180, 0.085, 0.095, 0, 0.012},
               {0.230, 0.095, 0.105, 0, 0.010},
               {0.280, 0.097, 0.107, 0, 0.008},
               {0.330, 0.090, 0.100, 0, 0.006},
               {0.370, 0.075, 0.085, 0, 0.004},
               {0.400, 0.045, 0.050, 0, 0.002}}, // crown
              0.015};
    extrude(
        m, [&](Vec3 c) { return near(c.y, kY1) && std::fabs(c.x) < cx && std::fabs(c.z) < 0.06; },
        head);

    // Arms (T-pose): each side face's top two rows, middle two columns,
    // outward. 12 segments each; the hand is flat (palm down).
    for (int side = -1; side <= 1; side += 2) {
        const double s = side;
        Limb arm{{s, 0, 0},
                 ey,
                 ez,
                 {{0.030, 0.068, 0.055, -0.001, 0}, // shoulder
                  {0.080, 0.063, 0.052, -0.003, 0},
                  {0.160, 0.055, 0.048, -0.006, 0},
                  {0.250, 0.049, 0.045, -0.010, 0},
                  {0.320, 0.044, 0.042, -0.013, 0}, // elbow
                  {0.360, 0.043, 0.041, -0.014, 0},
                  {0.440, 0.045, 0.043, -0.018, 0},
                  {0.520, 0.037, 0.035, -0.021, 0},
                  {0.580, 0.030, 0.028, -0.023, 0}, // wrist
                  {0.620, 0.020, 0.040, -0.025, 0}, // hand
                  {0.700, 0.018, 0.045, -0.028, 0},
                  {0.760, 0.012, 0.030, -0.030, 0}},
                 0.010};
        extrude(
            m,
            [&](Vec3 c) { return c.x * s > 0.19 && c.y > kY1 - 2 * cy && std::fabs(c.z) < 0.06; },
            arm);
    }

    // Legs: the bottom face's outer two columns, middle two rows, downward,
    // slightly apart. 12 segments each; the foot reaches forward (+z).
    for (int side = -1; side <= 1; side += 2) {
        const double s = side;
        Limb leg{{0, -1, 0},
                 ex,
                 ez,
                 {{0.030, 0.075, 0.068, s * 0.001, 0.000}, // hip
                  {0.100, 0.078, 0.070, s * 0.003, 0.000},
                  {0.200, 0.072, 0.066, s * 0.005, 0.000},
                  {0.300, 0.065, 0.060, s * 0.008, 0.000},
                  {0.400, 0.055, 0.055, s * 0.010, 0.000}, // knee
                  {0.460, 0.050, 0.052, s * 0.011, 0.000},
                  {0.550, 0.052, 0.056, s * 0.013, -0.005}, // calf
                  {0.650, 0.045, 0.048, s * 0.015, 0.000},
                  {0.740, 0.035, 0.038, s * 0.017, 0.000}, // ankle
                  {0.790, 0.040, 0.050, s * 0.018, 0.020},
                  {0.830, 0.045, 0.090, s * 0.019, 0.050}, // foot
                  {0.845, 0.040, 0.080, s * 0.019, 0.060}},
                 0.004};
        extrude(
            m, [&](Vec3 c) { return near(c.y, kY0) && c.x * s > cx && std::fabs(c.z) < 0.06; },
            leg);
    }
    return m;
}

TriMesh triangulate(const QuadMesh &mesh, int n) {
    if (n < 1) throw std::invalid_argument("triangulate: n must be >= 1");
    std::vector<Vec3> v = mesh.vertices;
    // New vertices on each undirected edge, ordered from its lower-numbered
    // end, so both quads that share the edge use the same ones.
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> edge_first;
    auto edge_point = [&](std::uint32_t a, std::uint32_t b, int i) -> std::uint32_t {
        if (i == 0) return a;
        if (i == n) return b;
        const bool flip = a > b;
        const std::uint32_t lo = flip ? b : a, hi = flip ? a : b;
        auto it = edge_first.find({lo, hi});
        if (it == edge_first.end()) {
            const std::uint32_t first = static_cast<std::uint32_t>(v.size());
            for (int k = 1; k < n; ++k) {
                const double t = double(k) / n;
                v.push_back(add(mul(v[lo], 1.0 - t), mul(v[hi], t)));
            }
            it = edge_first.emplace(std::make_pair(lo, hi), first).first;
        }
        const int k = flip ? n - i : i;
        return it->second + static_cast<std::uint32_t>(k - 1);
    };

    std::vector<Quad> quads;
    quads.reserve(mesh.quads.size() * std::size_t(n) * std::size_t(n));
    std::vector<std::uint32_t> grid(std::size_t(n + 1) * std::size_t(n + 1));
    for (const Quad &q : mesh.quads) {
        // (i, j) in [0, n]^2: q0 at (0,0), q1 at (n,0), q2 at (n,n), q3 at (0,n).
        auto at = [&](int i, int j) -> std::uint32_t & {
            return grid[std::size_t(j) * (n + 1) + i];
        };
        for (int i = 0; i <= n; ++i) {
            at(i, 0) = edge_point(q[0], q[1], i);
            at(n, i) = edge_point(q[1], q[2], i);
            at(n - i, n) = edge_point(q[2], q[3], i);
            at(0, n - i) = edge_point(q[3], q[0], i);
        }
        for (int j = 1; j < n; ++j)
            for (int i = 1; i < n; ++i) {
                const double s = double(i) / n, t = double(j) / n;
                const Vec3 p = add(add(mul(v[q[0]], (1 - s) * (1 - t)), mul(v[q[1]], s * (1 - t))),
                                   add(mul(v[q[2]], s * t), mul(v[q[3]], (1 - s) * t)));
                at(i, j) = static_cast<std::uint32_t>(v.size());
                v.push_back(p);
            }
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i)
                quads.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
    }

    TriMesh out;
    out.positions.reserve(v.size() * 3);
    for (const Vec3 &p : v) {
        out.positions.push_back(static_cast<float>(p.x));
        out.positions.push_back(static_cast<float>(p.y));
        out.positions.push_back(static_cast<float>(p.z));
    }
    out.indices.reserve(quads.size() * 6);
    for (const Quad &q : quads) {
        // Split along the shorter diagonal (ties: q0-q2).
        const Vec3 d02 = sub(v[q[2]], v[q[0]]), d13 = sub(v[q[3]], v[q[1]]);
        if (dot(d02, d02) <= dot(d13, d13)) {
            out.indices.insert(out.indices.end(), {q[0], q[1], q[2], q[0], q[2], q[3]});
        } else {
            out.indices.insert(out.indices.end(), {q[0], q[1], q[3], q[1], q[2], q[3]});
        }
    }
    return out;
}

TriMesh build_character(int n) { return triangulate(build_character_quads(), n); }

std::string model_file_name(const TriMesh &mesh) {
    return "character_" + std::to_string(mesh.num_triangles()) + ".glb";
}

} // namespace svgen
