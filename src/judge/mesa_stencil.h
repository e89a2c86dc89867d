/*
 * The second judge of the renderer (issue 12, "Proof 2"): the same shadow
 * volumes drawn by a real OpenGL implementation, Mesa's llvmpipe on the CPU
 * through OSMesa, so the project's own stencil can be compared with it
 * pixel for pixel.
 *
 * The job is exactly what the project's rasteriser gets: receivers drawn in
 * a depth pre-pass; then, per volume, the index list that
 * sv_create_shadow_volume returned, over the double-length shadow vertex
 * buffer, with the paper's section 3 vertex program in GLSL (a vertex with
 * w = 0 is moved away from the light: (xyz * light.w - light.xyz, 0)), and
 * two-sided stencil with INCR_WRAP / DECR_WRAP; the same view-projection
 * matrix (the caller's, with the infinite far plane of Everitt and
 * Kilgard 2002).
 *
 * Coordinates: world positions; clip = view_proj * world (column-major,
 * as GL). Images are returned with row 0 at the TOP (the project's
 * convention); GL's window row 0 is the bottom, so rows are flipped on
 * read-back. Winding: counter-clockwise in GL window space (y up) is front.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_GLJUDGE_MESA_STENCIL_H
#define SV_GLJUDGE_MESA_STENCIL_H

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "shadowvol.h"

namespace sv::gl {

/* A receiver for the depth pre-pass: world positions (x, y, z per vertex)
 * and triangles. Drawn without face culling (both sides write depth). */
struct MesaMesh {
    const float *positions = nullptr;
    int num_vertices = 0;
    const int *indices = nullptr;
    int num_indices = 0; /* multiple of 3 */
};

/* One volume's draw: INDICES (num_indices of them, a multiple of 3) into
 * the double-length buffer SHADOW_VERTICES (element 2v = (x, y, z, 1),
 * 2v + 1 = (x, y, z, 0); shadow_vertices() of shadowvol_mesh.h).
 *   zfail = false: z-pass, front faces INCR_WRAP and back faces DECR_WRAP
 *                  where the depth test (LESS) passes;
 *   zfail = true:  z-fail, back faces INCR_WRAP and front faces DECR_WRAP
 *                  where it fails. */
struct MesaVolume {
    const Vec4 *shadow_vertices = nullptr;
    int num_shadow_vertices = 0;
    const int *indices = nullptr;
    int num_indices = 0;
    bool zfail = false;
    /* Where SHADOW_VERTICES is the volume's own (seed 002's finite
     * extrusion: odd vertices (x, y, z, 1), drawn as they are): kept alive
     * with the draw. */
    std::shared_ptr<const void> own_vertices;
};

struct MesaStencilJob {
    int width = 0, height = 0; /* must equal the context's */
    double view_proj[16] = {}; /* column-major: element (row r, col c) at [c * 4 + r] */
    Vec4 light{0, 0, 0, 1};    /* shadowvol.h's convention: w = 1 point, w = 0 towards the light */
    std::vector<MesaMesh> receivers;
    std::vector<MesaVolume> volumes; /* all into one stencil buffer, cleared to 0 first */
};

struct MesaStencilResult {
    std::vector<uint8_t> stencil;    /* width * height, row 0 = top */
    std::vector<float> depth;        /* window depth in [0, 1] after the pre-pass, row 0 = top */
    double depth_pass_seconds = 0;   /* glFinish to glFinish */
    double stencil_pass_seconds = 0; /* the volumes only, glFinish to glFinish */
};

struct MesaFrameJob;    /* mesa_frame.h */
struct MesaFrameResult; /* mesa_frame.h */

class MesaContext {
public:
    /* An off-screen GL context (OSMesa, llvmpipe) with a WIDTH x HEIGHT
     * framebuffer of 32-bit float depth and 8-bit stencil. THREADS sets
     * LP_NUM_THREADS before the first context is made (1: single-threaded
     * llvmpipe, the comparison); it has effect only once per
     * process. Returns nullptr and sets *why_not when no context can be
     * made (library missing at build time, a size that is not positive or
     * beyond this GL's limits, or OSMesa's context creation fails). Throws
     * std::runtime_error when the context is made but the judge cannot be
     * set up on it (shaders, framebuffer): that is a bug to see, not a
     * reason to skip the comparison. */
    static std::unique_ptr<MesaContext> create(int width, int height, int threads,
                                               std::string *why_not);
    virtual ~MesaContext() = default;
    /* GL_RENDERER and GL_VERSION, e.g. "llvmpipe (LLVM 15.0.6, 256 bits), 4.5 (Core Profile) Mesa 22.3.6". */
    virtual std::string describe() const = 0;
    /* Draws the job and reads back stencil and depth. Throws
     * std::runtime_error on a GL error or a job that does not fit. */
    virtual MesaStencilResult run(const MesaStencilJob &job) = 0;
    /* Draws the whole frame of mesa_frame.h and reads back its radiance.
     * Throws std::runtime_error as run() does. */
    virtual MesaFrameResult run_frame(const MesaFrameJob &job) = 0;

    /* How run() reads the stencil back. create() picks stencil_index when
     * glReadPixels(GL_STENCIL_INDEX, GL_UNSIGNED_BYTE) works on the FBO (it
     * does on Mesa 22.3.6's core profile), else depth_stencil_packed
     * (GL_DEPTH_STENCIL, GL_FLOAT_32_UNSIGNED_INT_24_8_REV: depth and
     * stencil in one read). Both give the same images; set_readback lets a
     * test prove that. */
    enum class Readback { stencil_index, depth_stencil_packed };
    virtual Readback readback() const = 0;
    virtual void set_readback(Readback r) = 0;
    /* The LP_NUM_THREADS this process's llvmpipe was started with (the
     * THREADS of the first create(); 0: llvmpipe's own default, one per
     * CPU). A later create() with other THREADS cannot change it. */
    virtual int lp_num_threads() const = 0;
};

/* True when the build has OSMesa (SV_HAVE_OSMESA). */
bool mesa_available_at_build();

} // namespace sv::gl

#endif
