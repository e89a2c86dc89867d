/*
 * shadowvol: shadows right for any caster (issue 27). A prepared surface
 * splits into connected shells; a shell is CLOSED when every one of its
 * edges is run by exactly two triangles in opposite directions and it
 * encloses a positive volume. The paper's volume (the back-facing
 * triangles, dangling edges completed by the facing[numTriangles] = 1
 * sentinel) is the exact shadow only of closed shells; every other shell
 * (open, non-manifold, inconsistently wound, inside out) needs the general
 * rule, which counts the triangles between a point and the light. The
 * general rule is built here the cheap way: the shell made two-sided (each
 * triangle followed, after the surface's own triangles, by its reverse), so
 * that the paper's routines, unchanged, build the general volume. The
 * derivation and its limits are in docs/CASTERS.md.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SHADOWVOL_CASTERS_H
#define SHADOWVOL_CASTERS_H

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "shadowvol_mesh.h"

namespace sv {

/* Which volume a shell casts. */
enum class CasterRule {
    automatic, /* closed shells the paper's rule, the others the general rule */
    closed,    /* the paper's rule everywhere (exact only for closed shells) */
    general,   /* the general rule everywhere (exact for any triangle set) */
};
const char *caster_rule_name(CasterRule r);
/* "auto", "closed" or "general"; false for anything else. */
bool caster_rule_by_name(const std::string &name, CasterRule &out);

/* One connected shell: the triangles reachable from each other across
 * shared edges (sharing only a vertex does not connect). */
struct Shell {
    int64_t triangles = 0;
    int64_t boundary_edges = 0;       /* run by one triangle */
    int64_t same_direction_edges = 0; /* run by two triangles the same way */
    int64_t non_manifold_edges = 0;   /* run by three or more triangles */
    double signed_volume = 0;         /* sum of the triangles' tetrahedra to the origin */
    double volume_magnitude = 0;      /* the same sum of absolute values (its rounding scale) */
    /* Every edge run twice, in opposite directions, and a volume that is
     * not negative (an inside-out closed shell counts -1 per layer, which
     * could cancel another shell's +1 at a pixel). */
    bool closed() const;
    /* Why the shell is (not) closed, in words. */
    std::string reason() const;
};

struct ShellMap {
    std::vector<int> triangle_shell; /* per kept triangle of the surface */
    std::vector<Shell> shells;       /* numbered by their first triangle */
    int64_t closed_shells() const;
};

/* The shells of S. O(n log n). */
ShellMap find_shells(const PreparedSurface &s);

/* Does shell SHELL get the general rule under RULE? */
bool shell_uses_general_rule(const Shell &shell, CasterRule rule);

/* The ground hint (docs/CASTERS.md, "The ground hint"). A surface declared
 * GROUND is the top of a solid whose other side is never seen (the
 * `--ground` quad; a glTF mesh or node with extras "shadowvol_ground":
 * true, as the demo scene's terrain): the paper's volume of its dark
 * triangles, dangling edges and all, is then that solid's exact shadow
 * wherever nothing that can be lit lies below it, so under auto every
 * shell of it keeps the paper's rule. Nothing here checks the
 * declaration: the ray truth judges it (a wrong one shows as FAILED).
 * closed and general are kept as they are. */
CasterRule surface_caster_rule(CasterRule rule, bool declared_ground);
/* Shell SHELL's rule under RULE on a surface declared GROUND (or not), and
 * why, in words: what `shadowvol inspect` prints. */
bool shell_uses_general_rule(const Shell &shell, CasterRule rule, bool declared_ground);
std::string shell_rule_reason(const Shell &shell, bool declared_ground);

/* Shell SHELL of S alone: its triangles in their order, prepared again
 * (S's vertices, numbered the same). What `shadowvol verify` proves the
 * general rule on, one shell at a time. */
PreparedSurface shell_surface(const PreparedSurface &s, const ShellMap &shells, int shell);

/* The surface the volume routines take for S under RULE: nullptr when S
 * itself is (every shell gets the paper's rule), else S's triangles in
 * their order (so facing bytes 0 .. n-1 are S's own, for the lighting
 * pass) followed by the reverse (c, b, a) of every triangle (a, b, c) of
 * a shell under the general rule; triangle_source[n + j] names the
 * triangle reverse j comes from. The reverse's near cap is (a, b, c), S's
 * own triangle in its own vertex order, so a lit triangle and the cap of
 * its dark twin rasterise to the same depths. The caster's vertices are
 * S's, numbered the same (nothing is welded again), so a volume's indices
 * address S's shadow vertices; its planes are S's, and each reverse's is
 * its source's negated. */
std::shared_ptr<PreparedSurface> two_sided_caster(const PreparedSurface &s, const ShellMap &shells,
                                                  CasterRule rule);

/* Was CASTER built by two_sided_caster from a surface with S's vertex
 * count and triangles? Then a moved S (the same topology, new positions
 * and planes: a posed skin) needs only refresh_two_sided_caster. */
bool two_sided_caster_fits(const PreparedSurface &s, const PreparedSurface &caster);
/* CASTER's positions and planes from S's (O(n), no sorting). */
void refresh_two_sided_caster(const PreparedSurface &s, PreparedSurface &caster);

/* How the general rule's volume is built: the two-sided caster (the
 * paper's routines on the shell and its reverse) or the direct kernels
 * (sv_create_general_sil_triangles on the general edge table). Both give
 * the same stencil; docs/CASTERS.md measures them. */
enum class GeneralBuild { two_sided, direct };
const char *general_build_name(GeneralBuild b);
/* "two-sided" or "direct"; false for anything else. */
bool general_build_by_name(const std::string &name, GeneralBuild &out);

/* The general edge table of a surface under a rule (shadowvol.h,
 * sv_general_edges): built once per topology; positions may move. */
struct GeneralEdgeTable {
    std::vector<SilEdge> paper; /* the shells under the paper's rule: S's SilEdges, in order */
    std::vector<SilEdge> pairs, opens;
    std::vector<sv_shared_edge> shared;
    std::vector<int> shared_uses;
    /* Per triangle, the general byte of a triangle that faces the light:
     * SV_GENERAL_LIT in a general shell, SV_GENERAL_NONE under the paper's
     * rule (sv_general_facing_from_calculated). */
    std::vector<uint8_t> lit_byte;
    int64_t general_triangles = 0; /* in shells under the general rule */
    sv_general_edges view() const;
    std::size_t sil_capacity() const; /* sv_general_sil_capacity */
};

/* The table of S under RULE. Every welded edge of a general shell once, with every triangle on
 * it: a pair is (p1, p2, v1, v2) with p1 the earlier triangle, running v1
 * -> v2 (the paper's SilEdge, as prepare_surface pairs it); a shared
 * edge runs v1 -> v2 as its earliest use. O(n log n). */
GeneralEdgeTable general_edge_table(const PreparedSurface &s, const ShellMap &shells,
                                    CasterRule rule);

} // namespace sv

#endif /* SHADOWVOL_CASTERS_H */
