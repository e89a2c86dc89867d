/*
 * Triangle setup of the rasteriser (see rasterizer.h): clipping, snapping,
 * edge functions and the depth plane; each row span goes to a row kernel.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "rasterizer.h"

#include <sys/mman.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>

#include "fill_rule.h"
#include "row_kernels_c.h"
#include "row_walk.h"

namespace sv::raster {
namespace {

constexpr int kSubPixelBits = 8;
constexpr double kSubPixel = 1 << kSubPixelBits;
constexpr int kMaxPolygon = 3 + 5; /* a triangle cut by 5 planes */

/* Signed distance to clip plane P (>= 0 inside). */
inline double plane_distance(int p, const ClipVertex &v) {
    switch (p) {
    case 0: return v.z + v.w;  /* near */
    case 1: return v.x + v.w;  /* left */
    case 2: return v.w - v.x;  /* right */
    case 3: return v.y + v.w;  /* bottom */
    default: return v.w - v.y; /* top */
    }
}

/* The point where edge (IN, OUT) meets plane P, always computed from the
 * inside end, so both triangles of a shared edge get the same bits. */
inline ClipVertex cut(const ClipVertex &in, double d_in, const ClipVertex &out, double d_out) {
    const double t = d_in / (d_in - d_out);
    return {in.x + t * (out.x - in.x), in.y + t * (out.y - in.y), in.z + t * (out.z - in.z),
            in.w + t * (out.w - in.w)};
}

/* Sutherland-Hodgman against the five planes. Returns the vertex count
 * (0: nothing left). */
int clip_polygon(ClipVertex poly[kMaxPolygon], int n) {
    ClipVertex tmp[kMaxPolygon];
    for (int p = 0; p < 5 && n > 0; p++) {
        int m = 0;
        for (int i = 0; i < n; i++) {
            const ClipVertex &a = poly[i], &b = poly[(i + 1) % n];
            const double da = plane_distance(p, a), db = plane_distance(p, b);
            if (da >= 0) tmp[m++] = a;
            if ((da >= 0) != (db >= 0)) {
                tmp[m++] = da >= 0 ? cut(a, da, b, db) : cut(b, db, a, da);
            }
        }
        n = m;
        std::memcpy(poly, tmp, sizeof(ClipVertex) * (std::size_t)n);
    }
    return n;
}

struct Snapped {
    int64_t X, Y; /* 1/256 pixel, y down */
    double z;     /* window depth */
};

/* Window coordinates of the clipped polygon, snapped to 1/256 pixel (round
 * to nearest), and window depth. False when a vertex is not drawable (w <=
 * 0 or not finite: only a degenerate input gets here after clipping).
 *
 * Clipping leaves |x|, |y| <= w up to rounding, but a vertex cut from an
 * edge whose ends differ by many orders of magnitude can carry an error
 * far larger than its own w (a light very close to a vertex extrudes such
 * edges): x / w then reaches 1e16 and more, and the int64 cast and the
 * edge functions would overflow. Such a vertex lies on a side plane in
 * exact arithmetic, so it is clamped to a guard band of one pixel around
 * the frame, which no vertex that clipping placed correctly can leave; the
 * bound walk_rows' proof needs (|X|, |Y| < 2^21 + 2^8) then holds for
 * every input. */
/* nearbyint(v) in the default rounding mode (to nearest, ties to even)
 * for |v| < 2^51, without a call to libm (x86-64's baseline has no
 * roundsd): adding 1.5 * 2^52 leaves no fraction bits, so the sum is
 * rounded to an integer by the addition itself, and the subtraction is
 * exact. snap_polygon's values are below 2^22 after the guard band. */
inline double round_half_even(double v) {
    constexpr double kShift = 6755399441055744.0; /* 1.5 * 2^52 */
    return (v + kShift) - kShift;
}

