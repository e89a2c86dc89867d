// Shared test machinery: the seed, the random generator, guarded buffers,
// and calls through the ABI-checking trampoline.
//
// Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
#pragma once

#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "shadowvol.h"
#include "test_conditions.h"
#if defined(SV_HAVE_ABI_CHECKER)
#include "checked_call.h"
#endif

namespace svtest {

// The run's seed: SV_TEST_SEED=<number> reproduces a run, SV_TEST_SEED=random
// draws a fresh one; unset means the fixed default. Printed at start and in
// the trace of every failure.
uint64_t seed();

// xoshiro256** seeded through splitmix64: fast, and the same sequence on
// every platform for a given seed.
class Rng {
public:
    explicit Rng(uint64_t s);
    uint64_t next();
    uint32_t below(uint32_t n); // uniform in [0, n), n > 0
    double unit();              // uniform in [0, 1)
    bool chance(double p) { return unit() < p; }

private:
    uint64_t s_[4];
};

// Lifts the ISA limit (SV_ISA, sv_set_isa_limit) for one scope and puts it
// back: for tests of one named variant's contract, which must check it in
// the ISA-limited runs too (the hardware runs the variant; only dispatch
// is held down there).
class IsaLimitLifted {
public:
    IsaLimitLifted() : saved_(sv_isa_limit_name()) { sv_set_isa_limit(nullptr); }
    ~IsaLimitLifted() { sv_set_isa_limit(saved_); }
    IsaLimitLifted(const IsaLimitLifted &) = delete;
    IsaLimitLifted &operator=(const IsaLimitLifted &) = delete;

private:
    const char *saved_;
};

// 2^27-or-so SilEdges without 2 GiB of memory: one zeroed 2 MiB memfd
// mapped read-only over and over (edges {0, 0, 0, 0}: never a silhouette),
// and a private writable last chunk for the edges a test sets. For offsets
// above 2^31 bytes in the silhouette kernels. EDGES * sizeof(SilEdge) must
// be a multiple of 2 MiB. ok() is false if the mappings failed.
class HugeSilEdgeArray {
public:
    explicit HugeSilEdgeArray(size_t edges);
    ~HugeSilEdgeArray();
    HugeSilEdgeArray(const HugeSilEdgeArray &) = delete;
    HugeSilEdgeArray &operator=(const HugeSilEdgeArray &) = delete;
    bool ok() const { return ok_; }
    // Whether this platform can make one: memfd and 2 GiB of address space
    // (Linux x86-64). Elsewhere the tests that need it skip, by name.
    static constexpr bool available() {
#if defined(__linux__) && UINTPTR_MAX > 0xFFFFFFFFu
        return true;
#else
        return false;
#endif
    }
    SilEdge *data() { return reinterpret_cast<SilEdge *>(base_); }
    size_t size() const { return edges_; }

private:
    size_t edges_, bytes_;
    uint8_t *base_ = nullptr;
    int fd_ = -1;
    bool ok_ = false;
};

// A generator for one test: the run's seed mixed with the test's name, so
// tests do not share a stream and each is reproducible on its own.
Rng rng_for(const char *test_name);

// Trace line naming the seed; use as SCOPED_TRACE(seed_trace()).
std::string seed_trace();

// A byte array at a chosen offset from a 64-byte boundary, with guard bytes
// before and after that must survive every call: a write out of bounds
// (below or above) is caught by guards_intact().
class GuardedBuffer {
public:
    static constexpr size_t kGuard = 256;
    static constexpr uint8_t kPattern = 0xA5;

