/*
 * One rendered frame of a scene (issue 12): the depth pass of every
 * surface, then per light the shadow volumes (the library's facing and
 * volume routines), their stencil pass in z-pass or z-fail, and the
 * lighting pass that lights where the stencil is 0.
 *
 * The frame keeps what the judges need: the depth and triangle ids, each
 * light's stencil, and each volume's index list exactly as
 * sv_create_shadow_volume returned it, with the part that was drawn.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_RENDER_FRAME_H
#define SV_RENDER_FRAME_H

#include <cstdint>
#include <string>
#include <vector>

#include "rasterizer.h"
#include "shadowvol_scene.h"

namespace sv::render {

enum class ModeChoice { zpass, zfail, automatic };
const char *mode_name(ModeChoice m);

struct RenderOptions {
    int width = 1280, height = 1024;
    ModeChoice mode = ModeChoice::automatic;
    const raster::RowKernels *kernels = nullptr; /* nullptr: the best this CPU runs */
    const sv_variant *variant = nullptr;         /* nullptr: sv_best_variant() */
    const sv_facing_variant *facing = nullptr;   /* nullptr: sv_best_facing_variant() */
    double ambient = 0.12;
};

/* Largest frame side and pixel count accepted (a 8192 x 8192 frame needs
 * about 1.2 GiB with the truth's buffers). */
constexpr int kMaxFrameSide = 8192;
constexpr int64_t kMaxFramePixels = 8192LL * 8192LL;
/* Bytes a frame of W x H with L lights needs (target, per-light stencils,
 * colour, truth classes): what the CLI prints before it allocates. */
uint64_t frame_bytes(int width, int height, int lights);

struct Volume {
    int surface = 0;
    AlignedVector<int> indices; /* sv_create_shadow_volume's list, whole */
    int silhouette_indices = 0; /* its first part: the silhouette quads */
    bool zfail = false;         /* drawn in z-fail (all of it) or z-pass (the silhouette part) */
    int drawn_indices() const { return zfail ? (int)indices.size() : silhouette_indices; }
};

struct LightFrame {
    SceneLight light;
    Vec4 shadow_light{};
    std::vector<Volume> volumes;  /* surfaces that cast (a volume with indices) */
    int zfail_volumes = 0;
    int64_t indices = 0;          /* in all volumes */
    int64_t drawn_indices = 0;
    uint64_t ticks_facing = 0, ticks_volume = 0, ticks_stencil = 0;
    double seconds_stencil = 0;
    raster::PassCounters stencil_counters;
    std::vector<uint8_t> stencil; /* the stencil after this light's pass */
};

struct Frame {
    int width = 0, height = 0;
    Camera camera;
    Mat4d view_proj;
    std::string kernels;          /* row kernels used */
    std::string variant;          /* the library's kernels used */
    raster::Target target;        /* depth and ids after the depth pass */
    raster::PassCounters depth_counters;
    uint64_t ticks_depth = 0;
    double seconds_depth = 0;
    uint64_t ticks_shading = 0; /* the lighting pass, all lights */
    std::vector<LightFrame> lights;
    std::vector<uint8_t> rgb;     /* shaded image, 3 bytes per pixel, row 0 = top */
    /* The camera ray through pixel centre (px, py):
     * ray_forward + nx * ray_right + ny * ray_up, nx and ny in [-1, 1]. */
    Vec3d ray_forward, ray_right, ray_up;
    /* ids[] = surface_first_id[s] + triangle of surface s. */
    std::vector<int32_t> surface_first_id;
    void decode_id(int32_t id, int &surface, int &triangle) const;
};

/* Renders SCENE (validated: see validate_scene). */
Frame render_frame(const Scene &scene, const RenderOptions &options);

/* The clip-space position of world point (x, y, z, w) (the rasteriser's
 * input for every vertex, receivers and volumes alike). */
raster::ClipVertex to_clip(const Mat4d &view_proj, double x, double y, double z, double w);

/* Element SV_INDEX of the double-length shadow vertex buffer of P, through
 * the paper's section 3 vertex program, in clip space: even 2v = (x, y, z,
 * 1); odd 2v + 1 = (x L.w - L.x, y L.w - L.y, z L.w - L.z, 0), the point
 * moved to infinity away from the light. The one place the extrusion is
 * computed (its GLSL twin is in src/gljudge). */
raster::ClipVertex shadow_vertex_to_clip(const Mat4d &view_proj, const PreparedSurface &p,
                                         int sv_index, const Vec4 &L);

/* The camera ray through window point (x, y) (pixels, y down; a pixel's
 * centre is at + 0.5): unit length along the view axis. */
Vec3d camera_ray(const Frame &f, double x, double y);

/* Would z-pass be wrong for this surface and light: can a point of the
 * camera's near-plane rectangle lie in the surface's shadow volume? A
 * conservative test: the surface's box against the convex hull of the
 * near rectangle and the light (swept towards a directional light). */
bool near_plane_may_be_shadowed(const Camera &camera, double aspect, const SceneSurface &s,
                                const SceneLight &light);

/* The world point seen through the centre of pixel (px, py) on triangle
 * T of surface S (the camera ray meets the triangle's plane), in double. */
Vec3d visible_point(const Frame &f, const Scene &scene, int surface, int triangle, int px,
                    int py);

} // namespace sv::render

#endif
