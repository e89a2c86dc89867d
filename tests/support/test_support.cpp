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
    std::string t = "seed " + std::to_string(seed()) +
                    " (reproduce with SV_TEST_SEED=" + std::to_string(seed());
    // and the test alone, one variant's instance of it included
    if (const ::testing::TestInfo *info = ::testing::UnitTest::GetInstance()->current_test_info())
        t += std::string(" --gtest_filter=") + info->test_suite_name() + "." + info->name();
    return t + ")";
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
        if (in_this_run(all[i].isa, all[i].name)) out.push_back(&all[i]);
    }
    return out;
}

// The names of a table of variants (sv_variants, sv_facing_variants).
template <class T> static std::vector<std::string> names_of(const T *(*table)(int *)) {
    int n = 0;
    const T *all = table(&n);
    std::vector<std::string> out;
    for (int i = 0; i < n; i++) out.push_back(all[i].name);
    return out;
}

std::vector<std::string> variant_names() { return names_of(sv_variants); }
std::vector<std::string> facing_variant_names() { return names_of(sv_facing_variants); }

std::string param_name(const ::testing::TestParamInfo<std::string> &info) { return info.param; }

// The instance's own stream for the checker's garbage: named by the whole
// name, variant included.
static Rng instance_rng() {
    const ::testing::TestInfo *info = ::testing::UnitTest::GetInstance()->current_test_info();
    return rng_for((std::string(info->test_suite_name()) + "." + info->name()).c_str());
}

void VariantTest::SetUp() {
    const std::string &name = GetParam();
    abi = instance_rng();
    v = sv_variant_by_name(name.c_str());
    if (!v) {
        if (variant_built_here(name.c_str()))
            FAIL() << "no variant " << name << " in sv_variants()";
        GTEST_SKIP() << "variant " << name << ": not built on this platform (docs/PLATFORMS.md)";
    }
    const std::string why = isa_missing(v->isa);
    if (!why.empty()) GTEST_SKIP() << "variant " << name << ": " << why;
}

void FacingVariantTest::SetUp() {
    const std::string &name = GetParam();
    abi = instance_rng();
    v = sv_facing_variant_by_name(name.c_str());
    ASSERT_NE(v, nullptr) << "no facing variant " << name;
    const std::string why = isa_missing(v->isa);
    if (!why.empty()) GTEST_SKIP() << "facing variant " << name << ": " << why;
}

bool stop_after_failures(int limit) {
    const ::testing::TestResult *r =
        ::testing::UnitTest::GetInstance()->current_test_info()->result();
    if (r->total_part_count() < limit) return false;
    ADD_FAILURE() << "stopped at " << r->total_part_count() << " failures (the limit is " << limit
                  << "): the remaining cases did not run";
    return true;
}

#if defined(__linux__)
HugeSilEdgeArray::HugeSilEdgeArray(size_t edges) : edges_(edges), bytes_(edges * sizeof(SilEdge)) {
    const size_t chunk = 2u << 20;
    if (bytes_ == 0 || bytes_ % chunk != 0) return;
    const size_t chunks = bytes_ / chunk;
    void *base = mmap(nullptr, bytes_, PROT_NONE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1,
                      0);
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
