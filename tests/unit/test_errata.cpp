// One test per fixed erratum and per hidden limit of the printed listings
// (docs/ERRATA.md gives each the same ID). A fix test fails without the fix;
// a limit test pins the faithful behaviour so a change to it is noticed.
//
// Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
#include "test_support.h"

#include "mman_compat.h"

#if !defined(_WIN32)
#include <sys/wait.h> // the death tests' signal checks (Linux only)
#endif

#include <climits>
#include <csignal>

using namespace svtest;

// sse2_paper's own errata: where the platform has the SSE2 ports
// (SV_HAVE_ASM_SSE2, docs/PLATFORMS.md).
#if defined(SV_HAVE_ASM_SSE2)
namespace {

const sv_variant &paper() {
    const sv_variant *v = sv_variant_by_name("sse2_paper");
    EXPECT_NE(v, nullptr);
    return *v;
}

// `bytes` of memory whose last byte is the last byte before an unmapped
// page: reading one byte further faults.
class PageEndBuffer {
public:
    explicit PageEndBuffer(size_t bytes) {
        page_ = (size_t)sysconf(_SC_PAGESIZE);
        size_t pages = (bytes + page_ - 1) / page_ + 1;
        map_len_ = pages * page_;
        map_ = (uint8_t *)mmap(nullptr, map_len_, PROT_READ | PROT_WRITE,
                               MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
        EXPECT_NE(map_, MAP_FAILED);
        EXPECT_EQ(mprotect(map_ + map_len_ - page_, page_, PROT_NONE), 0);
        data_ = map_ + map_len_ - page_ - bytes;
    }
    ~PageEndBuffer() { munmap(map_, map_len_); }
    uint8_t *data() { return data_; }

private:
    size_t page_, map_len_;
    uint8_t *map_, *data_;
};

} // namespace

// C-2: appendix C jumps to `done` for numTriangles == 0 before anything is
// stored to its stack array n, and returns n[0]+n[1]+n[2]+n[3] of
// uninitialised memory. The port zeroes the accumulator first. The
// trampoline fills every xmm register with fresh garbage on each call.
TEST(Errata, C2_CountFacingOfZeroTrianglesIsZero) {
    Rng rng = rng_for("Errata.C2");
    uint8_t facing[16] __attribute__((aligned(16))) = {1, 1, 1, 1};
    for (int i = 0; i < 100; i++) {
        EXPECT_EQ(checked_call(rng, paper().count_facing, facing, 0), 0);
    }
}

// D-3: appendix D's `test eax, eax; jz done` skips `pxor xmm5, xmm5`, and
// `done` stores xmm5 as the result: whatever the caller left there.
TEST(Errata, D3_CountFacingCullOfZeroTrianglesIsZero) {
    Rng rng = rng_for("Errata.D3");
    uint8_t facing[4] = {1, 1, 1, 1}, cull[4] = {1, 1, 1, 1};
    int indices[3] = {0, 1, 2};
    for (int i = 0; i < 100; i++) {
        EXPECT_EQ(checked_call(rng, paper().count_facing_cull, facing, 0, indices, cull), 0);
    }
}

// E-1 / F-2: with no edges (no indices) appendices E and F jump to `done`
// before `shr ebx, 3`, where `shl ebx, 3` turns the raw pointer into
// pointer * 8: the returned count is (7 * pointer) / 4, not 0.
TEST(Errata, E1_SilTrianglesOfZeroEdgesIsZero) {
    Rng rng = rng_for("Errata.E1");
    int out[8] __attribute__((aligned(16)));
    uint8_t facing[2] = {0, 1};
    SilEdge edge = {0, 1, 0, 2};
    EXPECT_EQ(checked_call(rng, paper().create_sil_triangles, out, facing, &edge, 0), 0);
}

TEST(Errata, F2_CapTrianglesOfZeroIndicesIsZero) {
    Rng rng = rng_for("Errata.F2");
    int out[8] __attribute__((aligned(16)));
    int indices[4] __attribute__((aligned(16))) = {0, 1, 2, 0};
    uint8_t facing[1] = {0};
    EXPECT_EQ(checked_call(rng, paper().create_cap_triangles, out, facing, indices, 0), 0);
}

// F-3: appendix F's one-triangle loop loads the triangle with
// `movdqu xmm0, [edi+edx*4]`: 16 bytes for 12, so the last triangle reads 4
// bytes past the end of indices. With indices 16-byte aligned (the listing's
// contract) those 4 bytes always share the aligned 16-byte block of the
// array's last bytes, so they never cross a page and cannot fault: the read
// is "only" outside the object (undefined behaviour, flagged by memory
// checkers). It faults for a call of 1 to 3 triangles (the four-triangle
// loop and its movdqa never run) whose array ends at an unmapped page. The
// port loads 8 + 4 bytes and reads nothing past the array in any case.
TEST(Errata, F3_CapTrianglesTailReadsNothingPastIndices) {
    Rng rng = rng_for("Errata.F3");
    for (int tris = 1; tris <= 3; tris++) {
        const size_t bytes = (size_t)tris * 3 * sizeof(int);
        PageEndBuffer page(bytes);
        int *indices = (int *)page.data();
        ASSERT_EQ((uintptr_t)(indices + 3 * tris) % sysconf(_SC_PAGESIZE), (uintptr_t)0);
        for (int i = 0; i < 3 * tris; i++) indices[i] = 5 * i + 1;
        std::vector<uint8_t> facing((size_t)tris, 0);
        std::vector<int> out((size_t)6 * tris), expected((size_t)6 * tris);
        int n = checked_call(rng, paper().create_cap_triangles, out.data(), facing.data(), indices,
                             3 * tris);
        int e = sv_create_cap_triangles_c_ref(expected.data(), facing.data(), indices, 3 * tris);
        EXPECT_EQ(n, e);
        EXPECT_EQ(out, expected) << "tris=" << tris;
    }
}

// E-2 / F-4: both listings keep the output pointer / 8 in ebx and return
// `(num - (int)shadowIndexes) >> 2`. The 32-bit difference is harmless (it
// wraps alike on both sides), but a port that kept pointer / 8 in a 32-bit
// register would store to a truncated address. Here the output is mapped
// above 4 GiB explicitly: stores and count must still be right.
TEST(Errata, E2F4_CountsAreRightForOutputAbove4GiB) {
    if (UINTPTR_MAX <= 0xFFFFFFFFu) GTEST_SKIP() << "no addresses above 4 GiB in a 32-bit process";
    Rng rng = rng_for("Errata.E2F4");
    const size_t len = 1 << 16;
    void *hint = (void *)(uintptr_t)0x7e0000000000ull;
    int *out = (int *)mmap(hint, len, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    ASSERT_NE((void *)out, MAP_FAILED);
    ASSERT_GT((uintptr_t)out, (uintptr_t)0xFFFFFFFFull);
    uint8_t facing[5] = {1, 0, 0, 1, 1};
    SilEdge edges[3] = {{0, 1, 0, 2}, {1, 2, 2, 4}, {2, 3, 4, 6}};
    EXPECT_EQ(checked_call(rng, paper().create_sil_triangles, out, facing, edges, 3), 12);
    alignas(16) int indices[12] = {0, 1, 2, 2, 1, 3, 3, 1, 4, 4, 1, 0};
    EXPECT_EQ(checked_call(rng, paper().create_cap_triangles, out, facing, indices, 12), 12);
    munmap(out, len);
}

// LIMIT D-5 (kept): appendix D's four-triangle loop tests the AND of the
// cull bytes with the SIGNED pcmpgtb against zero, so a triangle whose
// vertices share only bit 7 (c = 0x80) is not culled there, while its
// one-triangle tail (neg; shr 31) and the C cull it. Triangles 0-3 run in
// the four-triangle loop, triangle 4 in the tail.
TEST(Errata, D5_Limit_SignedCompareIgnoresBit7InFourTriangleLoop) {
    Rng rng = rng_for("Errata.D5");
    uint8_t cull[3] = {0x80, 0x80, 0x80};
    int indices[15] = {0, 1, 2, 0, 1, 2, 0, 1, 2, 0, 1, 2, 0, 1, 2};
    uint8_t facing[5] = {0, 0, 0, 0, 0};
    int n = checked_call(rng, paper().count_facing_cull, facing, 5, indices, cull);
    EXPECT_EQ(n, 1);
    const uint8_t expected_paper[5] = {0, 0, 0, 0, 1};
    EXPECT_EQ(0, memcmp(facing, expected_paper, 5));

    uint8_t ref_facing[5] = {0, 0, 0, 0, 0};
    EXPECT_EQ(sv_count_facing_cull_c_ref(ref_facing, 5, indices, cull), 5);
    // Bits 0..6 behave the same in both: 0x40 is culled everywhere.
    uint8_t cull40[3] = {0x40, 0xC0, 0x7F};
    uint8_t facing2[5] = {0, 0, 0, 0, 0};
    EXPECT_EQ(checked_call(rng, paper().count_facing_cull, facing2, 5, indices, cull40), 5);
}

// LIMIT C-3 (kept): facing bytes must be 0 or 1. paddusb saturates each
// byte lane at 255, so 256 bytes of 0xFF (16 per lane in the 256-byte loop)
// count as 16 * 255, where the branchless C sums 256 * 255 and the paper's
// C counts 256 non-zero bytes.
TEST(Errata, C3_Limit_FacingBytesAboveOneSaturate) {
    Rng rng = rng_for("Errata.C3");
    alignas(16) uint8_t facing[256];
    memset(facing, 0xFF, sizeof facing);
    EXPECT_EQ(checked_call(rng, sv_count_facing_sse2_paper, facing, 256), 16 * 255);
    EXPECT_EQ(checked_call(rng, sv_count_facing_c_branchless, facing, 256), 256 * 255);
    EXPECT_EQ(checked_call(rng, sv_count_facing_c_ref, facing, 256), 256);
}

// LIMIT E-4 (kept): the xor trick needs even (doubled) vertex numbers. With
// an odd v the paper's C writes v + 1, the xor variants v - 1. The checked
// entry point refuses such edges (test_contracts.cpp).
TEST(Errata, E4_Limit_OddVertexNumbersBreakTheXorTrick) {
    Rng rng = rng_for("Errata.E4");
    uint8_t facing[2] = {1, 0};
    SilEdge edge = {0, 1, 3, 5};
    alignas(16) int ref[6], fast[6];
    ASSERT_EQ(sv_create_sil_triangles_c_ref(ref, facing, &edge, 1), 6);
    ASSERT_EQ(checked_call(rng, sv_create_sil_triangles_sse2_paper, fast, facing, &edge, 1), 6);
    EXPECT_EQ(ref[1], 6);  // v2 + 1
    EXPECT_EQ(fast[1], 4); // v2 ^ 1
}

// LIMIT E-5 / F-5 (kept): the output pointer is kept as pointer / 8, so an
// output that is only 4-byte aligned is written from 4 bytes BEFORE it.
// The header's contract asks for 8; the checked entry points refuse less.
TEST(Errata, E5F5_Limit_OutputBelow8ByteAlignmentWritesBeforeIt) {
    Rng rng = rng_for("Errata.E5F5");
    const svtest::IsaLimitLifted lifted; // a named variant's contract
    uint8_t facing[2] = {1, 0};
    SilEdge edge = {0, 1, 2, 4};
    GuardedBuffer out(6 * sizeof(int), 4); // 4 mod 8
    ASSERT_EQ((uintptr_t)out.data() % 8, (uintptr_t)4);
    int n = checked_call(rng, sv_create_sil_triangles_sse2_paper, out.as<int>(), facing, &edge, 1);
    EXPECT_EQ(n, 5); // (24 bytes written from start - 4) / 4: one index short
    EXPECT_FALSE(out.guards_intact()) << "the 4 bytes before the output were written";
    GuardedBuffer out2(6 * sizeof(int), 4);
    EXPECT_EQ(sv_create_sil_triangles_checked(&paper(), out2.as<int>(), 6, facing, 1, &edge, 1),
              SV_E_ALIGNMENT);
    EXPECT_TRUE(out2.guards_intact());
}

#endif // SV_HAVE_ASM_SSE2

namespace {

// A page that faults on any access: a routine given it must not touch it.
class NoAccessPage {
public:
    NoAccessPage() {
        len_ = (size_t)sysconf(_SC_PAGESIZE);
        p_ = mmap(nullptr, len_, PROT_NONE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
        EXPECT_NE(p_, MAP_FAILED);
    }
    ~NoAccessPage() { munmap(p_, len_); }
    template <class T> T *as() { return (T *)p_; }

private:
    void *p_;
    size_t len_;
};

const int kHugeNegativeCounts[] = {
    INT32_MIN, INT32_MIN + 1, INT32_MIN + 100, INT32_MIN + 255, INT32_MIN + 256, -1000, -256, -17,
    -1};

} // namespace

// The errata whose fix every variant must keep (negative counts), once per
// variant: Variants/ErrataVariants.<ID>_.../<variant>.
class ErrataVariants : public VariantTest {};

INSTANTIATE_TEST_SUITE_P(Variants, ErrataVariants, ::testing::ValuesIn(variant_names()),
                         param_name);

// C-7: appendix C tests only `jz done`; for a count in [INT_MIN,
// INT_MIN + 255], `sub eax, 256` and `add eax, 256 - 16` overflow and the
// 16- and 4-byte loops read about 2^28 bytes. The port exits on <= 0. The
// facing pointer is a no-access page: any read faults.
TEST_P(ErrataVariants, C7_HugeNegativeCountsReadNothing) {
    NoAccessPage page;
    for (int n : kHugeNegativeCounts) {
        EXPECT_EQ(checked_call(abi, v->count_facing, page.as<uint8_t>(), n), 0)
            << v->name << " n=" << n;
    }
}

// D-7: appendix D's `neg eax` leaves INT_MIN negative, so `add eax, 4` /
// `jg run1` falls into the loop, which walks ~2^29 triangles. The port
// negates in 64 bits. Every array is a no-access page.
TEST_P(ErrataVariants, D7_HugeNegativeCountsTouchNothing) {
    NoAccessPage page;
    for (int n : kHugeNegativeCounts) {
        EXPECT_EQ(checked_call(abi, v->count_facing_cull, page.as<uint8_t>(), n, page.as<int>(),
                               page.as<uint8_t>()),
                  0)
            << v->name << " n=" << n;
    }
}

// Negative counts for the writers: nothing read, nothing written, 0 back.
TEST_P(ErrataVariants, NegativeCountsWriteNothing) {
    NoAccessPage page;
    for (int n : kHugeNegativeCounts) {
        EXPECT_EQ(checked_call(abi, v->create_sil_triangles, page.as<int>(), page.as<uint8_t>(),
                               page.as<SilEdge>(), n),
                  0)
            << v->name << " n=" << n;
        EXPECT_EQ(checked_call(abi, v->create_cap_triangles, page.as<int>(), page.as<uint8_t>(),
                               page.as<int>(), n),
                  0)
            << v->name << " n=" << n;
    }
}

#if defined(SV_HAVE_ASM_SSE2)
// E-3: appendix E computes 16 * numSilEdges with `shl eax, 4`, which wraps
// to a negative offset at 2^27 edges (and to 0, "no edges", at 2^28). Here
// 2^27 edges: 2 GiB of address space built from one zeroed 2 MiB memfd
// mapped 1023 times (edges {0, 0, 0, 0}: never a silhouette) plus a private
// last chunk whose final edge is a silhouette edge. The port must find it.
TEST(Errata, E3_TwoToThe27EdgesDoNotWrapTheOffset) {
    Rng rng = rng_for("Errata.E3");
    const size_t edges = (size_t)1 << 27;
    if (!HugeSilEdgeArray::available())
        GTEST_SKIP() << "needs 2 GiB of memfd mappings (Linux x86-64)";
    HugeSilEdgeArray huge(edges);
    ASSERT_TRUE(huge.ok());
    SilEdge *e = huge.data();
    e[edges - 1] = SilEdge{0, 1, 4, 6};
    uint8_t facing[2] = {0, 1};
    alignas(16) int out[12];
    const int n = (int)edges;
    EXPECT_EQ(checked_call(rng, sv_create_sil_triangles_sse2_paper, out, facing, e, n), 6);
    const int expected[6] = {4, 6, 7, 5, 4, 7};
    EXPECT_EQ(0, memcmp(out, expected, sizeof expected));
}
#endif // SV_HAVE_ASM_SSE2

// C-7 / D-7, every count from INT_MIN to INT_MIN + 300 (the listings break
// on the first 256 of them in C and the first 5 in D, each in its own way:
// see docs/ERRATA.md), for every variant: 0 back, nothing touched.
TEST_P(ErrataVariants, C7D7_EveryCountNearIntMinTouchesNothing) {
    NoAccessPage page;
    for (int k = 0; k <= 300; k++) {
        const int n = INT32_MIN + k;
        EXPECT_EQ(checked_call(abi, v->count_facing, page.as<uint8_t>(), n), 0)
            << v->name << " count_facing n=INT_MIN+" << k;
        EXPECT_EQ(checked_call(abi, v->count_facing_cull, page.as<uint8_t>(), n, page.as<int>(),
                               page.as<uint8_t>()),
                  0)
            << v->name << " count_facing_cull n=INT_MIN+" << k;
    }
}

#if defined(SV_HAVE_ASM_SSE2)
// LIMIT D-5 (kept), for every count 1..12: the four-triangle loop runs over
// the first n - n % 4 triangles, the one-triangle tail over the LAST n % 4;
// with cull bytes sharing only bit 7 exactly the tail's triangles are culled.
TEST(Errata, D5_Limit_OnlyTheLastNMod4TrianglesAreCulled) {
    Rng rng = rng_for("Errata.D5EveryCount");
    uint8_t cull[3] = {0x80, 0x80, 0x80};
    std::vector<int> indices;
    for (int t = 0; t < 12; t++) indices.insert(indices.end(), {0, 1, 2});
    for (int n = 1; n <= 12; n++) {
        std::vector<uint8_t> facing((size_t)n + 1, 0), ref((size_t)n + 1, 0);
        EXPECT_EQ(checked_call(rng, sv_count_facing_cull_sse2_paper, facing.data(), n,
                               indices.data(), cull),
                  n % 4)
            << "n=" << n;
        for (int t = 0; t < n; t++) {
            EXPECT_EQ(facing[(size_t)t], t >= n - n % 4 ? 1 : 0) << "n=" << n << " triangle " << t;
        }
        EXPECT_EQ(sv_count_facing_cull_c_ref(ref.data(), n, indices.data(), cull), n);
    }
}

#if defined(__linux__) && GTEST_HAS_DEATH_TEST
// The child died of the fault: SIGSEGV, or (under AddressSanitizer, whose
// handler reports the SEGV and exits) a non-zero exit.
static bool faulted(int status) {
    return (WIFSIGNALED(status) && WTERMSIG(status) == SIGSEGV) ||
           (WIFEXITED(status) && WEXITSTATUS(status) != 0);
}

// LIMIT C-4 (kept), the raw routine: the 16-byte loops' movdqa / paddusb
// with a memory operand need 16-byte alignment, the 4- and 1-byte loops do
// not. 15 bytes at an odd address count right; 16 fault (SIGSEGV: #GP).
TEST(ErrataDeathTest, C4_Limit_UnalignedFacingFaultsFrom16Bytes) {
    Rng rng = rng_for("ErrataDeathTest.C4");
    alignas(16) uint8_t facing[64];
    memset(facing, 1, sizeof facing);
    EXPECT_EQ(checked_call(rng, sv_count_facing_sse2_paper, facing + 1, 15), 15);
    EXPECT_EXIT(checked_call(rng, sv_count_facing_sse2_paper, facing + 1, 16), faulted, "");
}

// LIMIT F-6 (kept), the raw routine: the walk starts at indices + numIndices
// and counts numIndices / 3 whole triangles back, so for numIndices % 3 != 0
// every triangle is read shifted by numIndices % 3 indices (7 indices: the
// triangles at indices + 1 and + 4); from four triangles on, loop4's movdqa
// meets the misaligned address and faults.
TEST(ErrataDeathTest, F6_Limit_PartialTrianglesShiftEveryTriangle) {
    Rng rng = rng_for("ErrataDeathTest.F6");
    alignas(16) int indices[16];
    for (int i = 0; i < 16; i++) indices[i] = 2 * i;
    uint8_t facing[6] = {0, 0, 0, 0, 0, 1};
    alignas(16) int out[48], shifted[48];
    const int n = checked_call(rng, sv_create_cap_triangles_sse2_paper, out, facing, indices, 7);
    const int e = sv_create_cap_triangles_c_ref(shifted, facing, indices + 1, 6);
    ASSERT_EQ(n, 12);
    ASSERT_EQ(n, e);
    EXPECT_EQ(0, memcmp(out, shifted, sizeof(int) * (size_t)n));
    EXPECT_EXIT(checked_call(rng, sv_create_cap_triangles_sse2_paper, out, facing, indices, 13),
                faulted, "");
}
#endif

// LIMIT E-7 (kept), the raw routine: the output advances by 3 * (f1 ^ f2)
// indices per half of the quad, so a facing byte of 2 against 0 advances
// twice as far: the C writes the edge's 6 indices and returns 6, the
// listing returns 12 (6 of them never written).
TEST(Errata, E7_Limit_FacingByteTwoAdvancesTwice) {
    Rng rng = rng_for("Errata.E7");
    uint8_t facing[3] = {2, 0, 1};
    SilEdge edge = {0, 1, 2, 4};
    alignas(16) int ref[12], fast[12];
    EXPECT_EQ(sv_create_sil_triangles_c_ref(ref, facing, &edge, 1), 6);
    EXPECT_EQ(checked_call(rng, sv_create_sil_triangles_sse2_paper, fast, facing, &edge, 1), 12);
}

// LIMIT F-5 (kept): appendix F keeps its output pointer / 8 as appendix E
// does (its own code, the same trick), so an output 4 mod 8 is written from
// 4 bytes before it and the count comes back one short, in the
// four-triangle loop and in the one-triangle tail alike.
TEST(Errata, F5_Limit_CapOutputBelow8ByteAlignmentWritesBeforeIt) {
    Rng rng = rng_for("Errata.F5");
    const svtest::IsaLimitLifted lifted;
    alignas(16) int indices[12];
    for (int i = 0; i < 12; i++) indices[i] = 2 * i;
    const uint8_t facing12[5] = {0, 1, 0, 0, 1}, facing9[4] = {0, 1, 0, 1};
    for (int numIndices : {12, 9}) { // loop4 + nothing; the tail only
        const uint8_t *facing = numIndices == 12 ? facing12 : facing9;
        alignas(16) int ref[24];
        const int e = sv_create_cap_triangles_c_ref(ref, facing, indices, numIndices);
        GuardedBuffer out((size_t)e * sizeof(int), 4); // 4 mod 8
        ASSERT_EQ((uintptr_t)out.data() % 8, (uintptr_t)4);
        const int n = checked_call(rng, sv_create_cap_triangles_sse2_paper, out.as<int>(), facing,
                                   indices, numIndices);
        EXPECT_EQ(n, e - 1) << "numIndices=" << numIndices;
        EXPECT_FALSE(out.guards_intact()) << "the 4 bytes before the output were written";
        // What lands from 4 bytes before the output is the whole volume.
        EXPECT_EQ(0, memcmp(out.data() - 4, ref, sizeof(int) * (size_t)e));
        GuardedBuffer out2((size_t)e * sizeof(int), 4);
        EXPECT_EQ(sv_create_cap_triangles_checked(&paper(), out2.as<int>(), (size_t)e, facing,
                                                  indices, numIndices, 24),
                  SV_E_ALIGNMENT);
        EXPECT_TRUE(out2.guards_intact());
    }
}

// LIMIT F-9 (kept), the raw routine: paddd x, x doubles in 32 bits, so a
// vertex number of 2^30 or more wraps (2^30 -> INT_MIN); the checked entry
// points refuse numVerts above 2^30 (Contracts.*).
TEST(Errata, F9_Limit_VertexNumbersFrom2To30WrapWhenDoubled) {
    Rng rng = rng_for("Errata.F9");
    alignas(16) int indices[4] = {1 << 30, (1 << 30) + 1, 5, 0};
    const uint8_t facing[2] = {0, 1};
    alignas(16) int out[8];
    ASSERT_EQ(checked_call(rng, sv_create_cap_triangles_sse2_paper, out, facing, indices, 3), 6);
    const int want[6] = {10, INT32_MIN + 2, INT32_MIN, INT32_MIN + 1, INT32_MIN + 3, 11};
    EXPECT_EQ(0, memcmp(out, want, sizeof want));
}
#endif // SV_HAVE_ASM_SSE2
