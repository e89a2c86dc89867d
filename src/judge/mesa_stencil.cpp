/*
 * The Mesa judge (mesa_stencil.h): an OSMesa GL 4.5 core context on
 * llvmpipe, an FBO of GL_DEPTH32F_STENCIL8, and the two passes of a
 * stenciled shadow volume renderer, read back as images (row 0 = top).
 *
 * What llvmpipe does at the pixel level (Mesa 22.3.6, LLVM 15), found by
 * experiment; tests/unit/test_mesa_stencil.cpp's FillRule tests assert every
 * point, so an upgrade that changes one is noticed. In GL WINDOW
 * coordinates (x right, y UP, row 0 at the bottom), drawing into this FBO
 * with GL's default lower-left origin:
 *   - Pixel centres at half-integers: pixel (i, j) is sampled at
 *     (i + 0.5, j + 0.5).
 *   - A centre exactly on an edge is covered iff the triangle's interior is
 *     on the +x side of the edge (a left edge, any slope), or the edge is
 *     exactly horizontal with the interior on the +y side (the triangle's
 *     bottom edge, y up). So for a counter-clockwise (y up) triangle and
 *     its edge A -> B, d = B - A: inclusive iff d.y < 0 || (d.y == 0 &&
 *     d.x > 0); either winding covers the same pixels. In the project's
 *     image coordinates (row 0 at the top, y down) that is a BOTTOM-left
 *     rule: left edges, and the horizontal edge whose triangle lies at
 *     smaller row numbers (above it in the picture). Not Direct3D's
 *     top-left rule in image coordinates.
 *   - Vertex positions are snapped to 1/256 pixel (8 sub-pixel bits),
 *     rounded to nearest; exactly halfway (1/512 off a pixel centre's grid
 *     point, either side) goes onto the centre's point, as round-half-even
 *     does (centres are even multiples of 1/256 from the origin).
 *   - With vertices on the 1/256 grid the coverage is exactly the integer
 *     edge-function rule above (FillRule.RandomTrianglesMatchTheReference-
 *     RuleExactly: every pixel, overlapping triangles, ties and degenerate
 *     ones). Window coordinates come from float arithmetic (VP * p in the
 *     shader, x / w, x * W/2 + W/2): exact for power-of-two sizes and
 *     binary-fraction positions, rounded otherwise (2/1280 is not a binary
 *     fraction), which is what a rasteriser must reproduce at ties.
 *
 * Stencil read-back: glReadPixels(GL_STENCIL_INDEX, GL_UNSIGNED_BYTE) from
 * the FBO works in the core profile on this Mesa; create() checks it with a
 * 1x1 read and falls back to GL_DEPTH_STENCIL /
 * GL_FLOAT_32_UNSIGNED_INT_24_8_REV (one read, both values) where it would
 * not. Depth:
 * glReadPixels(GL_DEPTH_COMPONENT, GL_FLOAT), the float depth buffer's
 * values exactly.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "mesa_stencil.h"

#include "mesa_gl.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace sv::gl {

bool mesa_available_at_build() { return true; }

namespace {

using namespace detail;

/* The paper's section 3 vertex program: a vertex with w = 0 is the far end
 * of an extruded edge, moved to infinity away from the light
 * (xyz * light.w - light.xyz: for a point light, xyz - light; for a
 * directional one, -light). w = 1 vertices (and the receivers, whose vec3
 * attribute GL completes with w = 1) go through unchanged. The w == 0.0
 * comparison is exact: shadow_vertices() writes w as exactly 0 or 1. */
const char *const kVertexShader = R"(#version 450 core
layout(location = 0) in vec4 v;
uniform mat4 VP;
uniform vec4 light;
void main() {
    vec4 p = (v.w == 0.0) ? vec4(v.xyz * light.w - light.xyz, 0.0) : v;
    gl_Position = VP * p;
}
)";

/* No colour is written (there is no colour attachment and colour writes
 * are off); a fragment shader is still linked, as the core profile
 * expects one. */
