/*
 * Shells and the caster rule of include/shadowvol_casters.h.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <algorithm>
#include <cmath>
#include <numeric>

#include "shadowvol_casters.h"

namespace sv {

namespace {

/* Union-find over triangles, with path halving. */
int find_root(std::vector<int> &parent, int t) {
    while (parent[(std::size_t)t] != t) {
        parent[(std::size_t)t] = parent[(std::size_t)parent[(std::size_t)t]];
        t = parent[(std::size_t)t];
    }
    return t;
}

enum class EdgeKind : uint8_t { manifold, boundary, same_direction, non_manifold };

} // namespace

const char *caster_rule_name(CasterRule r) {
    switch (r) {
    case CasterRule::automatic: return "auto";
    case CasterRule::closed: return "closed";
    case CasterRule::general: return "general";
    }
    return "?";
}

bool caster_rule_by_name(const std::string &name, CasterRule &out) {
    for (CasterRule r : {CasterRule::automatic, CasterRule::closed, CasterRule::general}) {
        if (name == caster_rule_name(r)) {
            out = r;
            return true;
        }
    }
    return false;
}

bool Shell::closed() const {
    /* The volume's rounding: each term is a product of three coordinates,
     * summed in double; 1e-9 of the magnitude is far above that and far
     * below any shell that is really inside out. A flat closed shell (a
     * plane and its reverse) has volume 0 and is closed: the paper's rule
     * counts it exactly (one of each pair faces away). */
    return boundary_edges == 0 && same_direction_edges == 0 && non_manifold_edges == 0 &&
           signed_volume >= -1e-9 * volume_magnitude;
}

std::string Shell::reason() const {
    std::string r;
    auto add = [&r](int64_t n, const char *what) {
        if (n == 0) return;
        if (!r.empty()) r += ", ";
        r += std::to_string(n) + " " + what;
    };
    add(boundary_edges, "boundary edges");
    add(non_manifold_edges, "edges of 3+ triangles");
    add(same_direction_edges, "edges run twice the same way");
    if (r.empty()) {
        return closed() ? "closed: every edge run twice, in opposite directions"
                        : "inside out: closed, but its volume is negative";
    }
    return "open: " + r;
}

int64_t ShellMap::closed_shells() const {
    return std::count_if(shells.begin(), shells.end(), [](const Shell &s) { return s.closed(); });
}

