/* A standalone check of the four faithful SSE2 ports built as elf32 cdecl
 * (asm/count_facing_sse2.asm, count_facing_cull_sse2.asm,
 * create_sil_triangles_sse2.asm, create_cap_triangles_sse2.asm), against the
 * C reference (src/core/ref/reference_paper.c), without GoogleTest or CMake: see
 * tests/checkasm/x86_32/run.sh. Prints one line per routine; exit 1 on a mismatch. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "shadowvol.h"

int sv_count_facing_sse2_paper(const uint8_t *facing, int numTriangles);
int sv_count_facing_cull_sse2_paper(uint8_t *facing, int numTriangles, const int *indices,
                                    const uint8_t *cullBits);
int sv_create_sil_triangles_sse2_paper(int *shadowIndices, const uint8_t *facing,
                                       const SilEdge *silEdges, int numSilEdges);
int sv_create_cap_triangles_sse2_paper(int *shadowIndices, const uint8_t *facing,
                                       const int *indices, int numIndices);

static uint32_t rng = 12345;
static uint32_t next(void) {
    rng = rng * 1664525u + 1013904223u;
    return rng >> 8;
}

int main(void) {
    enum { MAXT = 3000, NV = 500 };
    static uint8_t facing_a[MAXT + 64] __attribute__((aligned(16)));
    static uint8_t facing_b[MAXT + 64] __attribute__((aligned(16)));
    static int indices[3 * MAXT] __attribute__((aligned(16))); /* App. F: movdqa */
    static SilEdge edges[MAXT];
    static int out_a[6 * MAXT + 8] __attribute__((aligned(16)));
    static int out_b[6 * MAXT + 8] __attribute__((aligned(16)));
    static uint8_t cull[NV];
    int fails = 0, cases = 0;
    const int sizes[] = {0, 1, 3, 4, 15, 16, 17, 255, 256, 257, 1000, 1344, MAXT};
    for (unsigned s = 0; s < sizeof sizes / sizeof sizes[0]; s++) {
        int n = sizes[s];
        for (int i = 0; i < n; i++) facing_a[i] = next() & 1;
        int want = sv_count_facing_c_ref(facing_a, n);
        int got = sv_count_facing_sse2_paper(facing_a, n);
        cases++;
        if (got != want) {
            printf("count_facing n=%d: %d, want %d\n", n, got, want);
            fails++;
        }

        for (int i = 0; i < 3 * n; i++) indices[i] = (int)(next() % NV);
        for (int v = 0; v < NV; v++)
            cull[v] = (uint8_t)((next() & 3) ? next() & 0x7F
                                             : 0); /* bits 0-6: the listing's contract */
        memcpy(facing_b, facing_a, sizeof facing_a);
        want = sv_count_facing_cull_c_ref(facing_a, n, indices, cull);
        got = sv_count_facing_cull_sse2_paper(facing_b, n, indices, cull);
        cases++;
        if (got != want || memcmp(facing_a, facing_b, (size_t)n + 1) != 0) {
            printf("count_facing_cull n=%d: %d, want %d (or facing differs)\n", n, got, want);
            fails++;
        }

        /* App. E: n edges over the n facing bytes (v1, v2 even: doubled). */
        for (int i = 0; i < n; i++) {
            edges[i].p1 = (int)(next() % (unsigned)n);
            edges[i].p2 = (int)(next() % (unsigned)n);
            edges[i].v1 = 2 * (int)(next() % NV);
            edges[i].v2 = 2 * (int)(next() % NV);
        }
        want = sv_create_sil_triangles_c_ref(out_a, facing_a, edges, n);
        got = sv_create_sil_triangles_sse2_paper(out_b, facing_a, edges, n);
        cases++;
        if (got != want || memcmp(out_a, out_b, (size_t)want * sizeof(int)) != 0) {
            printf("create_sil_triangles n=%d: %d, want %d (or indices differ)\n", n, got, want);
            fails++;
        }

        /* App. F: n triangles, 3n indices (16-byte aligned), facing 0 / 1. */
        want = sv_create_cap_triangles_c_ref(out_a, facing_a, indices, 3 * n);
        got = sv_create_cap_triangles_sse2_paper(out_b, facing_a, indices, 3 * n);
        cases++;
        if (got != want || memcmp(out_a, out_b, (size_t)want * sizeof(int)) != 0) {
            printf("create_cap_triangles n=%d: %d, want %d (or indices differ)\n", n, got, want);
            fails++;
        }
    }
    printf("x86-32 SSE2 ports: %d cases, %d failed\n", cases, fails);
    return fails != 0;
}