const char *const kFragmentShader = R"(#version 450 core
void main() {}
)";

/* LP_NUM_THREADS is read once, when llvmpipe's screen is made (the first
 * context of the process); the value that took effect is kept here. */
std::mutex g_env_mutex;
bool g_env_set = false;
int g_lp_threads = 0;

class OsMesaContext final : public MesaContext {
public:
    OsMesaContext() = default;
    OsMesaContext(const OsMesaContext &) = delete;
    OsMesaContext &operator=(const OsMesaContext &) = delete;
    ~OsMesaContext() override { destroy(); }

    bool init(int width, int height, std::string *why_not);
    std::string describe() const override { return description_; }
    MesaStencilResult run(const MesaStencilJob &job) override;
    MesaFrameResult run_frame(const MesaFrameJob &job) override;
    Readback readback() const override { return readback_; }
    void set_readback(Readback r) override { readback_ = r; }
    int lp_num_threads() const override { return g_lp_threads; }

private:
    void check(const char *call) const;
    void make_current() const;
    void read_back(MesaStencilResult &out);
    void destroy();

    OSMesaContext ctx_ = nullptr;
    std::vector<uint8_t> colour_; /* OSMesa's own 1x1 window buffer */
    GlApi gl_;
    int width_ = 0, height_ = 0;
    GLuint fbo_ = 0, depth_stencil_rb_ = 0, program_ = 0;
    GLint vp_location_ = -1, light_location_ = -1;
    std::string description_;
    Readback readback_ = Readback::stencil_index;
    FrameDrawerPtr frame_; /* made by the first run_frame */
};

void OsMesaContext::check(const char *call) const { check_gl(gl_, call); }

void OsMesaContext::make_current() const {
    /* OSMesa wants a colour buffer to make a context current; drawing goes
     * to the FBO, so a 1x1 one is enough. */
    if (!OSMesaMakeCurrent(ctx_, const_cast<uint8_t *>(colour_.data()), GL_UNSIGNED_BYTE, 1, 1))
        throw std::runtime_error("OSMesaMakeCurrent failed");
}

