// The cases of each routine for `shadowvol check` (check_run.h): seeded
// inputs inside each routine's contract (include/shadowvol.h), every tail
// length 0..80 and a few sizes in the thousands (the last above 65536
// triangles, so "planned" runs its second size class too), the offsets the
// variant's alignment allows, facing none / all / half / random, cull bits
// on every plane, and the negative counts the contracts define. Each
// variant's output is compared with c_ref's byte for byte, and the guard
// zones around every buffer (the output sized exactly at its documented
// bound) must hold.
//
// Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>

#include "check_run.h"
#include "shadowvol_mesh.h"

namespace svcheck {

namespace {

enum class Facing { none, all, half, random };
constexpr Facing kFacingModes[] = {Facing::none, Facing::all, Facing::half, Facing::random};

const char *facing_name(Facing f) {
    switch (f) {
    case Facing::none: return "none facing";
    case Facing::all: return "all facing";
    case Facing::half: return "half facing";
    default: return "random facing";
    }
}

// Every tail of every loop the kernels have (256/64/32/16/8/4/1 elements),
// then sizes in the thousands; the last is in size class 1 of the planner.
// NEGATIVE adds the negative counts that A-E define (nothing read or
// written, 0 returned).
std::vector<int> case_sizes(bool negative) {
    std::vector<int> n;
    for (int i = 0; i <= 80; i++) n.push_back(i);
    for (int i : {255, 256, 257, 1021, 4099, 65541}) n.push_back(i);
    if (negative) n.insert(n.end(), {-1, -17});
    return n;
}

// Calls F(n, mode, caseno) for every size and every one of MODES, caseno
// counting from 1 (the offsets walk with it).
template <class Mode, size_t K, class F>
void for_each_case(bool negative, const Mode (&modes)[K], F f) {
    size_t caseno = 0;
    for (int n : case_sizes(negative)) {
        for (Mode mode : modes) f(n, mode, ++caseno);
    }
}

// Offsets with no alignment need: every byte, every int of a vector.
const std::vector<size_t> kByteOffsets = allowed_offsets(1, 1);
const std::vector<size_t> kIntOffsets = allowed_offsets(1, 4);

std::vector<uint8_t> facing_bytes(Rng &rng, int n, Facing mode) {
    std::vector<uint8_t> f((size_t)std::max(n, 0));
    const double p = mode == Facing::none   ? 0.0
                     : mode == Facing::all  ? 1.0
                     : mode == Facing::half ? 0.5
                                            : rng.unit();
    for (auto &b : f) b = rng.chance(p) ? 1 : 0;
    return f;
}

// A guard pattern per case: never 0 or 1 (a facing byte), and as an int
// negative (no index a kernel writes), so any write there shows.
uint8_t guard_pattern(Rng &rng) { return (uint8_t)(0xA0 | rng.below(0x20)); }

// The Ith offset of the allowed ones: cases walk through them, so every
// offset is met many times over the sizes.
size_t pick(const std::vector<size_t> &offsets, size_t i) { return offsets[i % offsets.size()]; }

std::string where(const char *what, int n, Facing mode, size_t offset) {
    return std::string(what) + "=" + std::to_string(n) + ", " + facing_name(mode) + ", offset " +
           std::to_string(offset);
}

template <class T> GuardedBuffer guarded_copy(const std::vector<T> &v, size_t offset, uint8_t pat) {
    GuardedBuffer b(v.size() * sizeof(T), offset, pat);
    if (!v.empty()) std::memcpy(b.data(), v.data(), v.size() * sizeof(T));
    return b;
}

template <class T> bool unchanged(const GuardedBuffer &b, const std::vector<T> &v) {
    return v.empty() || std::memcmp(b.data(), v.data(), v.size() * sizeof(T)) == 0;
}

// The checks every call ends with: each buffer's guards, each const input
// untouched. NAMES and BUFS pair up.
void check_guards(Row &row, const std::string &at, std::initializer_list<const char *> names,
                  std::initializer_list<const GuardedBuffer *> bufs) {
    auto n = names.begin();
    for (const GuardedBuffer *b : bufs) {
        const std::string d = b->guard_damage();
        if (!d.empty()) record_failure(row, at, std::string("wrote ") + *n + " " + d);
        ++n;
    }
}

float special_float(Rng &rng) {
    switch (rng.below(4)) {
    case 0: return 0.0f;
    case 1: return -0.0f;
    case 2: return std::numeric_limits<float>::quiet_NaN();
    default: return std::numeric_limits<float>::infinity();
    }
}

} // namespace

// ---- A: CalculateFacing, and A fused with C ---------------------------------

namespace {

Vec4 random_light(Rng &rng) {
    return {rng.uniform(-10, 10), rng.uniform(-10, 10), rng.uniform(-10, 10),
            rng.chance(0.5) ? 1.0f : 0.0f}; // a point or a direction
}

// N triangle planes facing LIGHT as MODE says.
std::vector<Plane> facing_planes(Rng &rng, int n, Facing mode, const Vec4 &light) {
    std::vector<Plane> planes((size_t)std::max(n, 0));
    for (Plane &p : planes) {
        p = {rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-10, 10)};
        // Light on the plane (sum 0 or -0), NaN and inf sums: the strict
        // test gives 0 for each, in every variant.
        if (rng.chance(0.04)) {
            const float s = special_float(rng);
            p = {s, rng.chance(0.5) ? s : 0.0f, 0.0f, rng.chance(0.5) ? s : -0.0f};
        }
        // none / all: turn the plane round when it faces the wrong way.
        // Negating all four coefficients negates every product and sum
        // exactly, so the decision flips exactly.
        if (mode == Facing::none || mode == Facing::all) {
            uint8_t f[2];
            sv_calculate_facing_c_ref(&p, 1, &light, f);
            if ((f[0] == 1) == (mode == Facing::none)) p = {-p.a, -p.b, -p.c, -p.d};
        }
    }
    return planes;
}

// A, or (FUSED) A with the count: the facing bytes against c_ref's, and
// the count against CountFacing's of c_ref on them.
void run_facing(std::vector<Row> &rows, Rng &rng, bool fused) {
    for_each_case(true, kFacingModes, [&](int n, Facing mode, size_t caseno) {
        const Vec4 light = random_light(rng);
        const std::vector<Plane> planes = facing_planes(rng, n, mode, light);
        const uint8_t pat = guard_pattern(rng);
        const size_t out_bytes = n >= 0 ? (size_t)n + 1 : 0;
        std::vector<uint8_t> want(out_bytes, pat);
        sv_calculate_facing_c_ref(planes.data(), n, &light, want.data());
        const int want_count = sv_count_facing_c_ref(want.data(), n);
        const size_t po = pick(kIntOffsets, caseno), fo = pick(kByteOffsets, caseno);
        const std::string at = where("n", n, mode, fo);
        for (Row &row : rows) {
            const Kernels &k = row.variant->for_triangles(n);
            GuardedBuffer pbuf = guarded_copy(planes, po, pat);
            GuardedBuffer out(out_bytes, fo, pat);
            const Vec4 l = light;
            uint32_t failed = 0;
            if (fused) {
                const int got = abi_call(row.abi, &failed, k.calculate_facing_count,
                                         pbuf.as<const Plane>(), n, &l, out.data());
                count_case(row);
                if (got != want_count) {
                    record_failure(row, at,
                                   "returned " + std::to_string(got) + ", c_ref's count " +
                                       std::to_string(want_count));
                }
            } else {
                abi_call(row.abi, &failed, k.calculate_facing, pbuf.as<const Plane>(), n, &l,
                         out.data());
                count_case(row);
            }
            record_abi(row, failed, at);
            const std::string d = first_difference(out.data(), want.data(), out_bytes, "facing");
            if (!d.empty()) record_failure(row, at, d);
            if (!unchanged(pbuf, planes)) record_failure(row, at, "modified its const planes");
            check_guards(row, at, {"below or past the facing bytes", "around the planes"},
                         {&out, &pbuf});
        }
    });
}

} // namespace