ShellMap find_shells(const PreparedSurface &s) {
    const int nt = s.num_triangles();
    struct Use {
        uint64_t key; /* (min vertex << 32) | max vertex */
        int triangle;
        bool forward; /* runs from the smaller vertex to the larger */
    };
    std::vector<Use> uses((std::size_t)nt * 3);
    for (int u = 0; u < 3 * nt; u++) {
        const auto a = (uint32_t)s.indices[(std::size_t)u];
        const auto b = (uint32_t)s.indices[(std::size_t)(u % 3 == 2 ? u - 2 : u + 1)];
        uses[(std::size_t)u] = {a < b ? ((uint64_t)a << 32 | b) : ((uint64_t)b << 32 | a), u / 3,
                                a < b};
    }
    std::sort(uses.begin(), uses.end(), [](const Use &x, const Use &y) { return x.key < y.key; });
    std::vector<int> parent((std::size_t)nt);
    std::iota(parent.begin(), parent.end(), 0);
    struct EdgeRecord {
        int triangle;
        EdgeKind kind;
    };
    std::vector<EdgeRecord> odd_edges; /* every edge that is not manifold */
    for (std::size_t k = 0; k < uses.size();) {
        std::size_t e = k;
        int forward = 0;
        while (e < uses.size() && uses[e].key == uses[k].key) {
            forward += uses[e].forward ? 1 : 0;
            const int ra = find_root(parent, uses[k].triangle),
                      rb = find_root(parent, uses[e].triangle);
            if (ra != rb) parent[(std::size_t)std::max(ra, rb)] = std::min(ra, rb);
            e++;
        }
        const std::size_t n = e - k;
        if (n == 1) {
            odd_edges.push_back({uses[k].triangle, EdgeKind::boundary});
        } else if (n == 2 && forward != 1) {
            odd_edges.push_back({uses[k].triangle, EdgeKind::same_direction});
        } else if (n > 2) {
            odd_edges.push_back({uses[k].triangle, EdgeKind::non_manifold});
        }
        k = e;
    }
    ShellMap m;
    m.triangle_shell.assign((std::size_t)nt, -1);
    std::vector<int> shell_of_root((std::size_t)nt, -1);
    for (int t = 0; t < nt; t++) {
        const int r = find_root(parent, t);
        int &id = shell_of_root[(std::size_t)r];
        if (id < 0) {
            id = (int)m.shells.size();
            m.shells.emplace_back();
        }
        m.triangle_shell[(std::size_t)t] = id;
        Shell &sh = m.shells[(std::size_t)id];
        sh.triangles++;
        const float *p[3];
        for (int c = 0; c < 3; c++)
            p[c] = &s.positions[3 * (std::size_t)s.indices[3 * (std::size_t)t + (std::size_t)c]];
        /* p0 . (p1 x p2): six times the tetrahedron's signed volume. */
        const double cx = (double)p[1][1] * p[2][2] - (double)p[1][2] * p[2][1];
        const double cy = (double)p[1][2] * p[2][0] - (double)p[1][0] * p[2][2];
        const double cz = (double)p[1][0] * p[2][1] - (double)p[1][1] * p[2][0];
        const double v = (double)p[0][0] * cx + (double)p[0][1] * cy + (double)p[0][2] * cz;
        sh.signed_volume += v / 6;
        sh.volume_magnitude += std::fabs(v) / 6;
    }
    for (const EdgeRecord &r : odd_edges) {
        Shell &sh = m.shells[(std::size_t)m.triangle_shell[(std::size_t)r.triangle]];
        switch (r.kind) {
        case EdgeKind::boundary: sh.boundary_edges++; break;
        case EdgeKind::same_direction: sh.same_direction_edges++; break;
        case EdgeKind::non_manifold: sh.non_manifold_edges++; break;
        case EdgeKind::manifold: break;
        }
    }
    return m;
}

bool shell_uses_general_rule(const Shell &shell, CasterRule rule) {
    switch (rule) {
    case CasterRule::closed: return false;
    case CasterRule::general: return true;
    case CasterRule::automatic: return !shell.closed();
    }
    return true;
}

CasterRule surface_caster_rule(CasterRule rule, bool declared_ground) {
    return rule == CasterRule::automatic && declared_ground ? CasterRule::closed : rule;
}

bool shell_uses_general_rule(const Shell &shell, CasterRule rule, bool declared_ground) {
    return shell_uses_general_rule(shell, surface_caster_rule(rule, declared_ground));
}

std::string shell_rule_reason(const Shell &shell, bool declared_ground) {
    if (declared_ground && !shell.closed())
        return "declared ground (the top of a solid never seen from below): " + shell.reason();
    return shell.reason();
}

PreparedSurface shell_surface(const PreparedSurface &s, const ShellMap &shells, int shell) {
    std::vector<uint32_t> idx;
    for (int t = 0; t < s.num_triangles(); t++) {
        if (shells.triangle_shell[(std::size_t)t] != shell) continue;
        for (int c = 0; c < 3; c++) idx.push_back((uint32_t)s.indices[3 * (std::size_t)t + c]);
    }
    return prepare_surface(s.positions.data(), (std::size_t)s.num_vertices(), idx.data(),
                           idx.size());
}

