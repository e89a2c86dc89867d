/*
 * A set of triangles in double with a bounding-volume hierarchy, for the
 * verifier's ray and segment crossings (volume_check.cpp). Only an index:
 * it hands out every triangle whose (slightly padded) box the ray meets,
 * and the caller runs its own exact test; so a crossing is never lost to
 * the hierarchy, only whole subtrees the ray cannot touch are skipped.
 * Without it, verify on a 100k-triangle mesh spends minutes testing every
 * triangle for every point.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_VERIFY_RAY_TRIANGLES_H
#define SV_VERIFY_RAY_TRIANGLES_H

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "shadowvol_verify.h"

namespace sv {

class RayTriangles {
public:
    /* Triangle t: corner a[t], edges e1[t] = b - a, e2[t] = c - a. */
    std::vector<Point3> a, e1, e2;

    void add(const Point3 &p0, const Point3 &p1, const Point3 &p2) {
        a.push_back(p0);
        e1.push_back({p1.x - p0.x, p1.y - p0.y, p1.z - p0.z});
        e2.push_back({p2.x - p0.x, p2.y - p0.y, p2.z - p0.z});
    }
    std::size_t size() const { return a.size(); }

    /* Builds the hierarchy; call once after the last add(). Boxes are
     * padded by PAD (absolute) so a crossing within the caller's edge
     * tolerance is never outside its triangle's box. */
    void build(double pad) {
        const std::size_t n = a.size();
        order_.resize(n);
        std::vector<Box> tri_box(n);
        std::vector<Point3> centroid(n);
        for (std::size_t t = 0; t < n; t++) {
            order_[t] = (uint32_t)t;
            const Point3 b{a[t].x + e1[t].x, a[t].y + e1[t].y, a[t].z + e1[t].z};
            const Point3 c{a[t].x + e2[t].x, a[t].y + e2[t].y, a[t].z + e2[t].z};
            Box &bx = tri_box[t];
            bx.lo = {std::min({a[t].x, b.x, c.x}) - pad, std::min({a[t].y, b.y, c.y}) - pad,
                     std::min({a[t].z, b.z, c.z}) - pad};
            bx.hi = {std::max({a[t].x, b.x, c.x}) + pad, std::max({a[t].y, b.y, c.y}) + pad,
                     std::max({a[t].z, b.z, c.z}) + pad};
            centroid[t] = {(bx.lo.x + bx.hi.x) / 2, (bx.lo.y + bx.hi.y) / 2,
                           (bx.lo.z + bx.hi.z) / 2};
        }
        nodes_.clear();
        if (n == 0) return;
        nodes_.reserve(2 * n / kLeafSize + 2);
        nodes_.emplace_back();
        build_node(0, 0, (uint32_t)n, tri_box, centroid);
    }

    /* Calls visit(t) for every triangle whose box the ray P + s*R, s in
     * [0, s_max], meets (s_max may be HUGE_VAL); visit returns false to
     * stop early. */
    template <class Visit>
    void for_each_candidate(const Point3 &p, const Point3 &r, double s_max, Visit &&visit) const {
        if (nodes_.empty()) return;
        uint32_t stack[128];
        int top = 0;
        stack[top++] = 0;
        while (top > 0) {
            const Node &nd = nodes_[stack[--top]];
            if (!meets(nd.box, p, r, s_max)) continue;
            if (nd.count > 0) {
                for (uint32_t i = nd.first; i < nd.first + nd.count; i++) {
                    if (!visit(order_[i])) return;
                }
            } else if (top + 2 <= 128) {
                stack[top++] = nd.first;     /* left child */
                stack[top++] = nd.first + 1; /* right child */
            } else {
                /* Deeper than any median-split tree of 2^60 triangles can
                 * be; fall back to visiting the subtree's triangles. */
                for (uint32_t i = nd.lo_tri; i < nd.hi_tri; i++) {
                    if (!visit(order_[i])) return;
                }
            }
        }
    }

private:
    static constexpr uint32_t kLeafSize = 4;
    struct Box {
        Point3 lo, hi;
    };
    struct Node {
        Box box;
        uint32_t first = 0;              /* leaf: first entry of order_; inner: left child */
        uint32_t count = 0;              /* leaf: triangles; inner: 0 */
        uint32_t lo_tri = 0, hi_tri = 0; /* the subtree's range of order_ */
    };
    std::vector<uint32_t> order_;
    std::vector<Node> nodes_;

    static bool meets(const Box &b, const Point3 &p, const Point3 &r, double s_max) {
        double s0 = 0, s1 = s_max;
        const double pl[3] = {p.x, p.y, p.z}, rl[3] = {r.x, r.y, r.z};
        const double lo[3] = {b.lo.x, b.lo.y, b.lo.z}, hi[3] = {b.hi.x, b.hi.y, b.hi.z};
        for (int k = 0; k < 3; k++) {
            if (rl[k] == 0.0) {
                if (pl[k] < lo[k] || pl[k] > hi[k]) return false;
                continue;
            }
            double t0 = (lo[k] - pl[k]) / rl[k], t1 = (hi[k] - pl[k]) / rl[k];
            if (t0 > t1) std::swap(t0, t1);
            s0 = std::max(s0, t0);
            s1 = std::min(s1, t1);
            if (s0 > s1) return false;
        }
        return true;
    }

    /* Fills node SLOT for order_[begin, end): a leaf of up to kLeafSize
     * triangles, or a median split of the centroids along the box's longest
     * axis with both children stored side by side (left at `first`, right
     * at `first + 1`). Indices only: nodes_ grows while this runs. */
    void build_node(uint32_t slot, uint32_t begin, uint32_t end, const std::vector<Box> &tri_box,
                    const std::vector<Point3> &centroid) {
        Box box = tri_box[order_[begin]];
        for (uint32_t i = begin + 1; i < end; i++) {
            const Box &t = tri_box[order_[i]];
            box.lo = {std::min(box.lo.x, t.lo.x), std::min(box.lo.y, t.lo.y),
                      std::min(box.lo.z, t.lo.z)};
            box.hi = {std::max(box.hi.x, t.hi.x), std::max(box.hi.y, t.hi.y),
                      std::max(box.hi.z, t.hi.z)};
        }
        nodes_[slot].box = box;
        nodes_[slot].lo_tri = begin;
        nodes_[slot].hi_tri = end;
        if (end - begin <= kLeafSize) {
            nodes_[slot].first = begin;
            nodes_[slot].count = end - begin;
            return;
        }
        const double ext[3] = {box.hi.x - box.lo.x, box.hi.y - box.lo.y, box.hi.z - box.lo.z};
        const int axis = ext[0] >= ext[1] && ext[0] >= ext[2] ? 0 : ext[1] >= ext[2] ? 1 : 2;
        auto key = [&](uint32_t t) {
            return axis == 0 ? centroid[t].x : axis == 1 ? centroid[t].y : centroid[t].z;
        };
        const uint32_t mid = begin + (end - begin) / 2;
        std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
                         [&](uint32_t x, uint32_t y) { return key(x) < key(y); });
        const uint32_t left = (uint32_t)nodes_.size();
        nodes_.emplace_back();
        nodes_.emplace_back();
        nodes_[slot].first = left;
        nodes_[slot].count = 0;
        build_node(left, begin, mid, tri_box, centroid);
        build_node(left + 1, mid, end, tri_box, centroid);
    }
};

} // namespace sv

#endif