void run_calculate_facing(std::vector<Row> &rows, Rng &rng) { run_facing(rows, rng, false); }

void run_calculate_facing_count(std::vector<Row> &rows, Rng &rng) { run_facing(rows, rng, true); }

// ---- B: CalculateCullBits --------------------------------------------------

namespace {

enum class Box { inside, every_plane, outside, mixed };
constexpr Box kBoxModes[] = {Box::inside, Box::every_plane, Box::outside, Box::mixed};
const char *box_name(Box b) {
    switch (b) {
    case Box::inside: return "box inside all planes";
    case Box::every_plane: return "every plane through the box";
    case Box::outside: return "box behind every plane";
    default: return "planes mixed";
    }
}

// A surface's box, NUMVERTS vertices inside it (w garbage: only x, y, z
// are read), and six light planes placed against the box as BOX says.
struct LightVolume {
    Bounds bounds;
    std::vector<Vec4> positions;
    std::vector<Plane> planes; // SV_NUM_LIGHT_PLANES
};

LightVolume light_volume(Rng &rng, int numVerts, Box box) {
    LightVolume lv;
    Bounds &b = lv.bounds;
    b.center = {rng.uniform(-5, 5), rng.uniform(-5, 5), rng.uniform(-5, 5), rng.uniform(-9, 9)};
    b.extents = {rng.uniform(0, 2), rng.uniform(0, 2), rng.uniform(0, 2), rng.uniform(-9, 9)};
    lv.positions.resize((size_t)std::max(numVerts, 0));
    for (Vec4 &v : lv.positions) {
        v = {b.center.x + b.extents.x * rng.uniform(-1, 1),
             b.center.y + b.extents.y * rng.uniform(-1, 1),
             b.center.z + b.extents.z * rng.uniform(-1, 1), rng.uniform(-9, 9)};
    }
    lv.planes.resize(SV_NUM_LIGHT_PLANES);
    for (Plane &p : lv.planes) {
        p = {rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1), 0.0f};
        const float dot = p.a * b.center.x + p.b * b.center.y + p.c * b.center.z;
        const float radius = std::fabs(p.a * b.extents.x) + std::fabs(p.b * b.extents.y) +
                             std::fabs(p.c * b.extents.z);
        const Box kind = box == Box::mixed ? (Box)rng.below(3) : box;
        if (kind == Box::inside) {
            p.d = -dot + radius + 1.0f + rng.uniform(0, 1); // margin: >= 0 in float too
        } else if (kind == Box::outside) {
            p.d = -dot - radius - 1.0f - rng.uniform(0, 1);
        } else {
            p.d = -dot + radius * rng.uniform(-0.9f, 0.9f); // cuts the box
        }
    }
    return lv;
}

} // namespace

void run_calculate_cull_bits(std::vector<Row> &rows, Rng &rng) {
    for_each_case(true, kBoxModes, [&](int n, Box box, size_t caseno) {
        const LightVolume lv = light_volume(rng, n, box);
        const Bounds &b = lv.bounds;
        const std::vector<Vec4> &pos = lv.positions;
        const Plane *planes = lv.planes.data();
        const uint8_t pat = guard_pattern(rng);
        const size_t nb = (size_t)std::max(n, 0);
        std::vector<uint8_t> want(nb, pat);
        const int want_ret = sv_calculate_cull_bits_c_ref(pos.data(), n, &b, planes, want.data());
        const std::vector<Plane> &plane_v = lv.planes;
        const size_t vo = pick(kIntOffsets, caseno), co = pick(kByteOffsets, caseno);
        const std::string at = std::string("n=") + std::to_string(n) + ", " + box_name(box) +
                               ", offset " + std::to_string(co);
        for (Row &row : rows) {
            const Kernels &k = row.variant->for_triangles(n);
            GuardedBuffer pbuf = guarded_copy(pos, vo, pat);
            GuardedBuffer lbuf = guarded_copy(plane_v, vo, pat);
            GuardedBuffer out(nb, co, pat);
            const Bounds bb = b;
            uint32_t failed = 0;
            const int got = abi_call(row.abi, &failed, k.calculate_cull_bits, pbuf.as<const Vec4>(),
                                     n, &bb, lbuf.as<const Plane>(), out.data());
            count_case(row);
            record_abi(row, failed, at);
            if (got != want_ret) {
                record_failure(row, at,
                               "returned " + std::to_string(got) + ", c_ref " +
                                   std::to_string(want_ret));
            }
            // Returning 1 leaves cullBits unwritten: the pattern stays.
            const std::string d = first_difference(out.data(), want.data(), nb, "cullBits");
            if (!d.empty()) record_failure(row, at, d);
            if (!unchanged(pbuf, pos) || !unchanged(lbuf, plane_v)) {
                record_failure(row, at, "modified its const input");
            }
            check_guards(row, at, {"around cullBits", "around the positions", "around the planes"},
                         {&out, &pbuf, &lbuf});
        }
    });
}

// ---- C: CountFacing --------------------------------------------------------

void run_count_facing(std::vector<Row> &rows, Rng &rng) {
    for_each_case(true, kFacingModes, [&](int n, Facing mode, size_t caseno) {
        const std::vector<uint8_t> facing = facing_bytes(rng, n, mode);
        const uint8_t pat = guard_pattern(rng);
        const int want = sv_count_facing_c_ref(facing.data(), n);
        for (Row &row : rows) {
            const Kernels &k = row.variant->for_triangles(n);
            const size_t fo = pick(allowed_offsets(k.kernels.align_facing, 1), caseno);
            const std::string at = where("n", n, mode, fo);
            GuardedBuffer fbuf = guarded_copy(facing, fo, pat);
            uint32_t failed = 0;
            const int got = abi_call(row.abi, &failed, k.kernels.count_facing,
                                     (const uint8_t *)fbuf.data(), n);
            count_case(row);
            record_abi(row, failed, at);
            if (got != want) {
                record_failure(row, at,
                               "returned " + std::to_string(got) + ", c_ref " +
                                   std::to_string(want));
            }
            if (!unchanged(fbuf, facing)) record_failure(row, at, "modified its const facing");
            check_guards(row, at, {"around facing"}, {&fbuf});
        }
    });
}

// ---- D: CountFacingCull ----------------------------------------------------

namespace {

// Cull bytes for NUMVERTS vertices: for every light plane (bits 0..5, and
// bit 6 and 7 too: bit 7 is kept only for variants whose contract has it),
// a share of the triangles with that bit on all three vertices, so each
// plane culls something; plus random bits on the rest.
std::vector<uint8_t> cull_bytes(Rng &rng, int numVerts, const std::vector<int> &indices) {
    std::vector<uint8_t> c((size_t)numVerts);
    const double p = rng.unit() * 0.5;
    for (auto &b : c) {
        for (int bit = 0; bit < 8; bit++)
            if (rng.chance(p)) b = (uint8_t)(b | (1u << bit));
    }
    for (size_t t = 0; t + 2 < indices.size(); t += 3) {
        if (!rng.chance(0.3)) continue;
        const uint8_t bit = (uint8_t)(1u << rng.below(8));
        for (size_t j = 0; j < 3; j++) c[(size_t)indices[t + j]] |= bit;
    }
    return c;
}

std::vector<uint8_t> without_bit7(std::vector<uint8_t> c) {
    for (auto &b : c) b &= 0x7F;
    return c;
}

} // namespace

