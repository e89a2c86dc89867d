// The slow exact reference for the facing predicate's tests
// (test_accuracy.cpp, test_extremes.cpp): the same determinant
//   det = ((p1 - p0) x (p2 - p0)) . ((x, y, z) - w p0)
// in plain big-integer arithmetic, with nothing in common with the
// library's expansion arithmetic.
//
// Every float is an integer multiple of 2^-149 (the smallest subnormal),
// below 2^128 in magnitude: f * 2^149 is an integer of at most 277 bits,
// computed exactly in double (a power-of-two scaling). The differences are
// integers at scale 2^-149, w p0 at scale 2^-298 (so the light's components
// are shifted by 149 bits to match), and det is their integer polynomial;
// its sign is the answer. Sign-magnitude, base 2^32 limbs, schoolbook
// multiplication: a few microseconds per determinant.
//
// Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "shadowvol.h"

namespace svtest {

class BigInt {
public:
    BigInt() = default;

    // f * 2^149 for a finite float f.
    static BigInt from_float_scaled(float f) {
        BigInt r;
        double v = std::ldexp((double)f, 149); // an integer below 2^277, exact
        if (v < 0) {
            r.neg_ = true;
            v = -v;
        }
        // v = m * 2^e with m an integer of at most 53 bits.
        int e = 0;
        const double fr = std::frexp(v, &e);
        if (fr == 0.0) return r;
        uint64_t m = (uint64_t)std::ldexp(fr, 53);
        e -= 53;
        while (e < 0) { // v is an integer: the shifted-out bits are zero
            m >>= 1;
            e++;
        }
        r.mag_ = {(uint32_t)m, (uint32_t)(m >> 32)};
        r.trim();
        return r.shl(e);
    }

    // d * 2^shift for a finite double d whose lowest set bit is at or
    // above 2^-shift (so the result is an integer).
    static BigInt from_double_scaled(double d, int shift) {
        BigInt r;
        if (d == 0.0) return r;
        if (d < 0) {
            r.neg_ = true;
            d = -d;
        }
        int e = 0;
        uint64_t m = (uint64_t)std::ldexp(std::frexp(d, &e), 53);
        e -= 53; // d = m * 2^e
        e += shift;
        while (e < 0) { // drop trailing zero bits (d * 2^shift is an integer)
            m >>= 1;
            e++;
        }
        r.mag_ = {(uint32_t)m, (uint32_t)(m >> 32)};
        r.trim();
        return r.shl(e);
    }

    BigInt shl(int bits) const {
        BigInt r;
        r.neg_ = neg_;
        const int limbs = bits / 32, rest = bits % 32;
        r.mag_.assign(mag_.size() + (std::size_t)limbs + 1, 0);
        for (std::size_t i = 0; i < mag_.size(); i++) {
            const uint64_t x = (uint64_t)mag_[i] << rest;
            r.mag_[i + (std::size_t)limbs] |= (uint32_t)x;
            r.mag_[i + (std::size_t)limbs + 1] |= (uint32_t)(x >> 32);
        }
        r.trim();
        return r;
    }

    friend BigInt operator*(const BigInt &a, const BigInt &b) {
        BigInt r;
        if (a.mag_.empty() || b.mag_.empty()) return r;
        r.mag_.assign(a.mag_.size() + b.mag_.size(), 0);
        for (std::size_t i = 0; i < a.mag_.size(); i++) {
            uint64_t carry = 0;
            for (std::size_t j = 0; j < b.mag_.size(); j++) {
                const uint64_t t = (uint64_t)a.mag_[i] * b.mag_[j] + r.mag_[i + j] + carry;
                r.mag_[i + j] = (uint32_t)t;
                carry = t >> 32;
            }
            r.mag_[i + b.mag_.size()] = (uint32_t)carry;
        }
        r.neg_ = a.neg_ != b.neg_;
        r.trim();
        return r;
    }

    friend BigInt operator+(const BigInt &a, const BigInt &b) {
        if (a.neg_ == b.neg_) {
            BigInt r = add_mag(a, b);
            r.neg_ = a.neg_;
            r.trim();
            return r;
        }
        // Different signs: subtract the smaller magnitude.
        const int c = cmp_mag(a, b);
        if (c == 0) return BigInt();
        BigInt r = c > 0 ? sub_mag(a, b) : sub_mag(b, a);
        r.neg_ = c > 0 ? a.neg_ : b.neg_;
        r.trim();
        return r;
    }