bool snap_polygon(const ClipVertex *poly, int n, int width, int height, Snapped *s) {
    for (int i = 0; i < n; i++) {
        const ClipVertex &q = poly[i];
        if (!(q.w > 0) || !std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z)) {
            return false;
        }
        const double xs = std::clamp((q.x / q.w + 1) * 0.5 * width, -1.0, width + 1.0);
        const double ys = std::clamp((1 - q.y / q.w) * 0.5 * height, -1.0, height + 1.0);
        s[i].X = (int64_t)round_half_even(xs * kSubPixel);
        s[i].Y = (int64_t)round_half_even(ys * kSubPixel);
        s[i].z = (q.z / q.w + 1) * 0.5;
    }
    return true;
}

inline bool snapped_less(const Snapped &a, const Snapped &b) {
    if (a.X != b.X) return a.X < b.X;
    if (a.Y != b.Y) return a.Y < b.Y;
    return a.z < b.z;
}

inline int64_t floor_div(int64_t a, int64_t b) { /* b > 0 */
    return a >= 0 ? a / b : -((-a + b - 1) / b);
}

/* Depth as z0 + a * (x - x0) + b * (y - y0), x and y in pixels. */
struct DepthPlane {
    double x0, y0, z0, a, b;
    bool ok;
};

DepthPlane plane_of(const Snapped &p, const Snapped &q, const Snapped &r) {
    const double x0 = (double)p.X / kSubPixel, y0 = (double)p.Y / kSubPixel;
    const double x1 = (double)q.X / kSubPixel - x0, y1 = (double)q.Y / kSubPixel - y0;
    const double x2 = (double)r.X / kSubPixel - x0, y2 = (double)r.Y / kSubPixel - y0;
    const double z1 = q.z - p.z, z2 = r.z - p.z;
    const double det = x1 * y2 - x2 * y1;
    DepthPlane d{x0, y0, p.z, 0, 0, det != 0};
    if (d.ok) {
        d.a = (z1 * y2 - z2 * y1) / det;
        d.b = (x1 * z2 - x2 * z1) / det;
        d.ok = std::isfinite(d.a) && std::isfinite(d.b);
    }
    return d;
}

/* The plane of a polygon from a choice of three vertices that does not
 * depend on their order: the vertices sorted, and the triple of largest
 * |area| (the first such in sorted order). */
DepthPlane canonical_plane(const Snapped *v, int n) {
    Snapped s[kMaxPolygon];
    /* Insertion sort: at most 8 vertices. */
    for (int i = 0; i < n; i++) {
        int j = i;
        for (; j > 0 && snapped_less(v[i], s[j - 1]); j--) s[j] = s[j - 1];
        s[j] = v[i];
    }
    if (n == 3) return plane_of(s[0], s[1], s[2]);
    int64_t best = -1;
    int bi = 0, bj = 1, bk = 2;
    for (int i = 0; i < n; i++) {
        for (int j = i + 1; j < n; j++) {
            for (int k = j + 1; k < n; k++) {
                const int64_t a2 = (s[j].X - s[i].X) * (s[k].Y - s[i].Y) -
                                   (s[k].X - s[i].X) * (s[j].Y - s[i].Y);
                const int64_t mag = a2 < 0 ? -a2 : a2;
                if (mag > best) best = mag, bi = i, bj = j, bk = k;
            }
        }
    }
    return plane_of(s[bi], s[bj], s[bk]);
}

} // namespace

void *allocate_frame_bytes(std::size_t bytes) {
    constexpr std::size_t kHuge = 2u << 20;
    /* kFrameSlack readable bytes after the last element, for the row
     * kernels' whole-vector loads (row_kernels.h). */
    const std::size_t rounded = (bytes + kFrameSlack + kHuge - 1) / kHuge * kHuge;
    void *p = std::aligned_alloc(kHuge, rounded);
    if (!p) throw std::bad_alloc();
    madvise(p, rounded, MADV_HUGEPAGE); /* a hint: without it the buffer still works */
    return p;
}

void free_frame_bytes(void *p) noexcept { std::free(p); }