void run_count_facing_cull(std::vector<Row> &rows, Rng &rng) {
    for_each_case(true, kFacingModes, [&](int n, Facing mode, size_t caseno) {
        const std::vector<uint8_t> facing = facing_bytes(rng, n, mode);
        const int tris = std::max(n, 0);
        const int numVerts = 1 + (int)rng.below((uint32_t)(3 * tris + 1));
        std::vector<int> indices((size_t)3 * tris);
        for (int &i : indices) i = (int)rng.below((uint32_t)numVerts);
        // Two inputs: all eight bits, and bits 0..6 for the contracts
        // without bit 7; each with its own c_ref answer.
        const std::vector<uint8_t> cull8 = cull_bytes(rng, numVerts, indices);
        const std::vector<uint8_t> cull7 = without_bit7(cull8);
        std::vector<uint8_t> want_f8 = facing, want_f7 = facing;
        const int want8 = sv_count_facing_cull_c_ref(want_f8.data(), n, indices.data(),
                                                     cull8.data());
        const int want7 = sv_count_facing_cull_c_ref(want_f7.data(), n, indices.data(),
                                                     cull7.data());
        const uint8_t pat = guard_pattern(rng);
        const size_t fo = pick(kByteOffsets, caseno), io = pick(kIntOffsets, caseno);
        for (Row &row : rows) {
            const Kernels &k = row.variant->for_triangles(n);
            const std::vector<uint8_t> &cull = k.cull_bit7 ? cull8 : cull7;
            const std::vector<uint8_t> &want_f = k.cull_bit7 ? want_f8 : want_f7;
            const int want = k.cull_bit7 ? want8 : want7;
            const std::string at = where("n", n, mode, fo) +
                                   (k.cull_bit7 ? ", cull bits 0-7" : ", cull bits 0-6");
            GuardedBuffer fbuf = guarded_copy(facing, fo, pat);
            GuardedBuffer ibuf = guarded_copy(indices, io, pat);
            GuardedBuffer cbuf = guarded_copy(cull, fo, pat);
            uint32_t failed = 0;
            const int got = abi_call(row.abi, &failed, k.kernels.count_facing_cull, fbuf.data(), n,
                                     ibuf.as<const int>(), (const uint8_t *)cbuf.data());
            count_case(row);
            record_abi(row, failed, at);
            if (got != want) {
                record_failure(row, at,
                               "returned " + std::to_string(got) + ", c_ref " +
                                   std::to_string(want));
            }
            const std::string d = first_difference(fbuf.data(), want_f.data(), want_f.size(),
                                                   "facing");
            if (!d.empty()) record_failure(row, at, d);
            if (!unchanged(ibuf, indices) || !unchanged(cbuf, cull)) {
                record_failure(row, at, "modified its const indices or cull bits");
            }
            check_guards(row, at, {"around facing", "around the indices", "around cullBits"},
                         {&fbuf, &ibuf, &cbuf});
        }
    });
}

// ---- E: CreateSilTriangles -------------------------------------------------

namespace {

// Even vertex numbers, up to the largest the contract allows (2^31 - 2).
int doubled_vertex(Rng &rng) {
    return rng.chance(0.02) ? std::numeric_limits<int>::max() - 1 : 2 * (int)rng.below(1u << 30);
}

std::vector<SilEdge> sil_edges(Rng &rng, int n, int numTriangles) {
    std::vector<SilEdge> e((size_t)std::max(n, 0));
    for (SilEdge &s : e) {
        s.p1 = (int)rng.below((uint32_t)numTriangles + 1);
        // some dangling edges (p2 = numTriangles, the sentinel's byte)
        s.p2 = rng.chance(0.1) ? numTriangles : (int)rng.below((uint32_t)numTriangles + 1);
        s.v1 = doubled_vertex(rng);
        s.v2 = doubled_vertex(rng);
    }
    return e;
}

// The part of an index output that counts (the first COUNT ints), then
// the rest up to the bound is the variant's to scribble on (branch-free
// variants write 6 ints past the count); the guards past the bound are not.
void compare_indices(Row &row, const std::string &at, int got, int want, const GuardedBuffer &out,
                     const std::vector<int> &want_out) {
    if (got != want) {
        record_failure(row, at,
                       "returned " + std::to_string(got) + ", c_ref " + std::to_string(want));
        return;
    }
    const std::string d = first_difference(reinterpret_cast<const int *>(out.data()),
                                           want_out.data(), (size_t)std::max(want, 0),
                                           "shadowIndices");
    if (!d.empty()) record_failure(row, at, d);
}

} // namespace

void run_create_sil_triangles(std::vector<Row> &rows, Rng &rng) {
    for_each_case(true, kFacingModes, [&](int n, Facing mode, size_t caseno) {
        const int numTriangles = (int)rng.below(2u * (uint32_t)std::max(n, 0) + 2);
        std::vector<uint8_t> facing = facing_bytes(rng, numTriangles + 1, mode);
        facing[(size_t)numTriangles] = 1; // the dangling edges' byte
        const std::vector<SilEdge> edges = sil_edges(rng, n, numTriangles);
        const size_t out_ints = (size_t)6 * (size_t)std::max(n, 0);
        std::vector<int> want_out(out_ints + 6);
        const int want = sv_create_sil_triangles_c_ref(want_out.data(), facing.data(), edges.data(),
                                                       n);
        const uint8_t pat = guard_pattern(rng);
        const size_t fo = pick(kByteOffsets, caseno), eo = pick(kIntOffsets, caseno);
        for (Row &row : rows) {
            const Kernels &k = row.variant->for_triangles(numTriangles);
            const size_t oo = pick(allowed_offsets(k.kernels.align_shadow_indices, 4), caseno);
            const std::string at = where("edges", n, mode, oo) + ", " +
                                   std::to_string(numTriangles) + " triangles";
            GuardedBuffer out(out_ints * sizeof(int), oo, pat);
            GuardedBuffer fbuf = guarded_copy(facing, fo, pat);
            GuardedBuffer ebuf = guarded_copy(edges, eo, pat);
            uint32_t failed = 0;
            const int got = abi_call(row.abi, &failed, k.kernels.create_sil_triangles,
                                     out.as<int>(), (const uint8_t *)fbuf.data(),
                                     ebuf.as<const SilEdge>(), n);
            count_case(row);
            record_abi(row, failed, at);
            compare_indices(row, at, got, want, out, want_out);
            if (!unchanged(fbuf, facing) || !unchanged(ebuf, edges)) {
                record_failure(row, at, "modified its const facing or edges");
            }
            check_guards(row, at,
                         {"outside 6 * numSilEdges ints", "around facing", "around the edges"},
                         {&out, &fbuf, &ebuf});
        }
    });
}

// ---- F: CreateCapTriangles -------------------------------------------------

namespace {

// Vertex numbers up to the largest the contract allows (2^30 - 1).
int vertex_index(Rng &rng, uint32_t numVerts) {
    return rng.chance(0.02) ? (int)numVerts - 1 : (int)rng.below(numVerts);
}

} // namespace

void run_create_cap_triangles(std::vector<Row> &rows, Rng &rng) {
    for_each_case(false, kFacingModes, [&](int n, Facing mode, size_t caseno) {
        const std::vector<uint8_t> facing = facing_bytes(rng, n, mode);
        const uint32_t numVerts = rng.chance(0.5) ? 1u << 30 : 1 + rng.below(3u * (uint32_t)n + 1);
        std::vector<int> indices((size_t)3 * n);
        for (int &i : indices) i = vertex_index(rng, numVerts);
        const size_t out_ints = (size_t)6 * n;
        std::vector<int> want_out(out_ints + 6);
        const int want = sv_create_cap_triangles_c_ref(want_out.data(), facing.data(),
                                                       indices.data(), 3 * n);
        const uint8_t pat = guard_pattern(rng);
        const size_t fo = pick(kByteOffsets, caseno);
        for (Row &row : rows) {
            const Kernels &k = row.variant->for_triangles(n);
            const size_t io = pick(allowed_offsets(k.kernels.align_indices, 4), caseno);
            const size_t oo = pick(allowed_offsets(k.kernels.align_shadow_indices, 4), caseno / 3);
            const std::string at = where("triangles", n, mode, oo) + ", indices offset " +
                                   std::to_string(io);
            GuardedBuffer out(out_ints * sizeof(int), oo, pat);
            GuardedBuffer fbuf = guarded_copy(facing, fo, pat);
            GuardedBuffer ibuf = guarded_copy(indices, io, pat);
            uint32_t failed = 0;
            const int got = abi_call(row.abi, &failed, k.kernels.create_cap_triangles,
                                     out.as<int>(), (const uint8_t *)fbuf.data(),
                                     ibuf.as<const int>(), 3 * n);
            count_case(row);
            record_abi(row, failed, at);
            compare_indices(row, at, got, want, out, want_out);
            if (!unchanged(fbuf, facing) || !unchanged(ibuf, indices)) {
                record_failure(row, at, "modified its const facing or indices");
            }
            check_guards(row, at,
                         {"outside 6 * numTriangles ints", "around facing", "around the indices"},
                         {&out, &fbuf, &ibuf});
        }
    });
}

