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
#include <functional>
#include <string>
#include <vector>

#include "rasterizer.h"
#include "reach.h"
#include "shadowvol_casters.h"
#include "shadowvol_extrude.h"
#include "shadowvol_scene.h"
#include "stencil_method.h"

namespace sv::render {

enum class ModeChoice { zpass, zfail, automatic };
const char *mode_name(ModeChoice m);

/* Which shadow volumes a frame draws: the paper's (silhouette quads and
 * caps from the facing routines) or seed 002's (issue 31: every surface's
 * shadow mesh through the vertex program emulated on the CPU, drawn whole
 * in z-fail; extruded_volumes.h). */
enum class VolumeSource { silhouette, extrude };

/* Only what the scene requires (DESIGN.md section 9; issue 13): each
 * shortcut is a conservative test made per frame, light and surface,
 * counted in the frame's decisions, and switchable off. With all of them
 * off (Shortcuts::none(), the CLI's --full) every surface gets the whole
 * volume (no culling, both caps) drawn in z-fail. */
struct Shortcuts {
    /* 1. No volume when the surface's box is outside a point or spot
     *    light's range, or outside a spot light's cone. */
    bool light_reach = true;
    /* 2. No volume when the box extruded from the light (its shadow's
     *    hull, to infinity) lies wholly outside one plane of the view
     *    frustum: it has no fragment in view. */
    bool view_reach = true;
    /* 3. Appendix B's cull bits only when the box straddles the light
     *    volume (the range's cube, a spot's pyramid); never for a box
     *    wholly inside. Off: no culling at all. */
    bool cull_straddling = true;
    /* 4. Caps only when z-fail is needed (near_plane_may_be_shadowed, in
     *    the automatic mode); otherwise the silhouette quads in z-pass,
     *    and the caps are not even built. Off: z-fail with both caps. */
    bool zpass_when_safe = true;
    /* 5. No dark cap for a directional light: its far vertices are all
     *    the one point at infinity (the light's direction, w = 0), so
     *    every dark-cap triangle has zero area and draws nothing. */
    bool no_directional_dark_cap = true;
    /* 6. A static surface under a static light: the volume (facing, cull
     *    bits, silhouette and caps) built once and reused until either
     *    moves (VolumeCache). */
    bool reuse_static = true;
    /* For the benchmark of test 3 only: the culling routine wherever the
     * light has a volume, even for a box wholly inside it (where it culls
     * nothing: the same pixels, at the routine's cost). */
    bool cull_always = false;
    static Shortcuts none() { return {false, false, false, false, false, false, false}; }
    bool any() const {
        return light_reach || view_reach || cull_straddling || zpass_when_safe ||
               no_directional_dark_cap || reuse_static;
    }
};

/* Deliberately wrong versions of the shortcuts' tests, for the tests that
 * show the proof (shortcuts against --full, pixel for pixel) catches a
 * test that is too tight. Never set outside tests. */
struct ShortcutFaults {
    double light_reach_scale = 1;         /* < 1: ranges and cones shrunk in test 1 */
    bool view_reach_no_extrusion = false; /* test 2 with the box alone, not its shadow */
    bool cull_inside_planes = false;      /* test 3's light volume shrunk to half */
    bool zpass_always = false;            /* test 4 always says z-pass */
    bool drop_dark_cap_always = false;    /* test 5 for point lights too */
    bool reuse_ignores_motion = false;    /* test 6 reuses after a surface moved */
};

enum class VolumeFate : uint8_t {
    built,        /* built this frame */
    reused,       /* taken from the cache: surface and light unchanged */
    out_of_reach, /* shortcut 1 */
    out_of_view,  /* shortcut 2 */
    no_shadow,    /* built, but no triangle casts */
};
const char *fate_name(VolumeFate f);

/* What the frame decided for one light and surface. */
struct VolumeDecision {
    int surface = 0;
    VolumeFate fate = VolumeFate::built;
    bool straddles = false; /* the box straddles the light volume */
    bool cull_bits = false; /* the culling routine ran (or its result was reused) */
    bool zfail = false;     /* drawn in z-fail with caps */
    bool dark_cap_dropped = false;
    bool general_rule = false; /* some shell cast under the general rule (shadowvol_casters.h) */
    int64_t indices_built = 0; /* written by the routines this frame (0 when reused) */
    int64_t indices_drawn = 0;
};

/* Volumes kept from frame to frame (shortcut 6), per light and surface:
 * valid while the surface's revision and the light's parameters are the
 * same. Keep one per scene sequence; a scene whose surfaces or lights
 * change in number must not reuse a cache (it is cleared when they do). */
class VolumeCache {
public:
    void clear();
    /* Sized for NUM_LIGHTS x NUM_SURFACES; cleared when that changes. */
    void fit(int num_lights, int num_surfaces);
    struct Entry;
    /* Per surface: its caster under the frame's rule (shadowvol_casters.h). */
    struct CasterEntry;
    std::vector<CasterEntry> &casters() { return *casters_; }
    ~VolumeCache();
    VolumeCache();
    VolumeCache(const VolumeCache &) = delete;
    VolumeCache &operator=(const VolumeCache &) = delete;
    std::vector<Entry> &entries() { return *entries_; }
    int lights = 0, surfaces = 0;

private:
    std::vector<Entry> *entries_;
    std::vector<CasterEntry> *casters_;
};

/* Buffers one frame fills and the next can fill again: the depth pass's
 * set-up records and bins, the lighting pass's triangle table. Kept by the
 * caller across a sequence of frames (as VolumeCache), their memory stays
 * with the process, where a buffer the size of a frame freed and allocated
 * again each frame is returned to the kernel and faulted in page by page.
 * Used by one render_frame at a time. */
class FrameScratch {
public:
    FrameScratch();
    ~FrameScratch();
    FrameScratch(const FrameScratch &) = delete;
    FrameScratch &operator=(const FrameScratch &) = delete;
    struct Buffers; /* frame_scratch.h */
    Buffers &buffers() { return *buffers_; }

private:
    Buffers *buffers_;
};

struct RenderOptions {
    int width = 1280, height = 1024;
    ModeChoice mode = ModeChoice::automatic;
    StencilMethod stencil = StencilMethod::brute_force; /* how the stencil pass fills */
    int stencil_tile = kDefaultStencilTile;             /* hier's tile side: 4, 8, 16, 32 */
    StencilFaults stencil_faults;                       /* tests only */
    StencilRule stencil_rule;                           /* auto's choice per light */
    /* Seed 002's IncrSat/DecrSat in place of additions modulo 256
     * (StencilPassInputs::saturate): the seed's stencil state. */
    bool stencil_saturate = false;
    VolumeSource volume = VolumeSource::silhouette;
    /* --volume extrude: every extruded vertex to infinity (w = 0), as the
     * paper's, in place of the seed's clamp0(range - |vLP|) for a light
     * with a range. */
    bool extrude_to_infinity = false;
    /* --volume extrude, tests and tools only: called with each surface's
     * shadow mesh once it is built (before any light's program runs) and
     * the caster it was built from (the surface, or its two-sided caster
     * under the caster rule), to give its vertices other normals
     * (skinned_normals.h: the seed's skinned artifact). */
    std::function<void(int surface, const PreparedSurface &caster, ShadowMesh &mesh)>
        shadow_mesh_hook;
    /* --volume extrude, tests and tools only: where set and it returns
     * true, it has written SURFACE's vertex program output (MESH's
     * vertices under LIGHT) in place of the seed's program
     * (skinned_normals.h: the neighbour fix, whose vertices carry their
     * neighbours' positions instead of a normal). */
    std::function<bool(int surface, const ShadowMesh &mesh, const sv_extrude_light &light,
                       Vec4 *out)>
        extrude_program;
    /* Which volume each shell casts: auto (closed shells the paper's
     * rule, the others the general rule: exact for any caster), closed
     * (the paper's everywhere) or general (docs/CASTERS.md). */
    CasterRule caster_rule = CasterRule::automatic;
    /* How the general rule's volumes are built (the same stencil either
     * way): the direct kernels on the general edge table, or the shells
     * made two-sided for the paper's kernels (docs/CASTERS.md). The
     * default is the one `shadowvol bench --casters` measures faster
     * (direct: 0.56-0.74x two-sided's ticks on the open character and the
     * demo terrain); it is not timed during a render. */
    GeneralBuild general_build = GeneralBuild::direct;
    /* Under auto, a surface declared ground keeps the paper's rule
     * (SceneSurface::declared_ground); false: the declarations are
     * ignored, to measure them or check one against the truth. */
    bool ground_hints = true;
    Shortcuts shortcuts;
    ShortcutFaults faults;
    /* Worker threads (oneTBB): 0 = every core; 1 = none. The pictures and
     * counts are the same at every count. */
    int threads = 1;
    VolumeCache *cache = nullptr;                /* shortcut 6 needs one */
    FrameScratch *scratch = nullptr;             /* nullptr: this frame's own */
    const raster::RowKernels *kernels = nullptr; /* nullptr: the best this CPU runs */
    const sv_variant *variant = nullptr;         /* nullptr: sv_best_variant() */
    const sv_facing_variant *facing = nullptr;   /* nullptr: sv_best_facing_variant() */
    double ambient = 0.12;
};

/* Largest frame side and pixel count accepted (a 8192 x 8192 frame needs
 * about 1.2 GiB with the truth's buffers). */
constexpr int kMaxFrameSide = raster::kMaxTargetSide;
constexpr int64_t kMaxFramePixels = 8192LL * 8192LL;
/* Bytes a frame of W x H with L lights needs (target, per-light stencils,
 * colour, truth classes): what the CLI prints before it allocates. */
uint64_t frame_bytes(int width, int height, int lights);

struct Volume {
    int surface = 0;
    AlignedVector<int> indices; /* sv_create_shadow_volume's list, whole */
    int silhouette_indices = 0; /* its first part: the silhouette quads */
    bool zfail = false;         /* drawn in z-fail (all of it) or z-pass (the silhouette part) */
    /* Seed 002's volume (extruded_volumes.h; empty: the paper's): odd
     * vertex 2v + 1 of INDICES is extruded[v] (x, y, z, w), the vertex
     * program's output, in place of the paper's point at infinity. */
    std::vector<Vec4> extruded;
    int drawn_indices() const { return zfail ? (int)indices.size() : silhouette_indices; }
};

struct LightFrame {
    SceneLight light;
    Vec4 shadow_light{};
    std::vector<Volume> volumes;           /* surfaces that cast (a volume with indices) */
    std::vector<VolumeDecision> decisions; /* one per surface */
    int zfail_volumes = 0;
    int built = 0, reused = 0, out_of_reach = 0, out_of_view = 0, culled = 0;
    int64_t indices = 0; /* in all volumes */
    int64_t drawn_indices = 0;
    int64_t built_indices = 0; /* written by the routines this frame */
    /* Work (summed over threads) in the facing, culling and volume
     * routines; wall ticks of the stencil pass. */
    uint64_t ticks_facing = 0, ticks_culling = 0, ticks_volume = 0, ticks_stencil = 0;
    /* --volume extrude: seed 002's vertex program over every volume's
     * shadow mesh (its calls alone, summed over threads: not the shadow
     * meshes' building nor the renumbering, extruded_volumes.h). */
    uint64_t ticks_extrude = 0;
    double seconds_stencil = 0;
    raster::PassCounters stencil_counters;
    std::vector<uint8_t> stencil; /* the stencil after this light's pass */
    /* --stencil hier: its boundary tiles (StencilPassResult). */
    std::vector<uint8_t> stencil_boundary_tiles;
    uint64_t stencil_psv_lines = 0;
    /* --stencil hier: the receiver's caps taken by coverage (StencilPassResult). */
    uint64_t stencil_coverage_rows = 0, stencil_coverage_pixels = 0;
    /* The method that filled this light's stencil (--stencil auto: the
     * one it chose), and the load auto chose by (StencilPassResult). */
    StencilMethod stencil_ran = StencilMethod::brute_force;
    StencilLoad stencil_load;
};

struct Frame {
    int width = 0, height = 0;
    Camera camera;
    Mat4d view_proj;
    std::string kernels;        /* row kernels used */
    std::string variant;        /* the library's kernels used */
    std::string stencil_method; /* the stencil pass's method (stencil_method.h) */
    raster::Target target;      /* depth and ids after the depth pass */
    raster::PassCounters depth_counters;
    uint64_t ticks_depth = 0;
    double seconds_depth = 0;
    uint64_t ticks_shading = 0;         /* the lighting pass, all lights */
    uint64_t shading_divider_lanes = 0; /* its lanes through the light formula's divider */
    uint64_t ticks_jobs = 0;            /* wall ticks of the (light, surface) jobs */
    uint64_t ticks_total = 0;           /* wall ticks of render_frame */
    int threads = 1;                    /* worker threads used */
    std::vector<LightFrame> lights;
    std::vector<uint8_t> rgb; /* shaded image, 3 bytes per pixel, row 0 = top */
    /* The camera ray through pixel centre (px, py):
     * ray_forward + nx * ray_right + ny * ray_up, nx and ny in [-1, 1]. */
    Vec3d ray_forward, ray_right, ray_up;
    /* ids[] = surface_first_id[s] + triangle of surface s. */
    std::vector<int32_t> surface_first_id;
    void decode_id(int32_t id, int &surface, int &triangle) const;
};

/* Is the visible point of pixel PIXEL in light LIGHT's reach at all (its
 * surface reached, and the point inside the range and the cone), shadows
 * aside? Outside it, a culled or skipped volume may leave another stencil
 * (culled triangles cast nothing there), and nothing is lit either way. */
bool pixel_in_light_reach(const Frame &f, const Scene &scene, int light, std::size_t pixel);

/* Two frames of the same scene, pixel for pixel: the proof that the
 * shortcuts change nothing (issue 13). */
struct FrameDifference {
    uint64_t rgb_bytes = 0;      /* shaded bytes that differ */
    uint64_t mask_in_reach = 0;  /* shadow-mask pixels (stencil == 0 or not) that differ in reach */
    uint64_t mask_elsewhere = 0; /* ... out of every light's reach: allowed */
    uint64_t first_rgb = UINT64_MAX, first_mask = UINT64_MAX; /* pixel numbers */
    bool identical() const { return rgb_bytes == 0 && mask_in_reach == 0; }
};
FrameDifference compare_frames(const Scene &scene, const Frame &a, const Frame &b);

/* Renders SCENE (validated: see validate_scene). Throws
 * std::invalid_argument for a frame outside 1..kMaxFrameSide per side or
 * over kMaxFramePixels. */
Frame render_frame(const Scene &scene, const RenderOptions &options);

/* The clip-space position of world point (x, y, z, w) (the rasteriser's
 * input for every vertex, receivers and volumes alike). */
raster::ClipVertex to_clip(const Mat4d &view_proj, double x, double y, double z, double w);

/* Element SV_INDEX of the double-length shadow vertex buffer of P, through
 * the paper's section 3 vertex program, in clip space: even 2v = (x, y, z,
 * 1); odd 2v + 1 = (x L.w - L.x, y L.w - L.y, z L.w - L.z, 0), the point
 * moved to infinity away from the light. The one place the extrusion is
 * computed (its GLSL twin is in src/judge). */
raster::ClipVertex shadow_vertex_to_clip(const Mat4d &view_proj, const PreparedSurface &p,
                                         int sv_index, const Vec4 &L);
/* Vertex SV_INDEX of VOL (of surface P) in clip space: Volume::extruded's
 * where it has it, else shadow_vertex_to_clip's. */
raster::ClipVertex volume_vertex_to_clip(const Mat4d &view_proj, const PreparedSurface &p,
                                         const Volume &vol, int sv_index, const Vec4 &L);

/* The camera ray through window point (x, y) (pixels, y down; a pixel's
 * centre is at + 0.5): unit length along the view axis. */
Vec3d camera_ray(const Frame &f, double x, double y);

/* The world point seen through the centre of pixel (px, py) on triangle
 * T of surface S (the camera ray meets the triangle's plane), in double. */
Vec3d visible_point(const Frame &f, const Scene &scene, int surface, int triangle, int px, int py);

} // namespace sv::render

#endif
