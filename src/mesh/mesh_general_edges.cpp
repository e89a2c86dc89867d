/*
 * The general edge table of include/shadowvol_casters.h: every welded edge
 * of a surface with every triangle on it and the way each runs along it,
 * sorted into the four classes of sv_general_edges (shadowvol.h) that the
 * general kernels draw. Built once per surface topology.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <algorithm>
#include <cstdint>

#include "shadowvol_casters.h"

namespace sv {

const char *general_build_name(GeneralBuild b) {
    return b == GeneralBuild::direct ? "direct" : "two-sided";
}

bool general_build_by_name(const std::string &name, GeneralBuild &out) {
    for (GeneralBuild b : {GeneralBuild::two_sided, GeneralBuild::direct}) {
        if (name == general_build_name(b)) {
            out = b;
            return true;
        }
    }
    return false;
}

sv_general_edges GeneralEdgeTable::view() const {
    sv_general_edges e{};
    e.paper = paper.data(), e.numPaper = (int)paper.size();
    e.pairs = pairs.data(), e.numPairs = (int)pairs.size();
    e.opens = opens.data(), e.numOpens = (int)opens.size();
    e.shared = shared.data(), e.numShared = (int)shared.size();
    e.sharedUses = shared_uses.data(), e.numSharedUses = (int)shared_uses.size();
    return e;
}

std::size_t GeneralEdgeTable::sil_capacity() const {
    const sv_general_edges e = view();
    return sv_general_sil_capacity(&e);
}

GeneralEdgeTable general_edge_table(const PreparedSurface &s, const ShellMap &shells,
                                    CasterRule rule) {
    const int nt = s.num_triangles();
    GeneralEdgeTable g;
    std::vector<uint8_t> general((std::size_t)nt);
    for (int t = 0; t < nt; t++) {
        const Shell &sh = shells.shells[(std::size_t)shells.triangle_shell[(std::size_t)t]];
        general[(std::size_t)t] = shell_uses_general_rule(sh, rule) ? 1 : 0;
        g.general_triangles += general[(std::size_t)t];
    }
    g.lit_byte.resize((std::size_t)nt);
    for (int t = 0; t < nt; t++)
        g.lit_byte[(std::size_t)t] = general[(std::size_t)t] ? SV_GENERAL_LIT : SV_GENERAL_NONE;
    /* The paper's shells keep S's SilEdges as they are, in their order: a
     * surface of closed shells under auto gives today's index list. (An
     * edge never joins two shells, so p1's shell is p2's.) */
    for (const SilEdge &e : s.sil_edges)
        if (!general[(std::size_t)e.p1]) g.paper.push_back(e);

    /* The general shells' uses, grouped by undirected edge, in use order
     * within an edge (as prepare_surface groups them). */
    struct Use {
        uint64_t key; /* (min vertex << 32) | max vertex */
        int use;      /* 3 * triangle + corner: the use a -> b is corner -> corner + 1 */
    };
    std::vector<Use> uses;
    uses.reserve(3 * (std::size_t)nt);
    auto from = [&](int u) { return s.indices[(std::size_t)u]; };
    auto to = [&](int u) { return s.indices[(std::size_t)(u % 3 == 2 ? u - 2 : u + 1)]; };
    for (int u = 0; u < 3 * nt; u++) {
        if (!general[(std::size_t)(u / 3)]) continue;
        const auto a = (uint32_t)from(u), b = (uint32_t)to(u);
        uses.push_back({a < b ? ((uint64_t)a << 32 | b) : ((uint64_t)b << 32 | a), u});
    }
    std::sort(uses.begin(), uses.end(), [](const Use &x, const Use &y) {
        return x.key != y.key ? x.key < y.key : x.use < y.use;
    });
    /* Each class in the order of its edges' first uses (the order
     * prepare_surface gives SilEdges: the triangles' order). */
    struct Ordered {
        int first_use;
        std::size_t uses_begin, uses_end;
    };
    std::vector<Ordered> pair_order, open_order, shared_order;
    for (std::size_t k = 0; k < uses.size();) {
        std::size_t e = k;
        while (e < uses.size() && uses[e].key == uses[k].key) e++;
        const int u0 = uses[k].use;
        const std::size_t n = e - k;
        if (n == 1) {
            open_order.push_back({u0, k, e});
        } else if (n == 2 && from(uses[k + 1].use) == to(u0)) {
            pair_order.push_back({u0, k, e});
        } else {
            shared_order.push_back({u0, k, e});
        }
        k = e;
    }
    auto by_first_use = [](const Ordered &x, const Ordered &y) {
        return x.first_use < y.first_use;
    };
    std::sort(pair_order.begin(), pair_order.end(), by_first_use);
    std::sort(open_order.begin(), open_order.end(), by_first_use);
    std::sort(shared_order.begin(), shared_order.end(), by_first_use);
    for (const Ordered &o : pair_order) {
        const int u1 = uses[o.uses_begin].use, u2 = uses[o.uses_begin + 1].use;
        g.pairs.push_back({u1 / 3, u2 / 3, 2 * from(u1), 2 * to(u1)});
    }
    for (const Ordered &o : open_order) {
        const int u = uses[o.uses_begin].use;
        g.opens.push_back({u / 3, u / 3, 2 * from(u), 2 * to(u)});
    }
    for (const Ordered &o : shared_order) {
        const int u0 = uses[o.uses_begin].use;
        const int v1 = from(u0);
        sv_shared_edge x{2 * v1, 2 * to(u0), (int)g.shared_uses.size(),
                         (int)(o.uses_end - o.uses_begin)};
        for (std::size_t k = o.uses_begin; k < o.uses_end; k++) {
            const int u = uses[k].use;
            g.shared_uses.push_back(2 * (u / 3) + (from(u) == v1 ? 0 : 1));
        }
        g.shared.push_back(x);
    }
    return g;
}

} // namespace sv