// ---- The whole volume (sv_create_shadow_volume) ----------------------------

namespace {

// A mesh's connectivity at random: NUMTRIANGLES triangles over at most
// 3 * NUMTRIANGLES vertices, about 1.5 edges per triangle (a closed mesh's
// count) between its triangles, their doubled vertex numbers in the mesh.
struct Mesh {
    int numIndices, numEdges, numVerts;
    std::vector<int> indices;
    std::vector<SilEdge> edges;
};

// The paper's C by name, not the table's c_ref: the oracle stays whatever
// a table holds.
const sv_variant kRef = {"c_ref",
                         SV_ISA_NONE,
                         sv_count_facing_c_ref,
                         sv_count_facing_cull_c_ref,
                         sv_create_sil_triangles_c_ref,
                         sv_create_cap_triangles_c_ref,
                         1,
                         1,
                         1};

Mesh random_mesh(Rng &rng, int numTriangles) {
    Mesh m;
    m.numIndices = 3 * numTriangles;
    m.numEdges = numTriangles * 3 / 2 + (int)rng.below(4);
    m.numVerts = 1 + (int)rng.below((uint32_t)m.numIndices + 1);
    m.indices.resize((size_t)m.numIndices);
    for (int &i : m.indices) i = (int)rng.below((uint32_t)m.numVerts);
    m.edges = sil_edges(rng, m.numEdges, numTriangles);
    for (SilEdge &e : m.edges) {
        e.v1 = 2 * (int)rng.below((uint32_t)m.numVerts);
        e.v2 = 2 * (int)rng.below((uint32_t)m.numVerts);
    }
    return m;
}

} // namespace

void run_shadow_volume(std::vector<Row> &rows, Rng &rng, bool cull) {
    for_each_case(false, kFacingModes, [&](int numTriangles, Facing mode, size_t caseno) {
        const Mesh mesh = random_mesh(rng, numTriangles);
        const int numIndices = mesh.numIndices, numEdges = mesh.numEdges, numVerts = mesh.numVerts;
        const std::vector<int> &indices = mesh.indices;
        const std::vector<SilEdge> &edges = mesh.edges;
        std::vector<uint8_t> facing = facing_bytes(rng, numTriangles + 1, mode);
        facing[(size_t)numTriangles] = 1;
        const std::vector<uint8_t> cull8 = cull_bytes(rng, numVerts, indices);
        const std::vector<uint8_t> cull7 = without_bit7(cull8);
        const size_t cap = sv_shadow_volume_capacity(numIndices, numEdges);
        std::vector<int> want_out[2] = {std::vector<int>(cap + 6), std::vector<int>(cap + 6)};
        std::vector<uint8_t> want_f[2] = {facing, facing};
        int want[2];
        for (int b7 = 0; b7 < 2; b7++) {
            want[b7] = sv_create_shadow_volume(&kRef, want_out[b7].data(), indices.data(),
                                               numIndices, edges.data(), numEdges,
                                               want_f[b7].data(),
                                               cull ? (b7 ? cull8 : cull7).data() : nullptr);
        }
        const uint8_t pat = guard_pattern(rng);
        for (Row &row : rows) {
            const Kernels &k = row.variant->for_triangles(numTriangles);
            const int b7 = k.cull_bit7 ? 1 : 0;
            const std::vector<uint8_t> &cb = b7 ? cull8 : cull7;
            const size_t oo = pick(allowed_offsets(k.kernels.align_shadow_indices, 4), caseno);
            const size_t io = pick(allowed_offsets(k.kernels.align_indices, 4), caseno);
            const size_t fo = pick(allowed_offsets(k.kernels.align_facing, 1), caseno);
            const std::string at = where("triangles", numTriangles, mode, oo) + ", " +
                                   std::to_string(numEdges) + " edges" +
                                   (cull ? (b7 ? ", cull bits 0-7" : ", cull bits 0-6") : "");
            GuardedBuffer out(cap * sizeof(int), oo, pat);
            GuardedBuffer ibuf = guarded_copy(indices, io, pat);
            GuardedBuffer fbuf = guarded_copy(facing, fo, pat);
            GuardedBuffer ebuf = guarded_copy(edges, 0, pat);
            GuardedBuffer cbuf = guarded_copy(cb, 0, pat);
            const sv_variant *kv = &k.kernels;
            uint32_t failed = 0;
            const int got = abi_call(row.abi, &failed, sv_create_shadow_volume, kv, out.as<int>(),
                                     ibuf.as<const int>(), numIndices, ebuf.as<const SilEdge>(),
                                     numEdges, fbuf.data(),
                                     cull ? (const uint8_t *)cbuf.data()
                                          : (const uint8_t *)nullptr);
            count_case(row);
            record_abi(row, failed, at);
            compare_indices(row, at, got, want[b7], out, want_out[b7]);
            const std::string d = first_difference(fbuf.data(), want_f[b7].data(), facing.size(),
                                                   "facing");
            if (!d.empty()) record_failure(row, at, d);
            if (!unchanged(ibuf, indices) || !unchanged(ebuf, edges) || !unchanged(cbuf, cb)) {
                record_failure(row, at, "modified its const input");
            }
            check_guards(row, at,
                         {"past sv_shadow_volume_capacity", "around the indices", "around facing",
                          "around the edges", "around cullBits"},
                         {&out, &ibuf, &fbuf, &ebuf, &cbuf});
        }
    });
}

// ---- One call per light (sv_shadow_volume_for_light) -----------------------

namespace {

// The light volume's cases: none (lightPlanes NULL), then the box modes.
constexpr int kLightVolumeModes[] = {-1, (int)Box::inside, (int)Box::every_plane, (int)Box::outside,
                                     (int)Box::mixed};

} // namespace