void PassCounters::add(const PassCounters &o) {
    triangles += o.triangles;
    triangles_clipped += o.triangles_clipped;
    triangles_outside += o.triangles_outside;
    triangles_degenerate += o.triangles_degenerate;
    pixels_tested += o.pixels_tested;
    pixels_written += o.pixels_written;
    rows += o.rows;
    depth_bytes_read += o.depth_bytes_read;
    depth_bytes_written += o.depth_bytes_written;
    stencil_bytes_read += o.stencil_bytes_read;
    stencil_bytes_written += o.stencil_bytes_written;
}

uint64_t Target::bytes_for(int width, int height) {
    return (uint64_t)width * (uint64_t)height * (sizeof(float) + sizeof(int32_t) + 1);
}

namespace {

void check_side(const char *what, int side) {
    if (side < 1 || side > kMaxTargetSide) {
        throw std::invalid_argument(std::string("rasteriser: target ") + what + " " +
                                    std::to_string(side) + " outside 1.." +
                                    std::to_string(kMaxTargetSide));
    }
}

} // namespace

void Target::resize(int w, int h) {
    check_side("width", w);
    check_side("height", h);
    width = w;
    height = h;
    const std::size_t n = (std::size_t)w * (std::size_t)h;
    depth.assign(n, 1.0f);
    ids.assign(n, -1);
    stencil.assign(n, 0);
}

void Target::allocate(int w, int h) {
    check_side("width", w);
    check_side("height", h);
    width = w;
    height = h;
    const std::size_t n = (std::size_t)w * (std::size_t)h;
    depth.resize(n);
    ids.resize(n);
    stencil.resize(n);
}

void Target::clear_rows(int row_begin, int row_end) {
    const std::size_t a = (std::size_t)row_begin * (std::size_t)width,
                      b = (std::size_t)row_end * (std::size_t)width;
    std::fill(depth.begin() + (std::ptrdiff_t)a, depth.begin() + (std::ptrdiff_t)b, 1.0f);
    std::fill(ids.begin() + (std::ptrdiff_t)a, ids.begin() + (std::ptrdiff_t)b, -1);
    std::fill(stencil.begin() + (std::ptrdiff_t)a, stencil.begin() + (std::ptrdiff_t)b, 0);
}

void Target::clear_depth() {
    std::fill(depth.begin(), depth.end(), 1.0f);
    std::fill(ids.begin(), ids.end(), -1);
}

void Target::clear_stencil() { std::fill(stencil.begin(), stencil.end(), 0); }