bool OsMesaContext::init(int width, int height, std::string *why_not) {
    auto fail = [&](const std::string &why) {
        if (why_not) *why_not = why;
        return false;
    };
    if (width <= 0 || height <= 0)
        return fail("Mesa judge: size " + std::to_string(width) + "x" + std::to_string(height) +
                    " is not positive");
    width_ = width;
    height_ = height;

    const int attribs[] = {OSMESA_FORMAT,
                           OSMESA_RGBA,
                           OSMESA_DEPTH_BITS,
                           24,
                           OSMESA_STENCIL_BITS,
                           8,
                           OSMESA_PROFILE,
                           OSMESA_CORE_PROFILE,
                           OSMESA_CONTEXT_MAJOR_VERSION,
                           4,
                           OSMESA_CONTEXT_MINOR_VERSION,
                           5,
                           0};
    ctx_ = OSMesaCreateContextAttribs(attribs, nullptr);
    if (!ctx_) return fail("OSMesaCreateContextAttribs (GL 4.5 core, 8-bit stencil) failed");
    colour_.assign(4, 0);
    try {
        make_current();
    } catch (const std::exception &e) {
        return fail(e.what());
    }

    bool missing = false;
    std::string missing_names;
#define SV_GL_LOAD(name)                                                                           \
    gl_.name = reinterpret_cast<decltype(gl_.name)>(OSMesaGetProcAddress(#name));                  \
    if (!gl_.name) {                                                                               \
        missing = true;                                                                            \
        missing_names += " " #name;                                                                \
    }
    SV_GL_FUNCTIONS(SV_GL_LOAD)
#undef SV_GL_LOAD
    if (missing) return fail("OSMesaGetProcAddress found no" + missing_names);

    /* From here on the context exists: a failure is the judge's own bug
     * (or a Mesa that breaks it), thrown, never reported as "no context" --
     * callers and tests skip on nullptr, and must not skip this. */
    {
        auto str = [&](GLenum name) {
            const GLubyte *s = gl_.glGetString(name);
            check("glGetString");
            return s ? std::string(reinterpret_cast<const char *>(s)) : std::string("?");
        };
        description_ = str(GL_RENDERER) + ", " + str(GL_VERSION);

        GLint max_rb = 0, max_vp[2] = {0, 0};
        SV_GL(glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_rb));
        SV_GL(glGetIntegerv(GL_MAX_VIEWPORT_DIMS, max_vp));
        if (width > max_rb || height > max_rb || width > max_vp[0] || height > max_vp[1])
            return fail("Mesa judge: size " + std::to_string(width) + "x" + std::to_string(height) +
                        " exceeds this GL's limits (renderbuffer " + std::to_string(max_rb) +
                        ", viewport " + std::to_string(max_vp[0]) + "x" +
                        std::to_string(max_vp[1]) + ")");

        /* The FBO: depth and stencil only. GL 4.5 needs no colour
         * attachment for completeness when the draw and read buffers are
         * GL_NONE. */
        SV_GL(glGenFramebuffers(1, &fbo_));
        SV_GL(glBindFramebuffer(GL_FRAMEBUFFER, fbo_));
        SV_GL(glGenRenderbuffers(1, &depth_stencil_rb_));
        SV_GL(glBindRenderbuffer(GL_RENDERBUFFER, depth_stencil_rb_));
        SV_GL(glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH32F_STENCIL8, width, height));
        SV_GL(glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT,
                                        GL_RENDERBUFFER, depth_stencil_rb_));
        SV_GL(glDrawBuffer(GL_NONE));
        SV_GL(glReadBuffer(GL_NONE));
        GLenum status = gl_.glCheckFramebufferStatus(GL_FRAMEBUFFER);
        check("glCheckFramebufferStatus");
        if (status != GL_FRAMEBUFFER_COMPLETE) {
            std::ostringstream os;
            os << "Mesa judge: the GL_DEPTH32F_STENCIL8 framebuffer is incomplete (status 0x"
               << std::hex << status << ")";
            throw std::runtime_error(os.str());
        }

        program_ = link_program(gl_, kVertexShader, kFragmentShader, "Mesa judge", "volume");
        vp_location_ = gl_.glGetUniformLocation(program_, "VP");
        check("glGetUniformLocation(VP)");
        light_location_ = gl_.glGetUniformLocation(program_, "light");
        check("glGetUniformLocation(light)");
        if (vp_location_ < 0 || light_location_ < 0)
            throw std::runtime_error("Mesa judge: the vertex shader lost its uniforms");

        /* Can the stencil be read as GL_STENCIL_INDEX here? (Core profiles
         * before GL 4.4 and some drivers refuse it; then read depth and
         * stencil packed.) */
        SV_GL(glPixelStorei(GL_PACK_ALIGNMENT, 1));
        uint8_t probe = 0xAB;
        gl_.glReadPixels(0, 0, 1, 1, GL_STENCIL_INDEX, GL_UNSIGNED_BYTE, &probe);
        if (gl_.glGetError() == GL_NO_ERROR && probe == 0) {
            readback_ = Readback::stencil_index;
        } else {
            while (gl_.glGetError() != GL_NO_ERROR) {
            }
            readback_ = Readback::depth_stencil_packed;
        }
    }
    return true;
}

