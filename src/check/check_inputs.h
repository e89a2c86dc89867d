// The raw material of `shadowvol check` (routine_checks.cpp): a seeded
// generator, guarded buffers at chosen offsets, and the offsets an
// alignment contract allows. No GoogleTest, glTF or threads here, so the
// check library builds wherever the core library does (SV_CORE_ONLY).
//
// Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace svcheck {

// splitmix64: one 64-bit state, the same stream on every platform and
// compiler for a given seed, so `--seed S` replays a run anywhere.
class Rng {
public:
    explicit Rng(uint64_t seed) : s_(seed) {}
    uint64_t next();
    uint32_t below(uint32_t n); // uniform in [0, n); 0 when n == 0
    double unit();              // uniform in [0, 1)
    bool chance(double p) { return unit() < p; }
    float uniform(float lo, float hi) { return lo + (hi - lo) * (float)unit(); }

private:
    uint64_t s_;
};

// A seed for one stream: the run's seed mixed with names (routine, and the
// variant for the ABI garbage), so each stream is independent of which
// other routines or variants run: `--variant X --function F` sees the
// inputs the full run saw.
uint64_t stream_seed(uint64_t seed, const std::string &a, const std::string &b = "");

// BYTES of storage at OFFSET from a 64-byte boundary, with guard zones
// before and after filled with a seeded pattern: a write below the start
// or past the documented bound is caught, and the byte it hit is named.
class GuardedBuffer {
public:
    static constexpr size_t kGuard = 64;

    GuardedBuffer(size_t bytes, size_t offset, uint8_t pattern);
    uint8_t *data() { return data_; }
    const uint8_t *data() const { return data_; }
    template <class T> T *as() { return reinterpret_cast<T *>(data_); }
    size_t size() const { return bytes_; }
    // "" when both guards hold, else where the first changed byte lies:
    // "3 bytes before the start" or "at byte 12 past the bound".
    std::string guard_damage() const;

private:
    std::vector<uint8_t> storage_;
    uint8_t *data_;
    size_t bytes_;
    uint8_t pattern_;
};

// Offsets from a 64-byte boundary that satisfy ALIGNMENT for elements of
// ELEMENT bytes: every such position in a 16-byte vector, or, for
// alignments of 16 and more, every aligned slot of a 64-byte line.
std::vector<size_t> allowed_offsets(unsigned alignment, unsigned element);

} // namespace svcheck