namespace {

/* Set-up's second half: the snapped polygon S of N corners into its
 * pieces (the fan of triangles, edge functions, the depth plane). */
void pieces_of(const Snapped *s, int n, int width, int height, int32_t id, PassCounters &c,
               std::vector<SetupTriangle> &out, std::vector<PieceExtent> *extents) {
    const DepthPlane dp = canonical_plane(s, n);
    if (!dp.ok) {
        c.triangles_degenerate++;
        return;
    }
    double off_plane = 0;
    if (extents && n > 3) {
        for (int i = 0; i < n; i++) {
            const double z = dp.z0 + dp.a * ((double)s[i].X / kSubPixel - dp.x0) +
                             dp.b * ((double)s[i].Y / kSubPixel - dp.y0);
            off_plane = std::max(off_plane, std::fabs(z - s[i].z));
        }
    }
    bool drew = false;
    for (int k = 1; k + 1 < n; k++) {
        Snapped t[3] = {s[0], s[k], s[k + 1]};
        const int64_t a2 = (t[1].X - t[0].X) * (t[2].Y - t[0].Y) -
                           (t[2].X - t[0].X) * (t[1].Y - t[0].Y);
        if (a2 == 0) continue;
        /* Counter-clockwise with y up is clockwise with y down: a2 < 0. */
        const bool front = a2 < 0;
        if (front) std::swap(t[1], t[2]);
        drew = true;
        SetupTriangle st;
        for (int e = 0; e < 3; e++) {
            const Snapped &a = t[e], &b = t[(e + 1) % 3];
            const int64_t ex = b.X - a.X, ey = b.Y - a.Y;
            /* E(P) = ex * (Py - a.Y) - ey * (Px - a.X), at the centre of
             * pixel (0, 0): P = (128, 128). */
            const int64_t half = (int64_t)kSubPixel / 2;
            st.e_origin[e] = ex * (half - a.Y) - ey * (half - a.X) + fill_rule_bias(ex, ey);
            st.step_x[e] = -ey * (int64_t)kSubPixel;
            st.step_y[e] = ex * (int64_t)kSubPixel;
        }
        const int64_t min_x = std::min({t[0].X, t[1].X, t[2].X}),
                      max_x = std::max({t[0].X, t[1].X, t[2].X});
        const int64_t min_y = std::min({t[0].Y, t[1].Y, t[2].Y}),
                      max_y = std::max({t[0].Y, t[1].Y, t[2].Y});
        const int64_t sub = (int64_t)kSubPixel, half = sub / 2;
        st.x_first = (int)std::max<int64_t>(0, floor_div(min_x - half + sub - 1, sub));
        st.x_last = (int)std::min<int64_t>(width - 1, floor_div(max_x - half, sub));
        st.y_first = (int)std::max<int64_t>(0, floor_div(min_y - half + sub - 1, sub));
        st.y_last = (int)std::min<int64_t>(height - 1, floor_div(max_y - half, sub));
        if (!extents && (st.x_first > st.x_last || st.y_first > st.y_last)) continue;
        st.x0 = dp.x0, st.y0 = dp.y0, st.z0 = dp.z0, st.a = dp.a, st.b = dp.b;
        st.id = id;
        st.front = front;
        out.push_back(st);
        if (extents) {
            extents->push_back({min_x,
                                max_x,
                                min_y,
                                max_y,
                                {t[0].X, t[1].X, t[2].X},
                                {t[0].Y, t[1].Y, t[2].Y},
                                off_plane});
        }
    }
    if (!drew) c.triangles_degenerate++;
}

} // namespace

Rasterizer::Rasterizer(const RowKernels *kernels) : kernels_(kernels) {}

void Rasterizer::setup(const ClipVertex v[3], int width, int height, int32_t id, PassCounters &c,
                       std::vector<SetupTriangle> &out, std::vector<PieceExtent> *extents) const {
    if (width < 1 || width > kMaxTargetSide || height < 1 || height > kMaxTargetSide) {
        check_side("width", width);
        check_side("height", height);
    }
    c.triangles++;
    ClipVertex poly[kMaxPolygon] = {v[0], v[1], v[2]};
    int n = 3;
    bool inside_all = true;
    for (int p = 0; p < 5; p++) {
        const double d0 = plane_distance(p, v[0]), d1 = plane_distance(p, v[1]),
                     d2 = plane_distance(p, v[2]);
        if (d0 < 0 && d1 < 0 && d2 < 0) {
            c.triangles_outside++;
            return;
        }
        if (d0 < 0 || d1 < 0 || d2 < 0) inside_all = false;
    }
    if (!inside_all) {
        c.triangles_clipped++;
        n = clip_polygon(poly, n);
        if (n < 3) {
            c.triangles_outside++;
            return;
        }
    }
    Snapped s[kMaxPolygon];
    if (!snap_polygon(poly, n, width, height, s)) {
        c.triangles_degenerate++;
        return;
    }
    pieces_of(s, n, width, height, id, c, out, extents);
}

WindowVertex window_vertex(const ClipVertex &v, int width, int height) {
    WindowVertex w;
    for (int p = 0; p < 5; p++) {
        if (plane_distance(p, v) < 0) w.outside = (uint8_t)(w.outside | (1u << p));
    }
    Snapped sn{};
    w.drawable = snap_polygon(&v, 1, width, height, &sn);
    w.X = sn.X, w.Y = sn.Y, w.z = sn.z;
    return w;
}