    friend BigInt operator-(const BigInt &a, const BigInt &b) {
        BigInt nb = b;
        if (!nb.mag_.empty()) nb.neg_ = !nb.neg_;
        return a + nb;
    }

    int sign() const { return mag_.empty() ? 0 : neg_ ? -1 : 1; }
    bool operator==(const BigInt &o) const { return neg_ == o.neg_ && mag_ == o.mag_; }

private:
    void trim() {
        while (!mag_.empty() && mag_.back() == 0) mag_.pop_back();
        if (mag_.empty()) neg_ = false;
    }
    static int cmp_mag(const BigInt &a, const BigInt &b) {
        if (a.mag_.size() != b.mag_.size()) return a.mag_.size() < b.mag_.size() ? -1 : 1;
        for (std::size_t i = a.mag_.size(); i-- > 0;) {
            if (a.mag_[i] != b.mag_[i]) return a.mag_[i] < b.mag_[i] ? -1 : 1;
        }
        return 0;
    }
    static BigInt add_mag(const BigInt &a, const BigInt &b) {
        BigInt r;
        const std::size_t n = std::max(a.mag_.size(), b.mag_.size());
        r.mag_.assign(n + 1, 0);
        uint64_t carry = 0;
        for (std::size_t i = 0; i < n; i++) {
            const uint64_t t = (uint64_t)(i < a.mag_.size() ? a.mag_[i] : 0) +
                               (i < b.mag_.size() ? b.mag_[i] : 0) + carry;
            r.mag_[i] = (uint32_t)t;
            carry = t >> 32;
        }
        r.mag_[n] = (uint32_t)carry;
        return r;
    }
    static BigInt sub_mag(const BigInt &a, const BigInt &b) { // |a| >= |b|
        BigInt r;
        r.mag_.assign(a.mag_.size(), 0);
        int64_t borrow = 0;
        for (std::size_t i = 0; i < a.mag_.size(); i++) {
            int64_t t = (int64_t)a.mag_[i] - (i < b.mag_.size() ? b.mag_[i] : 0) - borrow;
            borrow = t < 0;
            if (t < 0) t += (int64_t)1 << 32;
            r.mag_[i] = (uint32_t)t;
        }
        return r;
    }

    bool neg_ = false;
    std::vector<uint32_t> mag_; // little-endian
};

// sign(det) for finite input, by big integers: +1 facing, 0 on the plane or
// zero area, -1 behind (the convention of shadowvol_accuracy.h).
inline int reference_facing_sign(const float p0[3], const float p1[3], const float p2[3],
                                 const Vec4 &l) {
    BigInt u[3], v[3], r[3];
    const float lc[3] = {l.x, l.y, l.z};
    const BigInt w = BigInt::from_float_scaled(l.w);
    for (int i = 0; i < 3; i++) {
        const BigInt a = BigInt::from_float_scaled(p0[i]);
        u[i] = BigInt::from_float_scaled(p1[i]) - a; // scale 2^-149
        v[i] = BigInt::from_float_scaled(p2[i]) - a;
        r[i] = BigInt::from_float_scaled(lc[i]).shl(149) - w * a; // scale 2^-298
    }
    // u . (v x r)
    const BigInt det = u[0] * (v[1] * r[2] - v[2] * r[1]) + u[1] * (v[2] * r[0] - v[0] * r[2]) +
                       u[2] * (v[0] * r[1] - v[1] * r[0]);
    return det.sign();
}

// The same for coordinates that are integers below 2^20 in magnitude (the
// light's w too): det fits __int128 (|det| < 6 * 2^21 * 2^21 * 2^42).
inline int reference_facing_sign_int128(const float p0[3], const float p1[3], const float p2[3],
                                        const Vec4 &l) {
    const float lc[3] = {l.x, l.y, l.z};
    __int128 u[3], v[3], r[3];
    for (int i = 0; i < 3; i++) {
        u[i] = (__int128)((int64_t)p1[i] - (int64_t)p0[i]);
        v[i] = (__int128)((int64_t)p2[i] - (int64_t)p0[i]);
        r[i] = (__int128)((int64_t)lc[i] - (int64_t)l.w * (int64_t)p0[i]);
    }
    const __int128 det = u[0] * (v[1] * r[2] - v[2] * r[1]) + u[1] * (v[2] * r[0] - v[0] * r[2]) +
                         u[2] * (v[0] * r[1] - v[1] * r[0]);
    return (det > 0) - (det < 0);
}

} // namespace svtest