void run_shadow_volume_for_light(std::vector<Row> &rows, Rng &rng) {
    for_each_case(false, kLightVolumeModes, [&](int numTriangles, int mode, size_t caseno) {
        const Mesh mesh = random_mesh(rng, numTriangles);
        const int numIndices = mesh.numIndices, numEdges = mesh.numEdges, numVerts = mesh.numVerts;
        const std::vector<int> &indices = mesh.indices;
        const std::vector<SilEdge> &edges = mesh.edges;
        const Vec4 light = random_light(rng);
        const std::vector<Plane> planes = facing_planes(rng, numTriangles, Facing::random, light);
        const LightVolume lv = light_volume(rng, numVerts, mode < 0 ? Box::mixed : (Box)mode);
        const Plane *light_planes = mode < 0 ? nullptr : lv.planes.data();
        // The contract's reference: c_ref's A, its B and the decision, then
        // the volume of the reference kernels.
        const size_t cap = sv_shadow_volume_capacity(numIndices, numEdges);
        std::vector<uint8_t> want_f((size_t)numTriangles + 1), cull((size_t)numVerts);
        sv_calculate_facing_c_ref(planes.data(), numTriangles, &light, want_f.data());
        const bool culled = light_planes &&
                            !sv_calculate_cull_bits_c_ref(lv.positions.data(), numVerts, &lv.bounds,
                                                          light_planes, cull.data());
        std::vector<int> want_out(cap + 6);
        const int want = sv_create_shadow_volume(&kRef, want_out.data(), indices.data(), numIndices,
                                                 edges.data(), numEdges, want_f.data(),
                                                 culled ? cull.data() : nullptr);
        const uint8_t pat = guard_pattern(rng);
        // Every offset, aligned or not: the entry point stands in for a
        // kernel whose alignment need a buffer does not meet.
        const size_t oo = pick(kIntOffsets, caseno), io = pick(kIntOffsets, caseno / 4);
        const size_t fo = pick(kByteOffsets, caseno);
        static const char *const kModeNames[] = {"no light planes", "box inside all planes",
                                                 "every plane through the box",
                                                 "box behind every plane", "planes mixed"};
        const std::string at = "triangles=" + std::to_string(numTriangles) + ", " +
                               kModeNames[mode + 1] + ", output offset " + std::to_string(oo) +
                               ", indices offset " + std::to_string(io) + ", facing offset " +
                               std::to_string(fo);
        for (Row &row : rows) {
            const Kernels &k = row.variant->for_triangles(numTriangles);
            GuardedBuffer out(cap * sizeof(int), oo, pat);
            GuardedBuffer fbuf((size_t)numTriangles + 1, fo, pat);
            GuardedBuffer cbuf((size_t)numVerts, fo, pat);
            GuardedBuffer pbuf = guarded_copy(planes, 0, pat);
            GuardedBuffer ibuf = guarded_copy(indices, io, pat);
            GuardedBuffer ebuf = guarded_copy(edges, 0, pat);
            GuardedBuffer vbuf = guarded_copy(lv.positions, 0, pat);
            GuardedBuffer lbuf = guarded_copy(lv.planes, 0, pat);
            sv_surface surface;
            surface.planes = pbuf.as<const Plane>();
            surface.indices = ibuf.as<const int>();
            surface.numIndices = numIndices;
            surface.silEdges = ebuf.as<const SilEdge>();
            surface.numSilEdges = numEdges;
            surface.positions = vbuf.as<const Vec4>();
            surface.numVerts = numVerts;
            surface.bounds = lv.bounds;
            const Vec4 l = light;
            uint32_t failed = 0;
            const int got = abi_call(row.abi, &failed, sv_shadow_volume_for_light, k.plan,
                                     (const sv_surface *)&surface, (const Vec4 *)&l,
                                     light_planes ? lbuf.as<const Plane>() : (const Plane *)nullptr,
                                     out.as<int>(), cap, fbuf.data(), cbuf.data());
            count_case(row);
            record_abi(row, failed, at);
            compare_indices(row, at, got, want, out, want_out);
            const std::string d = first_difference(fbuf.data(), want_f.data(), want_f.size(),
                                                   "facing");
            if (!d.empty()) record_failure(row, at, d);
            if (!unchanged(pbuf, planes) || !unchanged(ibuf, indices) || !unchanged(ebuf, edges) ||
                !unchanged(vbuf, lv.positions) || !unchanged(lbuf, lv.planes)) {
                record_failure(row, at, "modified its const input");
            }
            check_guards(row, at,
                         {"past sv_shadow_volume_capacity", "around facing", "around cullBits",
                          "around the planes", "around the indices", "around the edges",
                          "around the positions", "around the light planes"},
                         {&out, &fbuf, &cbuf, &pbuf, &ibuf, &ebuf, &vbuf, &lbuf});
        }
    });
}

// ---- The general rule (issue 27): its silhouette and caps ------------------

namespace {

// General bytes: 0 (casts), 1 (nothing), 2 (its reverse casts), in
// proportions by MODE (none: all 0; all: all 2; half: 0 and 2; random).
std::vector<uint8_t> general_bytes(Rng &rng, int n, Facing mode) {
    std::vector<uint8_t> b((size_t)std::max(n, 0));
    for (uint8_t &x : b) {
        switch (mode) {
        case Facing::none: x = 0; break;
        case Facing::all: x = 2; break;
        case Facing::half: x = rng.chance(0.5) ? 2 : 0; break;
        default: x = (uint8_t)rng.below(3); break;
        }
    }
    return b;
}

// A table of N edges of each class over NUMTRIANGLES triangles, the first
// PAPER of them the paper's class (their bytes 0 or 1); shared edges of 2
// to 5 triangles running either way.
struct GeneralCase {
    std::vector<SilEdge> paper, pairs, opens;
    std::vector<sv_shared_edge> shared;
    std::vector<int> uses;
    sv_general_edges view() const {
        sv_general_edges e{};
        e.paper = paper.data(), e.numPaper = (int)paper.size();
        e.pairs = pairs.data(), e.numPairs = (int)pairs.size();
        e.opens = opens.data(), e.numOpens = (int)opens.size();
        e.shared = shared.data(), e.numShared = (int)shared.size();
        e.sharedUses = uses.data(), e.numSharedUses = (int)uses.size();
        return e;
    }
};

GeneralCase general_case(Rng &rng, int n, int numTriangles, int paperTriangles) {
    GeneralCase c;
    auto general = [&] {
        return paperTriangles + (int)rng.below((uint32_t)(numTriangles - paperTriangles));
    };
    for (int i = 0; i < n; i++) {
        const int p1 = (int)rng.below((uint32_t)paperTriangles);
        const int p2 = rng.chance(0.1) ? numTriangles : (int)rng.below((uint32_t)paperTriangles);
        c.paper.push_back({p1, p2, doubled_vertex(rng), doubled_vertex(rng)});
        c.pairs.push_back({general(), general(), doubled_vertex(rng), doubled_vertex(rng)});
        const int p = general();
        c.opens.push_back({p, p, doubled_vertex(rng), doubled_vertex(rng)});
        const int k = 2 + (int)rng.below(4);
        c.shared.push_back({doubled_vertex(rng), doubled_vertex(rng), (int)c.uses.size(), k});
        for (int j = 0; j < k; j++) c.uses.push_back(2 * general() + (int)rng.below(2));
    }
    return c;
}

} // namespace

void run_create_general_sil_triangles(std::vector<Row> &rows, Rng &rng) {
    for_each_case(false, kFacingModes, [&](int n, Facing mode, size_t caseno) {
        const int paperTriangles = 1 + (int)rng.below((uint32_t)n + 1);
        const int numTriangles = paperTriangles + 1 + (int)rng.below(2u * (uint32_t)n + 1);
        std::vector<uint8_t> facing = general_bytes(rng, numTriangles + 1, mode);
        for (int t = 0; t < paperTriangles; t++) facing[(size_t)t] &= 1; /* 0 or 1 */
        facing[(size_t)numTriangles] = 1; /* the paper's dangling edges' byte */
        const GeneralCase g = general_case(rng, n, numTriangles, paperTriangles);
        const sv_general_edges e = g.view();
        const size_t out_ints = sv_general_sil_capacity(&e);
        std::vector<int> want_out(out_ints + 6);
        const int want = sv_create_general_sil_triangles_c_ref(want_out.data(), facing.data(), &e);
        const uint8_t pat = guard_pattern(rng);
        const size_t fo = pick(kByteOffsets, caseno), oo = pick(kIntOffsets, caseno);
        for (Row &row : rows) {
            const Kernels &k = row.variant->for_triangles(numTriangles);
            const std::string at = where("edges of each class", n, mode, oo) + ", " +
                                   std::to_string(numTriangles) + " triangles";
            GuardedBuffer out(out_ints * sizeof(int), oo, pat);
            GuardedBuffer fbuf = guarded_copy(facing, fo, pat);
            uint32_t failed = 0;
            const int got = abi_call(row.abi, &failed, k.general->create_general_sil_triangles,
                                     out.as<int>(), (const uint8_t *)fbuf.data(), &e);
            count_case(row);
            record_abi(row, failed, at);
            compare_indices(row, at, got, want, out, want_out);
            if (!unchanged(fbuf, facing)) record_failure(row, at, "modified its const facing");
            check_guards(row, at, {"outside sv_general_sil_capacity ints", "around facing"},
                         {&out, &fbuf});
        }
    });
}

