/*
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "expected.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "oracle.h"

namespace svbench {

namespace {

/* The SplitMix64 finaliser: a bijection of 64-bit words. */
uint64_t mix(uint64_t z) {
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

/* Where two arrays first differ, for the message. */
template <class T> size_t first_difference(const T *a, const T *b, size_t n) {
    size_t i = 0;
    while (i < n && a[i] == b[i]) {
        i++;
    }
    return i;
}

} // namespace

uint64_t digest(const void *data, size_t bytes) {
    const unsigned char *p = static_cast<const unsigned char *>(data);
    uint64_t h = mix(0x6a09e667f3bcc909ull ^ bytes);
    size_t i = 0;
    for (; i + 8 <= bytes; i += 8) {
        uint64_t w;
        std::memcpy(&w, p + i, 8);
        h = mix(h ^ w);
    }
    if (i < bytes) {
        uint64_t w = 0;
        std::memcpy(&w, p + i, bytes - i);
        h = mix(h ^ w);
    }
    return h;
}

void initial_facing(Routine r, const Workload &w, const Light &l, uint8_t *facing) {
    const size_t n = (size_t)w.numTriangles + 1;
    if (r == Routine::calculate_facing || r == Routine::pipeline || r == Routine::pipeline_cull) {
        std::fill_n(facing, n, kPoisonByte);
    } else {
        std::memcpy(facing, l.facing.data(), n);
    }
}

SlotImage reference_image(Routine r, const Workload &w, const Light &l) {
    const sv_variant *ref = reference_variant().kernels;
    SlotImage s;
    s.facing.resize((size_t)w.numTriangles + 1);
    initial_facing(r, w, l, s.facing.data());
    uint8_t *f = s.facing.data();
    std::vector<int> out;
    if (writes_indices(r)) {
        out.assign(sv_shadow_volume_capacity(w.numIndices, w.numSilEdges), kPoisonIndex);
    }
    switch (r) {
    case Routine::calculate_facing:
        oracle_facing(w.planes.data(), w.numTriangles, l.position, f);
        break;
    case Routine::calculate_cull_bits:
        s.cull.assign((size_t)w.numVerts, kPoisonByte);
        s.count = oracle_cull_bits(w.positions.data(), w.numVerts, w.bounds, l.planes,
                                   s.cull.data());
        break;
    case Routine::count_facing: s.count = ref->count_facing(f, w.numTriangles); break;
    case Routine::count_facing_cull:
        s.count = ref->count_facing_cull(f, w.numTriangles, w.indices.data(), l.cullBits.data());
        break;
    case Routine::create_sil_triangles:
        s.count = ref->create_sil_triangles(out.data(), f, w.silEdges.data(), w.numSilEdges);
        break;
    case Routine::create_cap_triangles:
        s.count = ref->create_cap_triangles(out.data(), f, w.indices.data(), w.numIndices);
        break;
    case Routine::create_shadow_volume:
    case Routine::create_shadow_volume_cull:
        s.count = sv_create_shadow_volume(ref, out.data(), w.indices.data(), w.numIndices,
                                          w.silEdges.data(), w.numSilEdges, f,
                                          r == Routine::create_shadow_volume_cull
                                              ? l.cullBits.data()
                                              : nullptr);
        break;
    case Routine::pipeline:
    case Routine::pipeline_cull: {
        /* The second computation of A (and B) decides, then the volume
         * by c_ref: what the whole job must give. */
        oracle_facing(w.planes.data(), w.numTriangles, l.position, f);
        const uint8_t *cull = nullptr;
        if (r == Routine::pipeline_cull) {
            s.cull.assign((size_t)w.numVerts, kPoisonByte);
            if (oracle_cull_bits(w.positions.data(), w.numVerts, w.bounds, l.planes,
                                 s.cull.data()) == 0) {
                cull = s.cull.data();
            }
        }
        s.count = sv_create_shadow_volume(ref, out.data(), w.indices.data(), w.numIndices,
                                          w.silEdges.data(), w.numSilEdges, f, cull);
        break;
    }
    }
    if (writes_indices(r)) {
        out.resize((size_t)std::max(0, s.count));
        s.indices = std::move(out);
    }
    return s;
}

