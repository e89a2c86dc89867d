// Seeded generator, guarded buffers and allowed offsets (check_inputs.h).
//
// Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
#include "check_inputs.h"

#include <algorithm>
#include <cstring>
#include <string>

#include "fnv1a.h"

namespace svcheck {

uint64_t Rng::next() {
    uint64_t z = (s_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

uint32_t Rng::below(uint32_t n) {
    // Multiply-shift: no modulo bias worth the name at these sizes, and no
    // loop, so the number of draws per case is fixed.
    return n ? (uint32_t)(((next() >> 32) * (uint64_t)n) >> 32) : 0;
}

double Rng::unit() { return (double)(next() >> 11) * (1.0 / 9007199254740992.0); }

uint64_t stream_seed(uint64_t seed, const std::string &a, const std::string &b) {
    // FNV-1a over the names, then one splitmix step with the seed.
    const std::string names = a + "/" + b;
    Rng r(seed ^ sv::fnv1a64(names.data(), names.size()));
    return r.next();
}

GuardedBuffer::GuardedBuffer(size_t bytes, size_t offset, uint8_t pattern)
    : storage_(bytes + offset + 2 * kGuard + 64), bytes_(bytes), pattern_(pattern) {
    uint8_t *base = storage_.data();
    const uintptr_t line = ((uintptr_t)base + kGuard + 63) & ~(uintptr_t)63;
    data_ = (uint8_t *)line + offset;
    std::memset(storage_.data(), pattern, storage_.size());
}

std::string GuardedBuffer::guard_damage() const {
    for (size_t i = 1; i <= kGuard; i++) {
        if (data_[-(ptrdiff_t)i] != pattern_) return std::to_string(i) + " bytes before the start";
    }
    for (size_t i = 0; i < kGuard; i++) {
        if (data_[bytes_ + i] != pattern_)
            return "at byte " + std::to_string(i) + " past the bound";
    }
    return "";
}

std::vector<size_t> allowed_offsets(unsigned alignment, unsigned element) {
    std::vector<size_t> out;
    const unsigned step = std::max(std::max(alignment, element), 1u);
    const unsigned limit = step >= 16 ? 64 : 16;
    for (unsigned o = 0; o < limit; o += step) out.push_back(o);
    return out;
}

} // namespace svcheck