void Rasterizer::setup_shared(const ClipVertex v[3], const WindowVertex w[3], int width, int height,
                              int32_t id, PassCounters &c, std::vector<SetupTriangle> &out) const {
    /* Inside every plane: nothing to clip, and the corners snap as set-up
     * would snap them (the same formula, once per vertex). Else the whole
     * set-up. */
    if ((w[0].outside | w[1].outside | w[2].outside) != 0 || !w[0].drawable || !w[1].drawable ||
        !w[2].drawable) {
        setup(v, width, height, id, c, out);
        return;
    }
    if (width < 1 || width > kMaxTargetSide || height < 1 || height > kMaxTargetSide) {
        check_side("width", width);
        check_side("height", height);
    }
    c.triangles++;
    const Snapped s[3] = {{w[0].X, w[0].Y, w[0].z},
                          {w[1].X, w[1].Y, w[1].z},
                          {w[2].X, w[2].Y, w[2].z}};
    pieces_of(s, 3, width, height, id, c, out, nullptr);
}

void Rasterizer::walk_depth(const SetupTriangle &tri, Target &t, RowBand band, RowCounts &r) const {
    kernels_->walk_depth(tri, band, {t.depth.data(), t.ids.data(), nullptr, t.width, t.height}, r);
}

void Rasterizer::walk_stencil(const SetupTriangle &tri, const float *depth, uint8_t *stencil,
                              int width, int height, RowBand band, StencilMode mode,
                              RowCounts &r) const {
    const WalkBuffers b{const_cast<float *>(depth), nullptr, stencil, width, height};
    const uint8_t delta = detail::stencil_delta(mode, tri.front);
    (mode == StencilMode::zpass ? kernels_->walk_zpass : kernels_->walk_zfail)(tri, band, b, delta,
                                                                               r);
}

void Rasterizer::covered_spans(const SetupTriangle &tri, RowBand band,
                               std::vector<CoveredSpan> &out) {
    detail::walk_rows(tri, band, [&](const RowSpan &span, int y) {
        /* walk_rows's span is padded (a pixel or so each side); the
         * kernels' integer test decides, and so does this one. */
        auto covered = [&](int x) {
            const int64_t dx = (int64_t)x - span.x_begin;
            return span.e[0] + span.step[0] * dx >= 0 && span.e[1] + span.step[1] * dx >= 0 &&
                   span.e[2] + span.step[2] * dx >= 0;
        };
        int lo = span.x_begin, hi = span.x_end - 1;
        while (lo <= hi && !covered(lo)) lo++;
        while (hi >= lo && !covered(hi)) hi--;
        if (lo <= hi) out.push_back({y, lo, hi + 1});
    });
}

void Rasterizer::walk_stencil_bounded(const SetupTriangle &tri, const float *depth,
                                      uint8_t *stencil, int width, RowBand band, StencilMode mode,
                                      DepthBounds bounds, RowCounts &r) const {
    const uint8_t delta = detail::stencil_delta(mode, tri.front);
    detail::walk_rows(tri, band, [&](const RowSpan &span, int y) {
        const std::size_t row = (std::size_t)y * (std::size_t)width;
        const RowBuffers b{const_cast<float *>(depth) + row, nullptr, stencil + row};
        r.rows++;
        if (mode == StencilMode::zpass) {
            c_rows::stencil_bounded_c<false>(span, b, delta, bounds.skip_at_or_below,
                                             bounds.skip_above, r);
        } else {
            c_rows::stencil_bounded_c<true>(span, b, delta, bounds.skip_at_or_below,
                                            bounds.skip_above, r);
        }
    });
}