void run_create_general_cap_triangles(std::vector<Row> &rows, Rng &rng) {
    for_each_case(false, kFacingModes, [&](int n, Facing mode, size_t caseno) {
        std::vector<uint8_t> facing = general_bytes(rng, n, mode);
        if (mode == Facing::random)
            for (uint8_t &b : facing) b = rng.chance(0.3) ? 1 : b;
        const uint32_t numVerts = rng.chance(0.5) ? 1u << 30 : 1 + rng.below(3u * (uint32_t)n + 1);
        std::vector<int> indices((size_t)3 * n);
        for (int &i : indices) i = vertex_index(rng, numVerts);
        const size_t out_ints = (size_t)6 * n;
        std::vector<int> want_out(out_ints + 6);
        const int want = sv_create_general_cap_triangles_c_ref(want_out.data(), facing.data(),
                                                               indices.data(), 3 * n);
        const uint8_t pat = guard_pattern(rng);
        const size_t fo = pick(kByteOffsets, caseno), io = pick(kIntOffsets, caseno),
                     oo = pick(kIntOffsets, caseno / 3);
        for (Row &row : rows) {
            const Kernels &k = row.variant->for_triangles(n);
            const std::string at = where("triangles", n, mode, oo) + ", indices offset " +
                                   std::to_string(io);
            GuardedBuffer out(out_ints * sizeof(int), oo, pat);
            GuardedBuffer fbuf = guarded_copy(facing, fo, pat);
            GuardedBuffer ibuf = guarded_copy(indices, io, pat);
            uint32_t failed = 0;
            const int got = abi_call(row.abi, &failed, k.general->create_general_cap_triangles,
                                     out.as<int>(), (const uint8_t *)fbuf.data(),
                                     ibuf.as<const int>(), 3 * n);
            count_case(row);
            record_abi(row, failed, at);
            compare_indices(row, at, got, want, out, want_out);
            if (!unchanged(fbuf, facing) || !unchanged(ibuf, indices))
                record_failure(row, at, "modified its const facing or indices");
            check_guards(row, at,
                         {"outside 6 * numTriangles ints", "around facing", "around the indices"},
                         {&out, &fbuf, &ibuf});
        }
    });
}

} // namespace svcheck

// ---- Deforming surfaces: planes, facing from positions, skinning, one pass --