    GuardedBuffer(size_t bytes, size_t offset);
    uint8_t *data() { return data_; }
    template <class T> T *as() { return reinterpret_cast<T *>(data_); }
    size_t size() const { return bytes_; }
    bool guards_intact() const;
    void fill(uint8_t v) { std::memset(data_, v, bytes_); }

private:
    std::vector<uint8_t> storage_;
    uint8_t *data_;
    size_t bytes_;
};

// ---- ABI-checked calls ---------------------------------------------------

#if defined(SV_HAVE_ABI_CHECKER)
// Fresh random callee-saved canaries and xmm garbage for the next call.
void abi_scramble(Rng &rng);
// Names of the broken promises in a sv_abi_failed bit mask.
std::string abi_failures(uint32_t mask);
#endif

#if defined(SV_HAVE_ABI_CHECKER)
// Calls fn through the trampoline with scrambled registers, the argument
// words built from fn's prototype (svcheck::checked_call: every 32-bit int
// parameter gets a garbage upper half; no test can forget one). Fails the
// current test if the routine broke the ABI.
template <class Fn, class... A, class = std::enable_if_t<svcheck::is_fn_ptr_v<Fn>>>
typename svcheck::fn_traits<Fn>::ret checked_call(Rng &rng, Fn fn, A... args) {
    uint32_t failed = 0;
    struct Fail {
        uint32_t *f;
        ~Fail() { EXPECT_EQ(*f, 0u) << "ABI broken: " << abi_failures(*f); }
    } check{&failed};
    return svcheck::checked_call(rng, &failed, fn, args...);
}

#else
// No checker on this platform (docs/PLATFORMS.md): the routine is called
// directly with its own prototype, so results are still compared.
template <class R, class... P, class... A> R checked_call(Rng &, R (*fn)(P...), A... args) {
    static_assert(sizeof...(P) == sizeof...(A), "checked_call: wrong number of arguments");
    return fn(static_cast<P>(args)...);
}
#endif

// The variants of sv_variants() this ctest entry checks (in_this_run:
// the baseline and the entry's ISA tier, test_conditions.h).
std::vector<const sv_variant *> runnable_variants();

// Whether this platform's build has the named variant at all: the asm
// kernels exist per platform (CMake's SV_ASM_KERNELS, SV_HAVE_ASM_*,
// docs/PLATFORMS.md). A test that names a variant fails if it is missing
// where it is built, and skips it by name where it is not.
bool variant_built_here(const char *name);

// ---- Tests parametrised by variant --------------------------------------
// A TEST_P over a Variant fixture runs once per variant and is named after
// it (Variants/Differential.CountFacing/avx512vbmi): --gtest_filter=*avx512*
// runs those variants' checks alone, and a failing variant hides no other.
// A variant this CPU (or SV_ISA) does not run is still listed, and skipped
// with the reason. Instantiate with
//   INSTANTIATE_TEST_SUITE_P(Variants, Suite, ::testing::ValuesIn(variant_names()),
//                            param_name);

// sv_variants()' names, in table order: every variant built here.
std::vector<std::string> variant_names();
// sv_facing_variants()' names (appendices A and B), in table order.
std::vector<std::string> facing_variant_names();
// gtest's name for an instance: the variant's own.
std::string param_name(const ::testing::TestParamInfo<std::string> &info);

// The fixture of the four kernels' variants (sv_variants()). v is the
// variant; abi is the generator of the checker's garbage, one per instance.
// The cases come from rng_for(name of the test without the variant), so
// every variant sees the same cases, whichever of them the filter runs.
class VariantTest : public ::testing::TestWithParam<std::string> {
protected:
    void SetUp() override;
    const sv_variant *v = nullptr;
    Rng abi{0};
};

// The same over sv_facing_variants().
class FacingVariantTest : public ::testing::TestWithParam<std::string> {
protected:
    void SetUp() override;
    const sv_facing_variant *v = nullptr;
    Rng abi{0};
};

// A loop over thousands of cases checks each with EXPECT, so one failing
// case does not stop the others. Once the test has recorded this many
// failures, this adds one saying the rest were not run and returns true:
// the loop stops there instead of printing thousands of lines that say the
// same. The test has failed either way.
bool stop_after_failures(int limit = 20);

} // namespace svtest

// For a test of sse2_paper's own contract: skipped, by name and reason,
// where the platform has no SSE2 ports.
#if defined(SV_HAVE_ASM_SSE2)
#define SV_REQUIRE_SSE2_PAPER() (void)0
#else
#define SV_REQUIRE_SSE2_PAPER()                                                                    \
    GTEST_SKIP() << "sse2_paper is not built on this platform (docs/PLATFORMS.md)"
#endif

namespace svtest {} // namespace svtest
