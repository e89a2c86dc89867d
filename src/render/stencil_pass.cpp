/*
 * The stencil pass of stencil_pass.h: the methods by name, and the one
 * each frame runs.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "stencil_pass.h"

#include <algorithm>
#include <limits>

#include "pass_bins.h"

#include <string>

namespace sv::render {
namespace {

struct MethodName {
    StencilMethod method;
    const char *name;
};
constexpr MethodName kMethods[] = {
    {StencilMethod::brute_force, "bf"},
    {StencilMethod::depth_bounds, "db"},
    {StencilMethod::hierarchical, "hier"},
    {StencilMethod::automatic, "auto"},
};

} // namespace

const char *stencil_method_name(StencilMethod m) {
    for (const MethodName &k : kMethods) {
        if (k.method == m) return k.name;
    }
    return "?";
}

bool stencil_method_by_name(const std::string &name, StencilMethod &method) {
    for (const MethodName &k : kMethods) {
        if (name == k.name) {
            method = k.method;
            return true;
        }
    }
    return false;
}

std::string stencil_method_names() {
    std::string s;
    for (const MethodName &k : kMethods) s += (s.empty() ? "" : ", ") + std::string(k.name);
    return s;
}

bool valid_stencil_tile(int side) { return side == 4 || side == 8 || side == 16 || side == 32; }

std::vector<VolumeChunk> volume_chunks(const std::vector<Volume> &volumes) {
    std::vector<VolumeChunk> chunks;
    for (int vi = 0; vi < (int)volumes.size(); vi++) {
        const int n = volumes[(std::size_t)vi].drawn_indices() / 3;
        for (int t = 0; t < n; t += detail::kSetupChunk)
            chunks.push_back({vi, t, std::min(n, t + detail::kSetupChunk)});
    }
    return chunks;
}

std::vector<ShadowVertexBuffer> shadow_vertex_buffers(const StencilPassInputs &in) {
    const std::vector<Volume> &volumes = *in.volumes;
    std::vector<ShadowVertexBuffer> sv_clip(volumes.size());
    detail::parallel((int)volumes.size(), [&](int vi) {
        const Volume &vol = volumes[(std::size_t)vi];
        const PreparedSurface &p = in.scene->surfaces[(std::size_t)vol.surface].prepared;
        const std::size_t n = 2 * (std::size_t)p.num_vertices();
        /* Not value-initialised: the pages of vertices no index uses are
         * never touched. */
        sv_clip[(std::size_t)vi].reset(new raster::ClipVertex[n]);
        raster::ClipVertex *out = sv_clip[(std::size_t)vi].get();
        const std::vector<raster::ClipVertex> &receiver = (*in.receivers)[(std::size_t)vol.surface];
        std::vector<uint8_t> done(n, 0);
        const int drawn = vol.drawn_indices();
        for (int k = 0; k < drawn; k++) {
            const int i = vol.indices[(std::size_t)k];
            if (done[(std::size_t)i]) continue;
            done[(std::size_t)i] = 1;
            out[i] = (i & 1) == 0 ? receiver[(std::size_t)(i / 2)]
                                  : volume_vertex_to_clip(in.view_proj, p, vol, i, in.light);
        }
    });
    return sv_clip;
}

SaturatingCounts::SaturatingCounts(int width, int height)
    : increments((std::size_t)width * (std::size_t)height, 0),
      decrements((std::size_t)width * (std::size_t)height, 0) {}

void SaturatingCounts::resolve(std::vector<uint8_t> &stencil) const {
    const std::size_t n = increments.size();
    stencil.resize(n);
    constexpr std::size_t kBlock = 1 << 16;
    detail::parallel((int)((n + kBlock - 1) / kBlock), [&](int b) {
        const std::size_t lo = (std::size_t)b * kBlock, hi = std::min(n, lo + kBlock);
        for (std::size_t i = lo; i < hi; i++) {
            const int d = (int)increments[i] - (int)decrements[i];
            stencil[i] = (uint8_t)(d > 0 ? d : 0);
        }
    });
}

raster::DepthBounds no_depth_bounds() {
    return {-std::numeric_limits<float>::infinity(), std::numeric_limits<float>::infinity()};
}

StencilPassResult stencil_pass(StencilMethod method, const StencilPassInputs &in) {
    switch (method) {
    case StencilMethod::brute_force: return stencil_pass_brute_force(in);
    case StencilMethod::depth_bounds: return stencil_pass_depth_bounds(in);
    case StencilMethod::hierarchical: return stencil_pass_hierarchical(in);
    case StencilMethod::automatic: return stencil_pass_automatic(in);
    }
    return stencil_pass_brute_force(in); /* (every method is a case above) */
}

} // namespace sv::render