namespace svcheck {

namespace {

// What a case's positions and triangles are like: the planes' contract
// holds for every input (the zero plane for a NaN, an overflow or no area).
enum class Shape { ordinary, specials, extreme_scales, degenerate };
constexpr Shape kShapes[] = {Shape::ordinary, Shape::specials, Shape::extreme_scales,
                             Shape::degenerate};

const char *shape_name(Shape s) {
    switch (s) {
    case Shape::ordinary: return "ordinary";
    case Shape::specials: return "some 0, -0, NaN, infinity";
    case Shape::extreme_scales: return "huge and tiny coordinates";
    default: return "many zero-area triangles";
    }
}

// V positions of SHAPE.
std::vector<float> deform_positions(Rng &rng, int v, Shape shape) {
    std::vector<float> p(3 * (size_t)std::max(v, 0));
    for (float &x : p) {
        const double r = rng.unit();
        x = shape == Shape::specials && r < 0.05        ? special_float(rng)
            : shape == Shape::extreme_scales && r < 0.3 ? rng.uniform(-1, 1) * 1e30f
            : shape == Shape::extreme_scales && r < 0.6 ? rng.uniform(-1, 1) * 1e-30f
                                                        : rng.uniform(-50, 50);
    }
    return p;
}

// 3 * T vertex numbers below V (V > 0 when T > 0); some repeated corners,
// many for SHAPE degenerate.
std::vector<int> deform_indices(Rng &rng, int t, int v, Shape shape) {
    const double repeat = shape == Shape::degenerate ? 0.5 : 0.05;
    std::vector<int> ix;
    ix.reserve(3 * (size_t)std::max(t, 0));
    for (int i = 0; i < 3 * t; i++) {
        ix.push_back(i % 3 && rng.chance(repeat) ? ix.back() : (int)rng.below((uint32_t)v));
    }
    return ix;
}

// The first plane of OUT that differs from WANT's bits, recorded.
void compare_planes(Row &row, const std::string &at, const GuardedBuffer &out,
                    const std::vector<Plane> &want) {
    for (size_t t = 0; t < want.size(); t++) {
        // Bit for bit is the contract (-0.0 against 0.0, a NaN's payload).
        // NOLINTNEXTLINE(bugprone-suspicious-memory-comparison): Plane is four floats, no padding
        if (std::memcmp(out.data() + t * sizeof(Plane), &want[t], sizeof(Plane)) != 0) {
            record_failure(row, at, "plane " + std::to_string(t) + " differs from c_ref's");
            return;
        }
    }
}

} // namespace

void run_derive_planes(std::vector<Row> &rows, Rng &rng) {
    for_each_case(true, kShapes, [&](int n, Shape shape, size_t caseno) {
        const int v = std::max(n, 0) / 2 + 3;
        const std::vector<float> pos = deform_positions(rng, v, shape);
        const std::vector<int> ix = deform_indices(rng, std::max(n, 0), v, shape);
        const uint8_t pat = guard_pattern(rng);
        std::vector<Plane> want((size_t)std::max(n, 0));
        sv_derive_planes_c_ref(pos.data(), ix.data(), n, want.data());
        const size_t po = pick(kIntOffsets, caseno), oo = pick(kIntOffsets, caseno + 3);
        const std::string at = "n=" + std::to_string(n) + ", " + shape_name(shape) + ", offset " +
                               std::to_string(oo);
        for (Row &row : rows) {
            const Kernels &k = row.variant->for_triangles(n);
            GuardedBuffer pbuf = guarded_copy(pos, po, pat);
            GuardedBuffer ibuf = guarded_copy(ix, 0, pat);
            GuardedBuffer out(want.size() * sizeof(Plane), oo, pat);
            uint32_t failed = 0;
            abi_call(row.abi, &failed, k.planes->derive_planes, pbuf.as<const float>(),
                     ibuf.as<const int>(), n, out.as<Plane>());
            count_case(row);
            record_abi(row, failed, at);
            compare_planes(row, at, out, want);
            if (!unchanged(pbuf, pos) || !unchanged(ibuf, ix)) {
                record_failure(row, at, "modified its const positions or indices");
            }
            check_guards(row, at,
                         {"around the planes", "around the positions", "around the indices"},
                         {&out, &pbuf, &ibuf});
        }
    });
}

// The planes by clusters: the clusters of each case's index list built by
// sv::plane_clusters (its contract is the kernels' input), the planes
// against sv_derive_planes_c_ref's on the same list bit for bit.
void run_derive_planes_clustered(std::vector<Row> &rows, Rng &rng) {
    for_each_case(false, kShapes, [&](int n, Shape shape, size_t caseno) {
        const int v = n / 2 + 3;
        const std::vector<float> pos = deform_positions(rng, v, shape);
        const std::vector<int> ix = deform_indices(rng, n, v, shape);
        const sv::PlaneClusters clusters = sv::plane_clusters(ix.data(), n, v);
        const sv_plane_clusters view = clusters.view();
        const uint8_t pat = guard_pattern(rng);
        std::vector<Plane> want((size_t)n);
        sv_derive_planes_c_ref(pos.data(), ix.data(), n, want.data());
        const size_t po = pick(kIntOffsets, caseno), oo = pick(kIntOffsets, caseno + 3);
        const std::string at = "n=" + std::to_string(n) + ", " + shape_name(shape) + ", " +
                               std::to_string(clusters.num_clusters()) + " clusters, offset " +
                               std::to_string(oo);
        for (Row &row : rows) {
            const Kernels &k = row.variant->for_triangles(n);
            if (!k.clustered) continue; /* "planned" kept the planes variant for this class */
            GuardedBuffer pbuf = guarded_copy(pos, po, pat);
            GuardedBuffer out(want.size() * sizeof(Plane), oo, pat);
            uint32_t failed = 0;
            abi_call(row.abi, &failed, k.clustered->derive_planes, pbuf.as<const float>(), &view,
                     out.as<Plane>());
            count_case(row);
            record_abi(row, failed, at);
            compare_planes(row, at, out, want);
            if (!unchanged(pbuf, pos)) record_failure(row, at, "modified its const positions");
            check_guards(row, at, {"around the planes", "around the positions"}, {&out, &pbuf});
        }
    });
}

void run_facing_from_positions(std::vector<Row> &rows, Rng &rng) {
    for_each_case(true, kShapes, [&](int n, Shape shape, size_t caseno) {
        const int v = std::max(n, 0) / 2 + 3;
        const std::vector<float> pos = deform_positions(rng, v, shape);
        const std::vector<int> ix = deform_indices(rng, std::max(n, 0), v, shape);
        Vec4 light = random_light(rng);
        if (n > 0 && shape == Shape::degenerate) { // on a vertex: facing sums of 0
            const int c = ix[0];
            light = {pos[3 * (size_t)c], pos[3 * (size_t)c + 1], pos[3 * (size_t)c + 2], 1.0f};
        }
        const uint8_t pat = guard_pattern(rng);
        const size_t out_bytes = n >= 0 ? (size_t)n + 1 : 0;
        std::vector<uint8_t> want(out_bytes, pat);
        sv_facing_from_positions_c_ref(pos.data(), ix.data(), n, &light, want.data());
        const size_t po = pick(kIntOffsets, caseno), fo = pick(kByteOffsets, caseno);
        const std::string at = "n=" + std::to_string(n) + ", " + shape_name(shape) + ", offset " +
                               std::to_string(fo);
        for (Row &row : rows) {
            const Kernels &k = row.variant->for_triangles(n);
            GuardedBuffer pbuf = guarded_copy(pos, po, pat);
            GuardedBuffer ibuf = guarded_copy(ix, 0, pat);
            GuardedBuffer out(out_bytes, fo, pat);
            const Vec4 l = light;
            uint32_t failed = 0;
            abi_call(row.abi, &failed, k.planes->facing_from_positions, pbuf.as<const float>(),
                     ibuf.as<const int>(), n, &l, out.data());
            count_case(row);
            record_abi(row, failed, at);
            const std::string d = first_difference(out.data(), want.data(), out_bytes, "facing");
            if (!d.empty()) record_failure(row, at, d);
            if (!unchanged(pbuf, pos) || !unchanged(ibuf, ix)) {
                record_failure(row, at, "modified its const positions or indices");
            }
            check_guards(row, at,
                         {"around the facing bytes", "around the positions", "around the indices"},
                         {&out, &pbuf, &ibuf});
        }
    });
}

namespace {

// A skin of J joints over V vertices with INFLUENCES each: matrices with
// wide translations, weights with exact zeros (as files have them).
struct CheckSkin {
    std::vector<float> matrices, rest, weights;
    std::vector<uint16_t> joints;
    int influences = 4;
};

CheckSkin check_skin(Rng &rng, int v, int influences) {
    const int kJoints = 13;
    CheckSkin s;
    s.influences = influences;
    s.matrices.resize(16 * kJoints);
    for (float &m : s.matrices) m = rng.uniform(-2, 2);
    for (int j = 0; j < kJoints; j++) {
        for (int r = 0; r < 3; r++)
            s.matrices[16 * (size_t)j + 12 + (size_t)r] = rng.uniform(-1000, 1000);
    }
    s.rest = deform_positions(rng, v, Shape::ordinary);
    for (int i = 0; i < v * influences; i++) {
        s.joints.push_back((uint16_t)rng.below(kJoints));
        s.weights.push_back(rng.chance(0.3) ? 0.0f : (float)rng.unit());
    }
    return s;
}

} // namespace

// Influences per vertex: the loader's 4 and 8 (unrolled in the kernels)
// and counts on the general path.
constexpr int kInfluences[] = {1, 3, 4, 8};

void run_skinning(std::vector<Row> &rows, Rng &rng) {
    for_each_case(false, kInfluences, [&](int n, int influences, size_t caseno) {
        const CheckSkin s = check_skin(rng, n, influences);
        const uint8_t pat = guard_pattern(rng);
        std::vector<float> want(3 * (size_t)n);
        sv_skin_c_ref(s.matrices.data(), s.rest.data(), s.joints.data(), s.weights.data(),
                      influences, (size_t)n, want.data());
        const size_t oo = pick(kIntOffsets, caseno);
        const std::string at = "vertices=" + std::to_string(n) + ", influences " +
                               std::to_string(influences) + ", offset " + std::to_string(oo);
        for (Row &row : rows) {
            const Kernels &k = row.variant->for_triangles(n);
            GuardedBuffer mbuf = guarded_copy(s.matrices, 0, pat);
            GuardedBuffer rbuf = guarded_copy(s.rest, pick(kIntOffsets, caseno + 1), pat);
            GuardedBuffer out(want.size() * sizeof(float), oo, pat);
            uint32_t failed = 0;
            abi_call(row.abi, &failed, k.skin->fn, mbuf.as<const float>(), rbuf.as<const float>(),
                     s.joints.data(), s.weights.data(), influences, (size_t)n, out.as<float>());
            count_case(row);
            record_abi(row, failed, at);
            if (!want.empty() && std::memcmp(out.data(), want.data(), out.size()) != 0) {
                record_failure(row, at, "positions differ from c_ref's");
            }
            if (!unchanged(mbuf, s.matrices) || !unchanged(rbuf, s.rest)) {
                record_failure(row, at, "modified its const matrices or rest positions");
            }
            check_guards(row, at,
                         {"around the positions", "around the matrices",
                          "around the rest positions"},
                         {&out, &mbuf, &rbuf});
        }
    });
}

// Segment lengths of the schedule: one segment, single triangles, and
// lengths across the vector widths.
constexpr int kSegmentLengths[] = {0, 1, 17, 256};

void run_skin_planes(std::vector<Row> &rows, Rng &rng) {
    for_each_case(false, kSegmentLengths, [&](int n, int seg, size_t caseno) {
        const int influences = kInfluences[caseno % 4];
        const CheckSkin s = check_skin(rng, n, influences);
        const int t = n > 0 ? (int)rng.below((uint32_t)(2 * n + 2)) : 0;
        std::vector<int> ix;
        for (int i = 0; i < 3 * t; i++) { // near their place in the list, as exported meshes
            const int centre = (int)((long long)(i / 3) * n / std::max(t, 1));
            ix.push_back(std::min(n - 1, centre + (int)rng.below(4)));
        }
        const int segments = sv_skin_planes_schedule(ix.data(), t, (size_t)n, seg, nullptr, nullptr,
                                                     0);
        std::vector<size_t> vend((size_t)std::max(segments, 0));
        std::vector<int> tend(vend.size());
        sv_skin_planes_schedule(ix.data(), t, (size_t)n, seg, vend.data(), tend.data(), segments);
        const uint8_t pat = guard_pattern(rng);
        std::vector<float> want(3 * (size_t)n);
        std::vector<Plane> want_planes((size_t)t);
        sv_skin_c_ref(s.matrices.data(), s.rest.data(), s.joints.data(), s.weights.data(),
                      influences, (size_t)n, want.data());
        sv_derive_planes_c_ref(want.data(), ix.data(), t, want_planes.data());
        const std::string at = "vertices=" + std::to_string(n) + ", triangles " +
                               std::to_string(t) + ", segments of " + std::to_string(seg);
        for (Row &row : rows) {
            const Kernels &k = row.variant->for_triangles(t);
            if (!k.skin_planes) continue; /* "planned" chose two passes for this class */
            GuardedBuffer out(want.size() * sizeof(float), pick(kIntOffsets, caseno), pat);
            GuardedBuffer planes(want_planes.size() * sizeof(Plane), pick(kIntOffsets, caseno + 2),
                                 pat);
            sv_skin_planes_args a{};
            a.joint_matrices = s.matrices.data();
            a.rest = s.rest.data();
            a.joints = s.joints.data();
            a.weights = s.weights.data();
            a.influences = influences;
            a.num_vertices = (size_t)n;
            a.indices = ix.data();
            a.num_triangles = t;
            a.segments = segments;
            a.vertex_end = vend.data();
            a.triangle_end = tend.data();
            a.out = out.as<float>();
            a.planes = planes.as<Plane>();
            uint32_t failed = 0;
            abi_call(row.abi, &failed, k.skin_planes->fn, (const sv_skin_planes_args *)&a);
            count_case(row);
            record_abi(row, failed, at);
            if (!want.empty() && std::memcmp(out.data(), want.data(), out.size()) != 0) {
                record_failure(row, at, "positions differ from c_ref's");
            }
            for (size_t i = 0; i < want_planes.size(); i++) {
                // NOLINTNEXTLINE(bugprone-suspicious-memory-comparison): Plane is four floats, no padding
                if (std::memcmp(planes.data() + i * sizeof(Plane), &want_planes[i],
                                sizeof(Plane)) != 0) {
                    record_failure(row, at, "plane " + std::to_string(i) + " differs from c_ref's");
                    break;
                }
            }
            check_guards(row, at, {"around the positions", "around the planes"}, {&out, &planes});
        }
    });
}

} // namespace svcheck

