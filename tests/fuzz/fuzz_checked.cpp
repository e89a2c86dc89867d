/*
 * libFuzzer target: the *_checked entry points of include/shadowvol.h on
 * fuzzer-chosen counts, edges, indices, facing and cull bytes, alignments
 * and capacities (issue 17). Each call must either refuse with an SV_E_*
 * code (and then write nothing) or give exactly c_ref's result: the same
 * return value, the same indices up to it, the same facing bytes after
 * (CountFacingCull modifies them). Every array is allocated at exactly the
 * size its contract documents (output: exactly `capacity` ints), so ASan
 * reports any byte touched past the bound. Counts that the contract refuses
 * outright (3 * numTriangles, 6 * numSilEdges or 2 * numIndices past
 * INT_MAX) are tried with tiny arrays: they must be refused unread. The
 * general rule's entry points (issue 27) likewise: edge tables with
 * triangles, vertices and shared uses out of range, k-way shared edges up
 * to 64 uses, facing bytes above 2 or 2 on the paper's class, output room
 * short of sv_general_sil_capacity; every accepted call gives c_ref's list.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <fuzzer/FuzzedDataProvider.h>

#include <climits>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <tuple>
#include <vector>

#include "shadowvol.h"

namespace {

[[noreturn]] void finding(const char *routine, const char *variant, const char *what, long a,
                          long b) {
    std::fprintf(stderr, "FUZZ FINDING: %s, %s: %s (%ld vs %ld)\n", routine, variant, what, a, b);
    std::fflush(stderr);
    std::abort();
}

/* N elements of T at a fuzzer-chosen misalignment (0..15 bytes past a
 * 64-byte boundary), in a block of exactly the bytes they need: ASan's
 * redzone starts right after the last element. */
template <class T> struct Exact {
    unsigned char *block = nullptr;
    T *p = nullptr;
    size_t n = 0;
    Exact(size_t count, unsigned misalign) : n(count) {
        const size_t bytes = count * sizeof(T) + misalign;
        block = static_cast<unsigned char *>(std::malloc(bytes ? bytes : 1));
        /* malloc gives 16-byte alignment; misalign steps of sizeof(T) keep T aligned */
        p = reinterpret_cast<T *>(block + misalign);
    }
    ~Exact() { std::free(block); }
    Exact(const Exact &) = delete;
    Exact &operator=(const Exact &) = delete;
};

/* A cap routine's counts: NT triangles' indices over NV vertices, now and
 * then off by a few (not a multiple of 3, or negative). */
struct CapCounts {
    int nv, ni;
    size_t nidx; /* ni, or 0 when negative */
};
CapCounts cap_counts(FuzzedDataProvider &d) {
    const int nt = d.ConsumeIntegralInRange<int>(0, 300),
              nv = d.ConsumeIntegralInRange<int>(0, 300);
    int ni = 3 * nt;
    if (d.ConsumeIntegral<uint8_t>() < 8) ni += d.ConsumeIntegralInRange<int>(-4, 2);
    return {nv, ni, ni > 0 ? (size_t)ni : 0};
}

/* N indices, mostly in [0, NV), now and then one out of range. */
void fill_indices(FuzzedDataProvider &d, int *idx, size_t n, int nv) {
    for (size_t i = 0; i < n; i++) {
        idx[i] = d.ConsumeIntegral<uint8_t>() < 250 && nv > 0
                     ? d.ConsumeIntegralInRange<int>(0, nv - 1)
                     : d.ConsumeIntegralInRange<int>(-1, nv + 1);
    }
}

/* A cap routine's output room: its bound 2 * NIDX, now and then short. */
size_t cap_capacity(FuzzedDataProvider &d, size_t nidx) {
    size_t capacity = 2 * nidx;
    if (d.ConsumeIntegral<uint8_t>() < 8 && capacity)
        capacity -= d.ConsumeIntegralInRange<size_t>(1, capacity);
    return capacity;
}

unsigned misalignment(FuzzedDataProvider &d, size_t element) {
    return (unsigned)(d.ConsumeIntegralInRange<unsigned>(0, 3) * element) % 16u;
}