void OsMesaContext::destroy() {
    if (!ctx_) return;
    /* Objects die with the context; deleting them first keeps a context
     * that shares nothing from holding them any longer than it lives. */
    if (OSMesaMakeCurrent(ctx_, colour_.data(), GL_UNSIGNED_BYTE, 1, 1) && gl_.glDeleteProgram) {
        frame_.reset();
        if (program_) gl_.glDeleteProgram(program_);
        if (depth_stencil_rb_) gl_.glDeleteRenderbuffers(1, &depth_stencil_rb_);
        if (fbo_) gl_.glDeleteFramebuffers(1, &fbo_);
        while (gl_.glGetError() != GL_NO_ERROR) {
        }
    }
    /* Unbound first, so this thread is not left with a destroyed context
     * current. (OSMesa 22.3.6 still keeps about 150 bytes of each
     * context's window buffer: tests/support/lsan_osmesa.supp.) */
    OSMesaMakeCurrent(nullptr, nullptr, 0, 0, 0);
    OSMesaDestroyContext(ctx_);
    ctx_ = nullptr;
}

void validate(const MesaStencilJob &job, int width, int height) {
    if (job.width != width || job.height != height)
        bad_job("size " + std::to_string(job.width) + "x" + std::to_string(job.height) +
                " differs from the context's " + std::to_string(width) + "x" +
                std::to_string(height));
    for (double m : job.view_proj)
        if (!std::isfinite(m)) bad_job("view_proj has a non-finite element");
    if (!std::isfinite(job.light.x) || !std::isfinite(job.light.y) || !std::isfinite(job.light.z) ||
        !std::isfinite(job.light.w))
        bad_job("the light has a non-finite coordinate");
    for (size_t r = 0; r < job.receivers.size(); ++r)
        validate_mesh(job.receivers[r], "receiver " + std::to_string(r));
    for (size_t v = 0; v < job.volumes.size(); ++v)
        validate_volume(job.volumes[v], "volume " + std::to_string(v));
}

} // namespace

void OsMesaContext::read_back(MesaStencilResult &out) {
    const size_t n = static_cast<size_t>(width_) * static_cast<size_t>(height_);
    out.stencil.assign(n, 0);
    out.depth.assign(n, 0.0f);
    std::vector<float> depth(n);
    std::vector<uint8_t> stencil(n);
    SV_GL(glPixelStorei(GL_PACK_ALIGNMENT, 1));
    if (readback_ == Readback::stencil_index) {
        SV_GL(glReadPixels(0, 0, width_, height_, GL_STENCIL_INDEX, GL_UNSIGNED_BYTE,
                           stencil.data()));
        SV_GL(glReadPixels(0, 0, width_, height_, GL_DEPTH_COMPONENT, GL_FLOAT, depth.data()));
    } else {
        /* Per pixel: the float depth, then a 32-bit word with the stencil
         * in its 8 low bits (the other 24 unused). */
        std::vector<uint32_t> packed(2 * n);
        SV_GL(glReadPixels(0, 0, width_, height_, GL_DEPTH_STENCIL,
                           GL_FLOAT_32_UNSIGNED_INT_24_8_REV, packed.data()));
        for (size_t i = 0; i < n; ++i) {
            std::memcpy(&depth[i], &packed[2 * i], sizeof(float));
            stencil[i] = static_cast<uint8_t>(packed[2 * i + 1] & 0xFFu);
        }
    }
    /* GL's row 0 is the bottom; the project's is the top. */
    const size_t w = static_cast<size_t>(width_);
    for (int row = 0; row < height_; ++row) {
        const size_t src = static_cast<size_t>(height_ - 1 - row) * w;
        const size_t dst = static_cast<size_t>(row) * w;
        std::memcpy(&out.stencil[dst], &stencil[src], w);
        std::memcpy(&out.depth[dst], &depth[src], w * sizeof(float));
    }
}