// ---- Seed 002's vertex program (shadowvol_extrude.h, issue 31) --------------

namespace svcheck {

namespace {

// What a case's stream is like: the program's contract holds for every
// input (bit-identical to c_ref, a NaN's sign and payload aside).
enum class ExtrudeShape { ordinary, specials, extreme_scales, light_on_vertices };
constexpr ExtrudeShape kExtrudeShapes[] = {ExtrudeShape::ordinary, ExtrudeShape::specials,
                                           ExtrudeShape::extreme_scales,
                                           ExtrudeShape::light_on_vertices};

const char *extrude_shape_name(ExtrudeShape s) {
    switch (s) {
    case ExtrudeShape::ordinary: return "ordinary";
    case ExtrudeShape::specials: return "some 0, -0, NaN, infinity, FLT_MAX, zero normals";
    case ExtrudeShape::extreme_scales: return "huge and tiny coordinates";
    default: return "the light on a fifth of the vertices";
    }
}

// The light kinds the program tells apart: a finite range (the seed's
// clamp0(range - |vLP|)), no range (0: to infinity), an infinite range, a
// directional light (w = 0).
sv_extrude_light extrude_light(Rng &rng, size_t caseno) {
    sv_extrude_light l{};
    l.position = {rng.uniform(-60, 60), rng.uniform(-60, 60), rng.uniform(-60, 60), 1.0f};
    switch (caseno % 4) {
    case 0: l.range = rng.uniform(1, 150); break;
    case 1: l.range = 0.0f; break;
    case 2: l.range = std::numeric_limits<float>::infinity(); break;
    default: l.position.w = 0.0f; l.range = rng.uniform(1, 150);
    }
    return l;
}

// N vertices of SHAPE: positions as deform_positions makes them, unit face
// normals (some zero: a zero-area face), the light's own position on some
// vertices for LIGHT_ON_VERTICES.
std::vector<float> extrude_stream(Rng &rng, int n, ExtrudeShape shape, const Vec4 &light) {
    const Shape positions = shape == ExtrudeShape::specials         ? Shape::specials
                            : shape == ExtrudeShape::extreme_scales ? Shape::extreme_scales
                                                                    : Shape::ordinary;
    const std::vector<float> p = deform_positions(rng, std::max(n, 0), positions);
    std::vector<float> s((size_t)std::max(n, 0) * SV_EXTRUDE_STREAM_FLOATS);
    for (size_t i = 0; i < (size_t)std::max(n, 0); i++) {
        float *v = &s[i * SV_EXTRUDE_STREAM_FLOATS];
        for (int c = 0; c < 3; c++) v[c] = p[3 * i + (size_t)c];
        if (shape == ExtrudeShape::light_on_vertices && rng.chance(0.2)) {
            v[0] = light.x, v[1] = light.y, v[2] = light.z;
        }
        float nx = rng.uniform(-1, 1), ny = rng.uniform(-1, 1), nz = rng.uniform(-1, 1);
        const float len = std::sqrt(nx * nx + ny * ny + nz * nz);
        if (len > 0) nx /= len, ny /= len, nz /= len;
        if (rng.chance(0.05)) nx = ny = nz = 0.0f;
        v[3] = nx, v[4] = ny, v[5] = nz;
        if (shape == ExtrudeShape::specials && rng.chance(0.05)) {
            v[3 + rng.below(3)] = rng.chance(0.5) ? special_float(rng) : FLT_MAX;
        }
    }
    return s;
}

// Equal bits, or both NaN: the contract leaves a NaN's sign and payload to
// the operand order of a commutative operation.
bool same_float_or_nan(float a, float b) {
    uint32_t x = 0, y = 0;
    std::memcpy(&x, &a, sizeof x);
    std::memcpy(&y, &b, sizeof y);
    return (std::isnan(a) && std::isnan(b)) || x == y;
}

} // namespace

void run_extrude(std::vector<Row> &rows, Rng &rng) {
    for_each_case(true, kExtrudeShapes, [&](int n, ExtrudeShape shape, size_t caseno) {
        const sv_extrude_light light = extrude_light(rng, caseno);
        const std::vector<float> stream = extrude_stream(rng, n, shape, light.position);
        const uint8_t pat = guard_pattern(rng);
        std::vector<Vec4> want((size_t)std::max(n, 0));
        sv_extrude_c_ref(stream.data(), n, &light, want.data());
        const size_t so = pick(kIntOffsets, caseno), oo = pick(kIntOffsets, caseno + 5);
        const std::string at = "vertices=" + std::to_string(n) + ", " + extrude_shape_name(shape) +
                               ", range " + std::to_string(light.range) + ", w " +
                               std::to_string(light.position.w) + ", offset " + std::to_string(oo);
        for (Row &row : rows) {
            const Kernels &k = row.variant->for_triangles(std::max(n, 0) / 3);
            GuardedBuffer sbuf = guarded_copy(stream, so, pat);
            GuardedBuffer out(want.size() * sizeof(Vec4), oo, pat);
            const sv_extrude_light l = light;
            uint32_t failed = 0;
            abi_call(row.abi, &failed, k.extrude->extrude, sbuf.as<const float>(), n, &l,
                     out.as<Vec4>());
            count_case(row);
            record_abi(row, failed, at);
            const float *got = out.as<const float>();
            const float *ref = reinterpret_cast<const float *>(want.data());
            for (size_t i = 0; i < 4 * want.size(); i++) {
                if (!same_float_or_nan(got[i], ref[i])) {
                    record_failure(row, at,
                                   "vertex " + std::to_string(i / 4) + " differs from c_ref's");
                    break;
                }
            }
            if (!unchanged(sbuf, stream)) record_failure(row, at, "modified its const stream");
            check_guards(row, at, {"around the positions", "around the stream"}, {&out, &sbuf});
        }
    });
}

} // namespace svcheck