/* The contract, written again here from the header (not from
 * src/core/contracts.c): the harness's own oracle of what must be accepted. */
bool aligned_to(const void *p, unsigned a) { return ((uintptr_t)p & (uintptr_t)(a - 1)) == 0; }
bool all_bool(const uint8_t *f, long n) {
    for (long i = 0; i < n; i++) {
        if (f[i] > 1) return false;
    }
    return true;
}
bool all_general(const uint8_t *f, long n) {
    for (long i = 0; i < n; i++) {
        if (f[i] > SV_GENERAL_LIT) return false;
    }
    return true;
}
bool indices_in(const int *idx, long n, int nv) {
    for (long i = 0; i < n; i++) {
        if (idx[i] < 0 || idx[i] >= nv) return false;
    }
    return true;
}
bool edges_in(const SilEdge *e, long n, int nt, long nv /* -1: unknown */) {
    for (long i = 0; i < n; i++) {
        if (e[i].p1 < 0 || e[i].p1 > nt || e[i].p2 < 0 || e[i].p2 > nt) return false;
        if (e[i].v1 < 0 || e[i].v2 < 0 || (e[i].v1 & 1) || (e[i].v2 & 1)) return false;
        if (nv >= 0 && (e[i].v1 / 2 >= nv || e[i].v2 / 2 >= nv)) return false;
    }
    return true;
}
bool paper_cull(const sv_variant *v) {
    return v->count_facing_cull == sv_count_facing_cull_sse2_paper;
}
bool no_bit7(const uint8_t *c, int n) {
    for (int i = 0; i < n; i++) {
        if (c[i] & 0x80) return false;
    }
    return true;
}
/* Accepted exactly when in contract: a refusal of valid input, or an
 * acceptance of invalid input (facing[numTriangles] = 0, sse2_paper's bit
 * 7, ...), is a finding. */
void hold_contract(const char *routine, const sv_variant *v, int status, bool valid) {
    if (status >= 0 && !valid)
        finding(routine, v->name, "accepted out-of-contract input", status, 0);
    if (status < 0 && valid) finding(routine, v->name, "refused in-contract input", status, 0);
}

const sv_variant *pick_variant(FuzzedDataProvider &d) {
    int n = 0;
    const sv_variant *all = sv_variants(&n);
    const sv_variant *v = &all[d.ConsumeIntegralInRange<int>(0, n - 1)];
    return (v->isa & sv_cpu_isa()) == v->isa ? v : sv_variant_by_name("c_ref");
}

/* A facing byte: mostly 0 or 1, sometimes anything. */
uint8_t facing_byte(FuzzedDataProvider &d) {
    const uint8_t b = d.ConsumeIntegral<uint8_t>();
    return b < 240 ? (uint8_t)(b & 1) : b;
}

int count(FuzzedDataProvider &d, int max) {
    const uint8_t kind = d.ConsumeIntegral<uint8_t>();
    if (kind < 8) return -(int)d.ConsumeIntegralInRange<int>(1, 3);
    return d.ConsumeIntegralInRange<int>(0, max);
}

void fuzz_count_facing(FuzzedDataProvider &d, const sv_variant *v) {
    const int n = count(d, 1024);
    const size_t len = n > 0 ? (size_t)n : 0;
    Exact<uint8_t> f(len, misalignment(d, 1));
    for (size_t i = 0; i < len; i++) f.p[i] = facing_byte(d);
    const int got = sv_count_facing_checked(v, f.p, n);
    hold_contract("count_facing", v, got,
                  n >= 0 && aligned_to(f.p, v->align_facing) && all_bool(f.p, n));
    if (got < 0) return;
    const int want = sv_count_facing_checked(sv_variant_by_name("c_ref"), f.p, n);
    if (got != want) finding("count_facing", v->name, "differs from c_ref", got, want);
}