std::vector<Expected> expected_results(Routine r, const Workload &w) {
    std::vector<Expected> all;
    all.reserve(w.lights.size());
    for (size_t i = 0; i < w.lights.size(); i++) {
        const Light &l = w.lights[i];
        const SlotImage s = reference_image(r, w, l);
        /* What the light's counts promise. */
        int want = -1;
        switch (r) {
        case Routine::count_facing: want = l.numFacing; break;
        case Routine::count_facing_cull: want = l.numFacing + l.numTurned; break;
        case Routine::create_sil_triangles: want = 6 * l.numSilhouette; break;
        case Routine::create_cap_triangles: want = 6 * (w.numTriangles - l.numFacing); break;
        case Routine::create_shadow_volume:
            want = w.numTriangles == l.numFacing
                       ? 0
                       : 6 * l.numSilhouette + 6 * (w.numTriangles - l.numFacing);
            break;
        default: break;
        }
        if (want >= 0 && s.count != want) {
            throw std::logic_error(std::string("c_ref ") + routine_name(r) + " returned " +
                                   std::to_string(s.count) + " for light " + std::to_string(i) +
                                   ", its counts imply " + std::to_string(want));
        }
        Expected e;
        e.count = s.count;
        e.indices = digest(s.indices.data(), s.indices.size() * sizeof(int));
        e.facing = digest(s.facing.data(), s.facing.size());
        e.cull = digest(s.cull.data(), s.cull.size());
        all.push_back(e);
    }
    return all;
}

std::string compare_with_reference(Routine r, const Workload &w, const Light &l, const Expected &e,
                                   int got, const int *indices, const uint8_t *facing,
                                   const uint8_t *cull) {
    const char *what = needs_light(r) ? "the second computation" : "c_ref";
    char msg[200];
    if (got != e.count) {
        std::snprintf(msg, sizeof msg, "returned %d, %s %d", got, what, e.count);
        return msg;
    }
    const size_t nf = (size_t)w.numTriangles + 1;
    const bool indicesOk = !writes_indices(r) ||
                           digest(indices, (size_t)got * sizeof(int)) == e.indices;
    const bool facingOk = digest(facing, nf) == e.facing;
    const bool cullOk = (r != Routine::calculate_cull_bits && r != Routine::pipeline_cull) ||
                        digest(cull, (size_t)w.numVerts) == e.cull;
    if (indicesOk && facingOk && cullOk) {
        return std::string();
    }
    const SlotImage s = reference_image(r, w, l);
    if (!indicesOk) {
        const size_t i = first_difference(indices, s.indices.data(), s.indices.size());
        if (i < s.indices.size()) {
            std::snprintf(msg, sizeof msg, "index[%zu] = %d, %s %d", i, indices[i], what,
                          s.indices[i]);
            return msg;
        }
    }
    if (!facingOk) {
        const size_t i = first_difference(facing, s.facing.data(), nf);
        if (i < nf) {
            std::snprintf(msg, sizeof msg, "facing[%zu] = %d after the call, %s %d", i, facing[i],
                          what, s.facing[i]);
            return msg;
        }
    }
    if (!cullOk) {
        const size_t i = first_difference(cull, s.cull.data(), s.cull.size());
        if (i < s.cull.size()) {
            std::snprintf(msg, sizeof msg, "cullBits[%zu] = 0x%02x after the call, %s 0x%02x", i,
                          cull[i], what, s.cull[i]);
            return msg;
        }
    }
    /* Digests differ where the arrays do not: the reference itself is not
     * deterministic. */
    return std::string("the reference gave a different result on a second run");
}

} // namespace svbench