void Rasterizer::walk_stencil_saturating(const SetupTriangle &tri, const float *depth,
                                         uint8_t *count, int width, RowBand band, StencilMode mode,
                                         DepthBounds bounds, RowCounts &r) const {
    detail::walk_rows(tri, band, [&](const RowSpan &span, int y) {
        const std::size_t row = (std::size_t)y * (std::size_t)width;
        const RowBuffers b{const_cast<float *>(depth) + row, nullptr, count + row};
        r.rows++;
        if (mode == StencilMode::zpass) {
            c_rows::stencil_bounded_c<false, true>(span, b, 1, bounds.skip_at_or_below,
                                                   bounds.skip_above, r);
        } else {
            c_rows::stencil_bounded_c<true, true>(span, b, 1, bounds.skip_at_or_below,
                                                  bounds.skip_above, r);
        }
    });
}

void Rasterizer::add_depth_counts(const RowCounts &r, PassCounters &c) {
    c.rows += r.rows;
    c.pixels_tested += r.tested;
    c.pixels_written += r.written;
    c.depth_bytes_read += 4 * r.tested;
    c.depth_bytes_written += 4 * r.written;
}

void Rasterizer::add_stencil_counts(const RowCounts &r, PassCounters &c) {
    c.rows += r.rows;
    c.pixels_tested += r.tested;
    c.pixels_written += r.written;
    c.depth_bytes_read += 4 * r.tested;
    c.stencil_bytes_read += r.written;
    c.stencil_bytes_written += r.written;
}

void Rasterizer::draw_depth(Target &t, const ClipVertex v[3], int32_t id, PassCounters &c) const {
    std::vector<SetupTriangle> pieces;
    setup(v, t.width, t.height, id, c, pieces);
    RowCounts r;
    for (const SetupTriangle &p : pieces) walk_depth(p, t, {0, t.height}, r);
    add_depth_counts(r, c);
}

void Rasterizer::draw_stencil(Target &t, const ClipVertex v[3], StencilMode mode,
                              PassCounters &c) const {
    std::vector<SetupTriangle> pieces;
    setup(v, t.width, t.height, 0, c, pieces);
    RowCounts r;
    for (const SetupTriangle &p : pieces) {
        walk_stencil(p, t.depth.data(), t.stencil.data(), t.width, t.height, {0, t.height}, mode,
                     r);
    }
    add_stencil_counts(r, c);
}

Rasterizer::PlaneCoefficients Rasterizer::depth_plane(const ClipVertex v[3], int width,
                                                      int height) const {
    ClipVertex poly[kMaxPolygon] = {v[0], v[1], v[2]};
    const int n = clip_polygon(poly, 3);
    Snapped s[kMaxPolygon];
    if (n < 3 || !snap_polygon(poly, n, width, height, s)) return {0, 0, 0, 0, 0, false};
    const DepthPlane d = canonical_plane(s, n);
    return {d.x0, d.y0, d.z0, d.a, d.b, d.ok};
}

std::vector<Rasterizer::WindowTriangle> Rasterizer::window_triangles(const ClipVertex v[3],
                                                                     int width, int height) const {
    /* The same clipping and snapping as rasterize(), kept as pixels. */
    std::vector<WindowTriangle> out;
    ClipVertex poly[kMaxPolygon] = {v[0], v[1], v[2]};
    const int n = clip_polygon(poly, 3);
    Snapped s[kMaxPolygon];
    if (n < 3 || !snap_polygon(poly, n, width, height, s)) return {};
    for (int k = 1; k + 1 < n; k++) {
        const Snapped *t[3] = {&s[0], &s[k], &s[k + 1]};
        WindowTriangle w;
        for (int i = 0; i < 3; i++) {
            w.x[i] = (double)t[i]->X / kSubPixel;
            w.y[i] = (double)t[i]->Y / kSubPixel;
            w.z[i] = t[i]->z;
        }
        const double a2 = (w.x[1] - w.x[0]) * (w.y[2] - w.y[0]) -
                          (w.x[2] - w.x[0]) * (w.y[1] - w.y[0]);
        if (a2 == 0) continue;
        w.front = a2 < 0;
        out.push_back(w);
    }
    return out;
}

} // namespace sv::raster