void fuzz_count_facing_cull(FuzzedDataProvider &d, const sv_variant *v) {
    if (d.ConsumeIntegral<uint8_t>() < 4) { /* 3 * numTriangles past INT_MAX: refused unread */
        uint8_t f[1] = {0};
        int idx[3] = {0, 0, 0};
        uint8_t cull[1] = {0};
        const int r = sv_count_facing_cull_checked(v, f, INT_MAX / 3 + 1, idx, cull, 1);
        if (r != SV_E_OVERFLOW)
            finding("count_facing_cull", v->name, "huge count", r, SV_E_OVERFLOW);
        return;
    }
    const int nt = count(d, 512), nv = d.ConsumeIntegralInRange<int>(0, 300);
    const size_t t = nt > 0 ? (size_t)nt : 0;
    Exact<uint8_t> f(t, misalignment(d, 1)), fr(t, 0);
    Exact<int> idx(3 * t, misalignment(d, 4));
    Exact<uint8_t> cull((size_t)nv, 0);
    for (size_t i = 0; i < t; i++) fr.p[i] = f.p[i] = facing_byte(d);
    for (size_t i = 0; i < 3 * t; i++) {
        idx.p[i] = d.ConsumeIntegral<uint8_t>() < 250 && nv > 0
                       ? d.ConsumeIntegralInRange<int>(0, nv - 1)
                       : d.ConsumeIntegralInRange<int>(-2, nv + 2);
    }
    for (int i = 0; i < nv; i++) {
        const uint8_t b = d.ConsumeIntegral<uint8_t>();
        cull.p[i] = b < 200 ? (uint8_t)(b & 0x3F) : b; /* mostly six light planes */
    }
    const int got = sv_count_facing_cull_checked(v, f.p, nt, idx.p, cull.p, nv);
    hold_contract("count_facing_cull", v, got,
                  nt >= 0 && all_bool(fr.p, nt) && indices_in(idx.p, 3L * nt, nv) &&
                      (nt <= 0 || !paper_cull(v) || no_bit7(cull.p, nv)));
    if (got < 0) {
        if (t && std::memcmp(f.p, fr.p, t))
            finding("count_facing_cull", v->name, "refused but wrote", got, 0);
        return;
    }
    const int want = sv_count_facing_cull_checked(sv_variant_by_name("c_ref"), fr.p, nt, idx.p,
                                                  cull.p, nv);
    if (got != want) finding("count_facing_cull", v->name, "differs from c_ref", got, want);
    if (t && std::memcmp(f.p, fr.p, t))
        finding("count_facing_cull", v->name, "facing differs", 0, 0);
}

SilEdge edge(FuzzedDataProvider &d, int nt, int nv) {
    SilEdge e;
    const bool wild = d.ConsumeIntegral<uint8_t>() >= 250;
    e.p1 = wild ? d.ConsumeIntegralInRange<int>(-1, nt + 1) : d.ConsumeIntegralInRange<int>(0, nt);
    e.p2 = wild ? d.ConsumeIntegralInRange<int>(-1, nt + 1) : d.ConsumeIntegralInRange<int>(0, nt);
    e.v1 = 2 * d.ConsumeIntegralInRange<int>(0, nv > 0 ? nv - 1 : 0) + (wild ? d.ConsumeBool() : 0);
    e.v2 = 2 * d.ConsumeIntegralInRange<int>(0, nv > 0 ? nv - 1 : 0) + (wild ? d.ConsumeBool() : 0);
    return e;
}

