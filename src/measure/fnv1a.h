/*
 * FNV-1a 64 (Fowler, Noll and Vo): the project's one fingerprint of bytes.
 * It names the exact index list of each volume in `render --json` (pinned
 * by tools/pin_bytes.sh), seeds the accuracy study per model and light,
 * and gives `shadowvol check` a random stream per routine and case. Not
 * for anything adversarial.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_MEASURE_FNV1A_H
#define SV_MEASURE_FNV1A_H

#include <cstddef>
#include <cstdint>

namespace sv {

constexpr uint64_t kFnv1a64OffsetBasis = 0xcbf29ce484222325ull;
constexpr uint64_t kFnv1a64Prime = 0x100000001b3ull;

/* The hash of N bytes at DATA, continuing from H (the offset basis for a
 * new hash). */
inline uint64_t fnv1a64(const void *data, std::size_t n, uint64_t h = kFnv1a64OffsetBasis) {
    const auto *p = static_cast<const unsigned char *>(data);
    for (std::size_t i = 0; i < n; i++) h = (h ^ p[i]) * kFnv1a64Prime;
    return h;
}

} // namespace sv

#endif
