// Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
#include "test_support.h"

#include "mman_compat.h"

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <random>

namespace svtest {

static uint64_t splitmix64(uint64_t &x) {
    uint64_t z = (x += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

static uint64_t pick_seed() {
    const char *env = std::getenv("SV_TEST_SEED");
    if (!env || !*env) {
        return 20050408; // the paper's date
    }
    if (std::string(env) == "random") {
        std::random_device rd;
        return ((uint64_t)rd() << 32) ^ rd();
    }
    char *end = nullptr;
    uint64_t s = std::strtoull(env, &end, 0);
    if (*end) {
        std::fprintf(stderr, "SV_TEST_SEED=%s is neither a number nor 'random'\n", env);
        std::exit(2);
    }
    return s;
}

uint64_t seed() {
    static const uint64_t s = [] {
        uint64_t v = pick_seed();
        std::printf("shadowvol tests: seed %llu (reproduce with SV_TEST_SEED=%llu)\n",
                    (unsigned long long)v, (unsigned long long)v);
        return v;
    }();
    return s;
}

std::string seed_trace() {
    return "seed " + std::to_string(seed()) + " (reproduce with SV_TEST_SEED=" +
           std::to_string(seed()) + ")";
}

Rng::Rng(uint64_t s) {
    for (auto &w : s_) w = splitmix64(s);
}

static inline uint64_t rotl(uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

uint64_t Rng::next() {
    uint64_t r = rotl(s_[1] * 5, 7) * 9;
    uint64_t t = s_[1] << 17;
    s_[2] ^= s_[0];
    s_[3] ^= s_[1];
    s_[1] ^= s_[2];
    s_[0] ^= s_[3];
    s_[2] ^= t;
    s_[3] = rotl(s_[3], 45);
    return r;
}

uint32_t Rng::below(uint32_t n) { return (uint32_t)(((next() >> 32) * (uint64_t)n) >> 32); }

double Rng::unit() { return (double)(next() >> 11) * (1.0 / 9007199254740992.0); }

Rng rng_for(const char *test_name) {
    uint64_t h = 1469598103934665603ull; // FNV-1a of the name
    for (const char *p = test_name; *p; p++) h = (h ^ (uint8_t)*p) * 1099511628211ull;
    return Rng(seed() ^ h);
}

GuardedBuffer::GuardedBuffer(size_t bytes, size_t offset)
    : storage_(bytes + offset + 2 * kGuard + 64, kPattern), bytes_(bytes) {
    uintptr_t base = (uintptr_t)storage_.data() + kGuard;
    base = (base + 63) & ~(uintptr_t)63;
    data_ = (uint8_t *)base + offset;
    std::memset(data_, 0, bytes_);
}

bool GuardedBuffer::guards_intact() const {
    const uint8_t *lo = storage_.data();
    const uint8_t *hi = storage_.data() + storage_.size();
    for (const uint8_t *p = lo; p < data_; p++)
        if (*p != kPattern) return false;
    for (const uint8_t *p = data_ + bytes_; p < hi; p++)
        if (*p != kPattern) return false;
    return true;
}

#if defined(SV_HAVE_ABI_CHECKER)
void abi_scramble(Rng &rng) { svcheck::scramble(rng); }

std::string abi_failures(uint32_t mask) {
    char buf[512];
    return sv_abi_failure_names(mask, buf, sizeof buf);
}

#endif

uint64_t int_arg(int v, Rng &rng) {
    uint32_t hi = (uint32_t)rng.next();
    uint32_t sign_ext = v < 0 ? 0xFFFFFFFFu : 0u;
    if (hi == sign_ext) hi ^= 0xDEADBEEFu;
    return ((uint64_t)hi << 32) | (uint32_t)v;
}

#if defined(SV_HAVE_ABI_CHECKER)
int checked_call(Rng &rng, const void *fn, uint64_t a1, uint64_t a2, uint64_t a3, uint64_t a4,
                 uint64_t a5) {
    svcheck::detect_once();
    uintptr_t words[SV_ABI_ARGS] = {a1, a2, a3, a4, a5};
    for (int i = 5; i < SV_ABI_ARGS; i++) words[i] = rng.next();
    abi_scramble(rng);
    sv_abi_failed = 0;
    uint64_t r = sv_abi_checked_call(fn, words);
    EXPECT_EQ(sv_abi_failed, 0u) << "ABI broken: " << abi_failures(sv_abi_failed);
    return (int)(uint32_t)r;
}
#else
// No checker on this platform yet (tests/abi_checked_call.asm is System V
// x86-64 code; docs/platforms.md): the routine is called directly, so the
// results are still compared, but a broken calling convention is caught
// only as far as it corrupts them. Every routine called here takes at most
// five pointer or int arguments and returns int:
//  - Windows x64 passes the first four in rcx, rdx, r8, r9 and the fifth on
//    the stack, each in an 8-byte slot whose upper half an int parameter
//    ignores, so a prototype of five 64-bit integers passes them right;
//  - 32-bit cdecl passes 4-byte stack slots, and the caller pops them, so a
//    prototype of five 32-bit integers (pointers and ints are 32 bits)
//    passes them right, extra ones unread.
int checked_call(Rng &rng, const void *fn, uint64_t a1, uint64_t a2, uint64_t a3, uint64_t a4,
                 uint64_t a5) {
    (void)rng;
#if UINTPTR_MAX > 0xFFFFFFFFu
    using any5 = uint64_t (*)(uint64_t, uint64_t, uint64_t, uint64_t, uint64_t);
    return (int)(uint32_t)reinterpret_cast<any5>(const_cast<void *>(fn))(a1, a2, a3, a4, a5);
#else
    using any5 = uint32_t (*)(uint32_t, uint32_t, uint32_t, uint32_t, uint32_t);
    return (int)reinterpret_cast<any5>(const_cast<void *>(fn))(
        (uint32_t)a1, (uint32_t)a2, (uint32_t)a3, (uint32_t)a4, (uint32_t)a5);
#endif
}
#endif

bool variant_built_here(const char *name) {
    const std::string n = name;
    if (n == "c_ref" || n == "c_branchless") return true;
#if defined(SV_HAVE_ASM_SSE2)
    if (n == "sse2_paper") return true;
#endif
#if defined(SV_HAVE_ASM_AVX2)
    if (n == "avx2") return true;
#endif
#if defined(SV_HAVE_ASM_AVX512)
    if (n == "avx512" || n == "avx512vbmi") return true;
#endif
    return false;
}

std::vector<const sv_variant *> runnable_variants() {
    int n = 0;
    const sv_variant *all = sv_variants(&n);
    std::vector<const sv_variant *> out;
    for (int i = 0; i < n; i++) {
        if ((all[i].isa & sv_cpu_isa()) == all[i].isa) {
            out.push_back(&all[i]);
        } else {
            std::printf("[  SKIPPED ] variant %s: this CPU lacks its instruction set\n",
                        all[i].name);
        }
    }
    return out;
}

#if defined(__linux__)
HugeSilEdgeArray::HugeSilEdgeArray(size_t edges)
    : edges_(edges), bytes_(edges * sizeof(SilEdge)) {
    const size_t chunk = 2u << 20;
    if (bytes_ == 0 || bytes_ % chunk != 0) return;
    const size_t chunks = bytes_ / chunk;
    void *base = mmap(nullptr, bytes_, PROT_NONE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE,
                      -1, 0);
    if (base == MAP_FAILED) return;
    base_ = (uint8_t *)base;
    fd_ = memfd_create("sv_zero_edges", 0);
    if (fd_ < 0 || ftruncate(fd_, (off_t)chunk) != 0) return;
    for (size_t i = 0; i + 1 < chunks; i++) {
        if (mmap(base_ + i * chunk, chunk, PROT_READ, MAP_SHARED | MAP_FIXED, fd_, 0) ==
            MAP_FAILED) {
            return;
        }
    }
    if (mmap(base_ + (chunks - 1) * chunk, chunk, PROT_READ | PROT_WRITE,
             MAP_PRIVATE | MAP_ANONYMOUS | MAP_FIXED, -1, 0) == MAP_FAILED) {
        return;
    }
    ok_ = true;
}

HugeSilEdgeArray::~HugeSilEdgeArray() {
    if (base_) munmap(base_, bytes_);
    if (fd_ >= 0) close(fd_);
}
#else
// memfd_create and MAP_FIXED file mappings are Linux's: elsewhere the array
// is not made, ok() is false and the tests that need it skip.
HugeSilEdgeArray::HugeSilEdgeArray(size_t edges) : edges_(edges), bytes_(0) {}
HugeSilEdgeArray::~HugeSilEdgeArray() {}
#endif

} // namespace svtest