void fuzz_sil(FuzzedDataProvider &d, const sv_variant *v) {
    if (d.ConsumeIntegral<uint8_t>() < 4) {
        uint8_t f[2] = {0, 1};
        SilEdge e = {0, 1, 0, 2};
        int out[6];
        const int r = sv_create_sil_triangles_checked(v, out, 6, f, 1, &e, INT_MAX / 6 + 1);
        if (r != SV_E_OVERFLOW)
            finding("create_sil_triangles", v->name, "huge count", r, SV_E_OVERFLOW);
        return;
    }
    const int nt = d.ConsumeIntegralInRange<int>(0, 300), ne = count(d, 400);
    const int nv = d.ConsumeIntegralInRange<int>(1, 300);
    const size_t edges = ne > 0 ? (size_t)ne : 0;
    Exact<uint8_t> f((size_t)nt + 1, 0);
    for (int i = 0; i <= nt; i++) f.p[i] = facing_byte(d);
    if (d.ConsumeIntegral<uint8_t>() < 240) f.p[nt] = 1;
    Exact<SilEdge> e(edges, 0);
    for (size_t i = 0; i < edges; i++) e.p[i] = edge(d, nt, nv);
    size_t capacity = 6 * edges;
    if (d.ConsumeIntegral<uint8_t>() < 8 && capacity)
        capacity -= d.ConsumeIntegralInRange<size_t>(1, capacity);
    Exact<int> out(capacity, misalignment(d, 4));
    const int got = sv_create_sil_triangles_checked(v, out.p, capacity, f.p, nt, e.p, ne);
    hold_contract("create_sil_triangles", v, got,
                  ne >= 0 && capacity >= 6 * edges && aligned_to(out.p, v->align_shadow_indices) &&
                      all_bool(f.p, nt) && f.p[nt] == 1 && edges_in(e.p, ne, nt, -1));
    if (got < 0) return;
    if ((size_t)got > capacity)
        finding("create_sil_triangles", v->name, "past capacity", got, (long)capacity);
    std::vector<int> ref(6 * edges + 1);
    const int want = sv_create_sil_triangles_checked(sv_variant_by_name("c_ref"), ref.data(),
                                                     6 * edges, f.p, nt, e.p, ne);
    if (got != want) finding("create_sil_triangles", v->name, "differs from c_ref", got, want);
    if (got && std::memcmp(out.p, ref.data(), (size_t)got * sizeof(int)))
        finding("create_sil_triangles", v->name, "indices differ", 0, 0);
}

void fuzz_cap(FuzzedDataProvider &d, const sv_variant *v) {
    if (d.ConsumeIntegral<uint8_t>() < 4) {
        uint8_t f[1] = {0};
        int idx[3] = {0, 0, 0}, out[6];
        const int r = sv_create_cap_triangles_checked(v, out, 6, f, idx, 3 * (INT_MAX / 6 + 1), 1);
        if (r != SV_E_OVERFLOW)
            finding("create_cap_triangles", v->name, "huge count", r, SV_E_OVERFLOW);
        return;
    }
    const CapCounts k = cap_counts(d);
    const int nv = k.nv, ni = k.ni;
    const size_t nidx = k.nidx;
    Exact<uint8_t> f((size_t)(nidx / 3), 0);
    for (size_t i = 0; i < nidx / 3; i++) f.p[i] = facing_byte(d);
    Exact<int> idx(nidx, misalignment(d, 4));
    fill_indices(d, idx.p, nidx, nv);
    const size_t capacity = cap_capacity(d, nidx);
    Exact<int> out(capacity, misalignment(d, 4));
    const int got = sv_create_cap_triangles_checked(v, out.p, capacity, f.p, idx.p, ni, nv);
    hold_contract("create_cap_triangles", v, got,
                  ni >= 0 && ni % 3 == 0 && aligned_to(idx.p, v->align_indices) &&
                      aligned_to(out.p, v->align_shadow_indices) && capacity >= 2 * nidx &&
                      all_bool(f.p, ni / 3) && indices_in(idx.p, ni, nv));
    if (got < 0) return;
    std::vector<int> ref(2 * nidx + 1);
    const int want = sv_create_cap_triangles_checked(sv_variant_by_name("c_ref"), ref.data(),
                                                     2 * nidx, f.p, idx.p, ni, nv);
    if (got != want) finding("create_cap_triangles", v->name, "differs from c_ref", got, want);
    if (got && std::memcmp(out.p, ref.data(), (size_t)got * sizeof(int)))
        finding("create_cap_triangles", v->name, "indices differ", 0, 0);
}

