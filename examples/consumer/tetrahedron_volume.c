/* The example program of docs/API.md, and the C consumer of the installed package (examples/consumer). LGPL-2.1-or-later. */
#include <stdio.h>
#include "shadowvol.h"

int main(void) {
    /* 4 vertices, 4 outward counter-clockwise triangles */
    static const float p[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    _Alignas(16) static const int tri[12] = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
    /* SilEdges: v1 -> v2 counter-clockwise in p1, clockwise in p2; doubled vertex numbers */
    static const SilEdge edges[6] = {{1, 0, 0, 2}, {2, 0, 4, 0}, {3, 0, 2, 4},
                                     {1, 2, 6, 0}, {1, 3, 2, 6}, {3, 2, 4, 6}};
    Plane planes[4];
    for (int t = 0; t < 4; t++) { /* plane through the triangle, normal outward */
        const float *a = p[tri[3 * t]], *b = p[tri[3 * t + 1]], *c = p[tri[3 * t + 2]];
        const float u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
        const float v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        const float n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                            u[0] * v[1] - u[1] * v[0]};
        planes[t] = (Plane){n[0], n[1], n[2], -(n[0] * a[0] + n[1] * a[1] + n[2] * a[2])};
    }
    const Vec4 light = {2, 3, 4, 1}; /* a point light */
    _Alignas(16) uint8_t facing[4 + 1];
    sv_calculate_facing_c_ref(planes, 4, &light, facing); /* facing[4] = 1 */
    _Alignas(16) int out[6 * 6 + 6 * 4];                  /* sv_shadow_volume_capacity(12, 6) */
    const sv_variant *v = sv_best_variant();
    const int n = sv_create_shadow_volume_checked(v, out, sizeof out / sizeof out[0], tri, 12, 4,
                                                  edges, 6, facing, NULL);
    if (n < 0) {
        fprintf(stderr, "refused: %s\n", sv_status_string(n));
        return 1;
    }
    printf("%s: %d indices (%d triangles); even index 2v is vertex v, 2v+1 its extrusion\n",
           v->name, n, n / 3);
    return 0;
}