std::shared_ptr<PreparedSurface> two_sided_caster(const PreparedSurface &s, const ShellMap &shells,
                                                  CasterRule rule) {
    const int nt = s.num_triangles();
    std::vector<uint32_t> idx(s.indices.begin(), s.indices.end());
    std::vector<int> reversed_of; /* the surface's triangle each reverse comes from */
    for (int t = 0; t < nt; t++) {
        const Shell &sh = shells.shells[(std::size_t)shells.triangle_shell[(std::size_t)t]];
        if (!shell_uses_general_rule(sh, rule)) continue;
        const std::size_t i = 3 * (std::size_t)t;
        /* (c, b, a): its near cap (i2, i1, i0) is (a, b, c) again. */
        idx.push_back((uint32_t)s.indices[i + 2]);
        idx.push_back((uint32_t)s.indices[i + 1]);
        idx.push_back((uint32_t)s.indices[i]);
        reversed_of.push_back(t);
    }
    if (reversed_of.empty()) return nullptr;
    /* The topology from the indices alone: every vertex at a distinct
     * stand-in position, so that nothing welds (a posed surface may put
     * two of its vertices at one point; its numbering must stay). The
     * positions and planes are the surface's (refresh_two_sided_caster).
     * prepare_surface pairs an edge's opposite uses in the order of their
     * triangles, so the surface's own triangles pair with each other first
     * and the reverses with the reverses: a triangle meets its own reverse
     * only across an edge nothing else pairs (a boundary edge, the extra
     * uses of a non-manifold one). Pairing every triangle with its own
     * reverse would be exact too, at about three times the quads. */
    const int nv = s.num_vertices();
    std::vector<float> stand_in(3 * (std::size_t)nv);
    for (int v = 0; v < nv; v++) {
        stand_in[3 * (std::size_t)v] = (float)(v & 0xFFFFFF); /* exact in float */
        stand_in[3 * (std::size_t)v + 1] = (float)(v >> 24);
        stand_in[3 * (std::size_t)v + 2] = 0.0f;
    }
    auto caster = std::make_shared<PreparedSurface>(
        prepare_surface(stand_in.data(), (std::size_t)nv, idx.data(), idx.size()));
    if (caster->num_vertices() != nv || caster->num_triangles() != (int)idx.size() / 3)
        throw PrepareError("two_sided_caster: the caster does not keep the surface's vertices");
    for (std::size_t j = 0; j < reversed_of.size(); j++)
        caster->triangle_source[(std::size_t)nt + j] = reversed_of[j];
    refresh_two_sided_caster(s, *caster);
    return caster;
}

bool two_sided_caster_fits(const PreparedSurface &s, const PreparedSurface &caster) {
    /* Built from exactly S's triangle count: its triangle n - 1 is its own
     * source, its triangle n (the first reverse) comes from before n. */
    const int nt = s.num_triangles();
    const std::vector<int> &src = caster.triangle_source;
    return nt > 0 && caster.num_vertices() == s.num_vertices() && caster.num_triangles() > nt &&
           src[(std::size_t)nt - 1] == nt - 1 && src[(std::size_t)nt] < nt &&
           std::equal(s.indices.begin(), s.indices.end(), caster.indices.begin());
}

void refresh_two_sided_caster(const PreparedSurface &s, PreparedSurface &caster) {
    const int nt = s.num_triangles();
    caster.positions = s.positions;
    caster.planes.resize((std::size_t)caster.num_triangles());
    caster.report.zero_normal_triangles = 0;
    for (int t = 0; t < caster.num_triangles(); t++) {
        /* The surface's own planes, bit for bit (the lighting pass reads
         * the caster's facing bytes as the surface's); a reverse's plane
         * is its source's negated, so that exactly one of the two faces
         * the light whenever the light is off their plane. */
        const Plane &p =
            s.planes[(std::size_t)(t < nt ? t : caster.triangle_source[(std::size_t)t])];
        caster.planes[(std::size_t)t] = t < nt ? p : Plane{-p.a, -p.b, -p.c, -p.d};
        if (p.a == 0.0f && p.b == 0.0f && p.c == 0.0f && p.d == 0.0f)
            caster.report.zero_normal_triangles++;
    }
}

} // namespace sv