void fuzz_volume(FuzzedDataProvider &d, const sv_variant *v) {
    const int nt = d.ConsumeIntegralInRange<int>(0, 200),
              nv = d.ConsumeIntegralInRange<int>(1, 200);
    const int ne = d.ConsumeIntegralInRange<int>(0, 300);
    const int ni = 3 * nt;
    Exact<int> idx((size_t)ni, misalignment(d, 4));
    for (int i = 0; i < ni; i++) {
        idx.p[i] = d.ConsumeIntegral<uint8_t>() < 250 ? d.ConsumeIntegralInRange<int>(0, nv - 1)
                                                      : d.ConsumeIntegralInRange<int>(-1, nv + 1);
    }
    Exact<SilEdge> e((size_t)ne, 0);
    for (int i = 0; i < ne; i++) e.p[i] = edge(d, nt, nv);
    Exact<uint8_t> f((size_t)nt + 1, misalignment(d, 1)), fr((size_t)nt + 1, 0);
    for (int i = 0; i <= nt; i++) fr.p[i] = f.p[i] = facing_byte(d);
    if (d.ConsumeIntegral<uint8_t>() < 240) fr.p[nt] = f.p[nt] = 1;
    const bool use_cull = d.ConsumeBool();
    Exact<uint8_t> cull((size_t)nv, 0);
    for (int i = 0; i < nv; i++) {
        const uint8_t b = d.ConsumeIntegral<uint8_t>();
        cull.p[i] = b < 200 ? (uint8_t)(b & 0x3F) : b; /* mostly six light planes */
    }
    size_t capacity = sv_shadow_volume_capacity(ni, ne);
    if (d.ConsumeIntegral<uint8_t>() < 8 && capacity)
        capacity -= d.ConsumeIntegralInRange<size_t>(1, capacity);
    Exact<int> out(capacity, misalignment(d, 4));
    const int got = sv_create_shadow_volume_checked(v, out.p, capacity, idx.p, ni, nv, e.p, ne, f.p,
                                                    use_cull ? cull.p : nullptr);
    hold_contract("create_shadow_volume", v, got,
                  capacity >= sv_shadow_volume_capacity(ni, ne) &&
                      (use_cull || aligned_to(f.p, v->align_facing)) &&
                      aligned_to(idx.p, v->align_indices) &&
                      aligned_to(out.p, v->align_shadow_indices) && all_bool(fr.p, nt) &&
                      fr.p[nt] == 1 && indices_in(idx.p, ni, nv) && edges_in(e.p, ne, nt, nv) &&
                      (!use_cull || nt == 0 || !paper_cull(v) || no_bit7(cull.p, nv)));
    if (got < 0) {
        if (std::memcmp(f.p, fr.p, (size_t)nt + 1))
            finding("create_shadow_volume", v->name, "refused but wrote facing", got, 0);
        return;
    }
    std::vector<int> ref(sv_shadow_volume_capacity(ni, ne) + 1);
    const int want = sv_create_shadow_volume_checked(sv_variant_by_name("c_ref"), ref.data(),
                                                     ref.size() - 1, idx.p, ni, nv, e.p, ne, fr.p,
                                                     use_cull ? cull.p : nullptr);
    if (got != want) finding("create_shadow_volume", v->name, "differs from c_ref", got, want);
    if (got && std::memcmp(out.p, ref.data(), (size_t)got * sizeof(int)))
        finding("create_shadow_volume", v->name, "indices differ", 0, 0);
    if (std::memcmp(f.p, fr.p, (size_t)nt + 1))
        finding("create_shadow_volume", v->name, "facing differs", 0, 0);
}

/* ---- The general rule's entry points (issue 27) ---------------------------- */

const sv_general_variant *pick_general_variant(FuzzedDataProvider &d) {
    int n = 0;
    const sv_general_variant *all = sv_general_variants(&n);
    const sv_general_variant *v = &all[d.ConsumeIntegralInRange<int>(0, n - 1)];
    return (v->isa & sv_cpu_isa()) == v->isa ? v : sv_general_variant_by_name("c_ref");
}