MesaStencilResult OsMesaContext::run(const MesaStencilJob &job) {
    validate(job, width_, height_);
    make_current();
    while (gl_.glGetError() != GL_NO_ERROR) {
    }
    GlObjects objects(gl_);

    const std::vector<GlDraw> receiver_draws = upload_receivers(gl_, job.receivers, objects);
    const std::vector<GlDraw> volume_draws = upload_volumes(gl_, job.volumes, objects);

    /* The matrix in float, column-major as given. */
    float vp[16];
    for (int i = 0; i < 16; ++i) vp[i] = static_cast<float>(job.view_proj[i]);
    SV_GL(glUseProgram(program_));
    SV_GL(glUniformMatrix4fv(vp_location_, 1, GL_FALSE, vp));
    SV_GL(glUniform4f(light_location_, job.light.x, job.light.y, job.light.z, job.light.w));

    /* State both passes share. No depth clamp (the projection's epsilon
     * keeps points at infinity inside the far plane), no culling (both
     * sides of a receiver write depth; both sides of a volume count),
     * counter-clockwise front faces, no scissor, no colour. */
    SV_GL(glBindFramebuffer(GL_FRAMEBUFFER, fbo_));
    SV_GL(glViewport(0, 0, width_, height_));
    SV_GL(glDisable(GL_DEPTH_CLAMP));
    SV_GL(glDisable(GL_CULL_FACE));
    SV_GL(glDisable(GL_SCISSOR_TEST));
    SV_GL(glDisable(GL_BLEND));
    SV_GL(glDisable(GL_POLYGON_OFFSET_FILL));
    SV_GL(glDisable(GL_RASTERIZER_DISCARD));
    SV_GL(glFrontFace(GL_CCW));
    SV_GL(glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE));
    SV_GL(glEnable(GL_DEPTH_TEST));
    SV_GL(glDepthFunc(GL_LESS));

    MesaStencilResult out;
    SV_GL(glFinish());

    /* Depth pass: clear (depth 1, stencil 0), receivers with depth writes,
     * the stencil untouched. */
    auto t0 = std::chrono::steady_clock::now();
    SV_GL(glDepthMask(GL_TRUE));
    SV_GL(glStencilMask(0xFF));
    SV_GL(glClearDepth(1.0));
    SV_GL(glClearStencil(0));
    SV_GL(glClear(GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT));
    SV_GL(glDisable(GL_STENCIL_TEST));
    for (const GlDraw &d : receiver_draws) {
        SV_GL(glBindVertexArray(d.vao));
        SV_GL(glDrawElements(GL_TRIANGLES, d.count, GL_UNSIGNED_INT, nullptr));
    }
    SV_GL(glFinish());
    out.depth_pass_seconds = seconds_since(t0);

    /* Stencil pass: depth read-only, two-sided wrap-around counts. */
    auto t1 = std::chrono::steady_clock::now();
    SV_GL(glDepthMask(GL_FALSE));
    SV_GL(glEnable(GL_STENCIL_TEST));
    draw_volumes(gl_, volume_draws);
    SV_GL(glFinish());
    out.stencil_pass_seconds = seconds_since(t1);

    SV_GL(glBindVertexArray(0));
    read_back(out);
    return out;
}

MesaFrameResult OsMesaContext::run_frame(const MesaFrameJob &job) {
    make_current();
    while (gl_.glGetError() != GL_NO_ERROR) {
    }
    if (!frame_) {
        frame_ = make_frame_drawer(gl_, width_, height_, depth_stencil_rb_, program_, vp_location_,
                                   light_location_);
    }
    return draw_frame(*frame_, job);
}

std::unique_ptr<MesaContext> MesaContext::create(int width, int height, int threads,
                                                 std::string *why_not) {
    {
        std::lock_guard<std::mutex> lock(g_env_mutex);
        if (!g_env_set) {
            /* llvmpipe, not softpipe or a GPU driver: its rules are what
             * the tests pin down. */
            setenv("GALLIUM_DRIVER", "llvmpipe", 1);
            if (threads > 0) setenv("LP_NUM_THREADS", std::to_string(threads).c_str(), 1);
            const char *env = getenv("LP_NUM_THREADS");
            g_lp_threads = env ? std::atoi(env) : 0;
            g_env_set = true;
        }
    }
    auto ctx = std::make_unique<OsMesaContext>();
    if (!ctx->init(width, height, why_not)) return nullptr;
    return ctx;
}

} // namespace sv::gl
