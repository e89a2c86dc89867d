/*
 * Two frames of one scene compared pixel for pixel (frame.h's
 * compare_frames): the proof that the shortcuts change nothing in reach
 * of a light.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <algorithm>

#include "frame.h"

namespace sv::render {

bool pixel_in_light_reach(const Frame &f, const Scene &scene, int light, std::size_t pixel) {
    const int32_t id = f.target.ids[pixel];
    if (id < 0) return false;
    int si, t;
    f.decode_id(id, si, t);
    const SceneSurface &s = scene.surfaces[(std::size_t)si];
    const SceneLight &l = scene.lights[(std::size_t)light];
    if (!light_reaches_box(l, s.lo, s.hi)) return false;
    const auto row = (int)(pixel / (std::size_t)f.width),
               column = (int)(pixel % (std::size_t)f.width);
    return point_in_light_reach(l, visible_point(f, scene, si, t, column, row));
}

FrameDifference compare_frames(const Scene &scene, const Frame &a, const Frame &b) {
    FrameDifference d;
    if (a.rgb.size() != b.rgb.size() || a.lights.size() != b.lights.size()) {
        d.rgb_bytes = std::max(a.rgb.size(), b.rgb.size());
        d.first_rgb = 0;
        return d;
    }
    for (std::size_t i = 0; i < a.rgb.size(); i++) {
        if (a.rgb[i] == b.rgb[i]) continue;
        if (d.rgb_bytes++ == 0) d.first_rgb = i / 3;
    }
    for (std::size_t li = 0; li < a.lights.size(); li++) {
        const auto &sa = a.lights[li].stencil, &sb = b.lights[li].stencil;
        for (std::size_t i = 0; i < sa.size(); i++) {
            if ((sa[i] == 0) == (sb[i] == 0)) continue;
            if (pixel_in_light_reach(a, scene, (int)li, i)) {
                if (d.mask_in_reach++ == 0) d.first_mask = i;
            } else {
                d.mask_elsewhere++;
            }
        }
    }
    return d;
}

} // namespace sv::render