/* A general byte: mostly 0, 1 or 2, sometimes anything. */
uint8_t general_byte(FuzzedDataProvider &d) {
    const uint8_t b = d.ConsumeIntegral<uint8_t>();
    return b < 240 ? (uint8_t)(b % 3) : b;
}

bool doubled_vertex_in(int v, int nv) { return v >= 0 && v / 2 < nv && (v & 1) == 0; }

/* The general edge table's contract from the header: pairs and opens name
 * triangles below NT (an open edge its triangle twice), the paper's class
 * may name NT (then facing[NT] is read; it must be 1 where p2 is NT), and
 * bytes 0 or 1 there; every vertex even and below 2 * NV; every shared use
 * inside sharedUses and naming a triangle below NT. */
bool general_edges_in(const sv_general_edges &e, const uint8_t *f, int nt, int nv) {
    for (int i = 0; i < e.numPaper; i++) {
        const SilEdge &x = e.paper[i];
        if (x.p1 < 0 || x.p1 > nt || x.p2 < 0 || x.p2 > nt) return false;
        if (!doubled_vertex_in(x.v1, nv) || !doubled_vertex_in(x.v2, nv)) return false;
        if (f[x.p1] > 1 || f[x.p2] > 1 || (x.p2 == nt && f[nt] != 1)) return false;
    }
    for (const auto &[list, n, open] : {std::make_tuple(e.pairs, e.numPairs, false),
                                        std::make_tuple(e.opens, e.numOpens, true)}) {
        for (int i = 0; i < n; i++) {
            const SilEdge &x = list[i];
            if (x.p1 < 0 || x.p1 >= nt || x.p2 < 0 || x.p2 >= nt || (open && x.p2 != x.p1))
                return false;
            if (!doubled_vertex_in(x.v1, nv) || !doubled_vertex_in(x.v2, nv)) return false;
        }
    }
    for (int i = 0; i < e.numShared; i++) {
        const sv_shared_edge &x = e.shared[i];
        if (x.numUses < 1 || x.firstUse < 0 || (long)x.firstUse + x.numUses > e.numSharedUses)
            return false;
        if (!doubled_vertex_in(x.v1, nv) || !doubled_vertex_in(x.v2, nv)) return false;
        for (int k = 0; k < x.numUses; k++) {
            const int u = e.sharedUses[x.firstUse + k];
            if (u < 0 || (u >> 1) >= nt) return false;
        }
    }
    return true;
}

/* A pair (or, OPEN, an open edge: p2 = p1) of triangles below NT, now and
 * then out of range or with an odd vertex. */
SilEdge general_edge(FuzzedDataProvider &d, int nt, int nv, bool open) {
    SilEdge e = edge(d, nt > 0 ? nt - 1 : 0, nv);
    if (open && d.ConsumeIntegral<uint8_t>() < 250) e.p2 = e.p1;
    return e;
}

void fuzz_general_sil(FuzzedDataProvider &d, const sv_general_variant *v) {
    if (d.ConsumeIntegral<uint8_t>() < 4) { /* the bound past INT_MAX: refused unread */
        uint8_t f[2] = {0, 1};
        int out[12];
        sv_general_edges e = {};
        e.numPairs = INT_MAX / 12 + 1;
        SilEdge pair = {0, 0, 0, 2};
        e.pairs = &pair;
        const int r = sv_create_general_sil_triangles_checked(v, out, 12, f, 1, 2, &e);
        if (r != SV_E_OVERFLOW)
            finding("create_general_sil_triangles", v->name, "huge count", r, SV_E_OVERFLOW);
        return;
    }
    const int nt = d.ConsumeIntegralInRange<int>(0, 300),
              nv = d.ConsumeIntegralInRange<int>(1, 300);
    const int np = count(d, 40), npairs = count(d, 120), nopen = count(d, 40);
    const int nshared = count(d, 20);
    const size_t paper = np > 0 ? (size_t)np : 0, pairs = npairs > 0 ? (size_t)npairs : 0;
    const size_t opens = nopen > 0 ? (size_t)nopen : 0, shared = nshared > 0 ? (size_t)nshared : 0;
    Exact<SilEdge> pe(paper, 0), pa(pairs, 0), op(opens, 0);
    bool names_nt = false; /* the paper's class reads facing[nt] */
    for (size_t i = 0; i < paper; i++) {
        pe.p[i] = edge(d, nt, nv);
        names_nt = names_nt || pe.p[i].p1 == nt || pe.p[i].p2 == nt;
    }
    for (size_t i = 0; i < pairs; i++) pa.p[i] = general_edge(d, nt, nv, false);
    for (size_t i = 0; i < opens; i++) op.p[i] = general_edge(d, nt, nv, true);
    /* Shared edges of 1 to 64 uses (k-way edges up to the bound 6 * k),
     * laid end to end in sharedUses, now and then overlapping or past it. */
    Exact<sv_shared_edge> sh(shared, 0);
    std::vector<int> uses;
    for (size_t i = 0; i < shared; i++) {
        const int k = d.ConsumeIntegral<uint8_t>() < 240 ? d.ConsumeIntegralInRange<int>(1, 6)
                                                         : d.ConsumeIntegralInRange<int>(0, 64);
        const SilEdge ends = edge(d, nt, nv);
        sh.p[i] = {ends.v1, ends.v2, (int)uses.size(), k};
        if (d.ConsumeIntegral<uint8_t>() >= 250)
            sh.p[i].firstUse += d.ConsumeIntegralInRange<int>(-3, 3);
        for (int u = 0; u < k; u++) {
            uses.push_back(d.ConsumeIntegral<uint8_t>() < 250 && nt > 0
                               ? 2 * d.ConsumeIntegralInRange<int>(0, nt - 1) + d.ConsumeBool()
                               : d.ConsumeIntegralInRange<int>(-2, 2 * nt + 2));
        }
    }
    int num_uses = (int)uses.size();
    if (d.ConsumeIntegral<uint8_t>() < 8) num_uses += d.ConsumeIntegralInRange<int>(-3, 0);
    if (num_uses < 0) num_uses = 0;
    Exact<int> su((size_t)num_uses, 0);
    if (num_uses) std::memcpy(su.p, uses.data(), (size_t)num_uses * sizeof(int));
    /* Exactly the bytes the contract needs: facing[nt] only where the
     * paper's class names nt. */
    const size_t flen = (size_t)nt + (names_nt ? 1 : 0);
    Exact<uint8_t> f(flen, misalignment(d, 1));
    for (size_t i = 0; i < flen; i++) f.p[i] = general_byte(d);
    if (names_nt && d.ConsumeIntegral<uint8_t>() < 240) f.p[nt] = 1;
    sv_general_edges e = {pe.p, np, pa.p, npairs, op.p, nopen, sh.p, nshared, su.p, num_uses};
    const bool counts_ok = np >= 0 && npairs >= 0 && nopen >= 0 && nshared >= 0;
    const size_t bound = counts_ok ? 6 * paper + 12 * pairs + 6 * opens + 6 * (size_t)num_uses : 0;
    size_t capacity = bound;
    if (d.ConsumeIntegral<uint8_t>() < 8 && capacity)
        capacity -= d.ConsumeIntegralInRange<size_t>(1, capacity);
    Exact<int> out(capacity, misalignment(d, 4));
    for (size_t i = 0; i < capacity; i++) out.p[i] = -7;
    const int got = sv_create_general_sil_triangles_checked(v, out.p, capacity, f.p, nt, nv, &e);
    const bool valid = counts_ok && capacity >= bound && all_general(f.p, nt) &&
                       general_edges_in(e, f.p, nt, nv);
    if (got >= 0 && !valid)
        finding("create_general_sil_triangles", v->name, "accepted out-of-contract input", got, 0);
    if (got < 0 && valid)
        finding("create_general_sil_triangles", v->name, "refused in-contract input", got, 0);
    if (got < 0) {
        for (size_t i = 0; i < capacity; i++)
            if (out.p[i] != -7)
                finding("create_general_sil_triangles", v->name, "refused but wrote", got, (long)i);
        return;
    }
    if ((size_t)got > capacity || got % 6 != 0)
        finding("create_general_sil_triangles", v->name, "count past the bound", got, (long)bound);
    std::vector<int> ref(bound + 1);
    const int want = sv_create_general_sil_triangles_checked(sv_general_variant_by_name("c_ref"),
                                                             ref.data(), bound, f.p, nt, nv, &e);
    if (got != want)
        finding("create_general_sil_triangles", v->name, "differs from c_ref", got, want);
    if (got && std::memcmp(out.p, ref.data(), (size_t)got * sizeof(int)))
        finding("create_general_sil_triangles", v->name, "indices differ", 0, 0);
}

void fuzz_general_cap(FuzzedDataProvider &d, const sv_general_variant *v) {
    if (d.ConsumeIntegral<uint8_t>() < 4) { /* 2 * numIndices past INT_MAX: refused unread */
        uint8_t f[1] = {0};
        int idx[3] = {0, 0, 0}, out[6];
        const int r = sv_create_general_cap_triangles_checked(v, out, 6, f, idx,
                                                              3 * (INT_MAX / 6 + 1), 1);
        if (r != SV_E_OVERFLOW)
            finding("create_general_cap_triangles", v->name, "huge count", r, SV_E_OVERFLOW);
        return;
    }
    const CapCounts k = cap_counts(d);
    const int nv = k.nv, ni = k.ni;
    const size_t nidx = k.nidx;
    Exact<uint8_t> f(nidx / 3, misalignment(d, 1));
    for (size_t i = 0; i < nidx / 3; i++) f.p[i] = general_byte(d);
    Exact<int> idx(nidx, misalignment(d, 4));
    fill_indices(d, idx.p, nidx, nv);
    const size_t capacity = cap_capacity(d, nidx);
    Exact<int> out(capacity, misalignment(d, 4));
    for (size_t i = 0; i < capacity; i++) out.p[i] = -7;
    const int got = sv_create_general_cap_triangles_checked(v, out.p, capacity, f.p, idx.p, ni, nv);
    const bool valid = ni >= 0 && ni % 3 == 0 && capacity >= 2 * nidx && all_general(f.p, ni / 3) &&
                       indices_in(idx.p, ni, nv);
    if (got >= 0 && !valid)
        finding("create_general_cap_triangles", v->name, "accepted out-of-contract input", got, 0);
    if (got < 0 && valid)
        finding("create_general_cap_triangles", v->name, "refused in-contract input", got, 0);
    if (got < 0) {
        for (size_t i = 0; i < capacity; i++)
            if (out.p[i] != -7)
                finding("create_general_cap_triangles", v->name, "refused but wrote", got, (long)i);
        return;
    }
    std::vector<int> ref(2 * nidx + 1);
    const int want = sv_create_general_cap_triangles_checked(sv_general_variant_by_name("c_ref"),
                                                             ref.data(), 2 * nidx, f.p, idx.p, ni,
                                                             nv);
    if (got != want)
        finding("create_general_cap_triangles", v->name, "differs from c_ref", got, want);
    if (got && std::memcmp(out.p, ref.data(), (size_t)got * sizeof(int)))
        finding("create_general_cap_triangles", v->name, "indices differ", 0, 0);
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    FuzzedDataProvider d(data, size);
    const int routine = d.ConsumeIntegralInRange<int>(0, 6);
    if (routine >= 5) {
        const sv_general_variant *g = pick_general_variant(d);
        if (routine == 5)
            fuzz_general_sil(d, g);
        else
            fuzz_general_cap(d, g);
        return 0;
    }
    const sv_variant *v = pick_variant(d);
    switch (routine) {
    case 0: fuzz_count_facing(d, v); break;
    case 1: fuzz_count_facing_cull(d, v); break;
    case 2: fuzz_sil(d, v); break;
    case 3: fuzz_cap(d, v); break;
    default: fuzz_volume(d, v); break;
    }
    return 0;
}
