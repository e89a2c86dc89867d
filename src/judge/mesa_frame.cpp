/*
 * The whole frame drawn by Mesa (mesa_frame.h): a second framebuffer on
 * the context's depth-stencil renderbuffer with a GL_RGBA32F colour
 * buffer, two programs for the receivers (ambient, one light), and the
 * passes of a stenciled shadow-volume renderer.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "mesa_gl.h"

namespace sv::gl::detail {

namespace {

/* Receivers, in both of their passes: world position out for the
 * fragment shader. invariant: the lighting pass tests depth EQUAL against
 * the pre-pass, which the same shader with the same input makes exact. */
const char *const kReceiverVertex = R"(#version 450 core
layout(location = 0) in vec3 pos;
uniform mat4 VP;
out vec3 world;
invariant gl_Position;
void main() {
    world = pos;
    gl_Position = VP * vec4(pos, 1.0);
}
)";

/* The pre-pass: ambient times albedo, the ground's checker (0.9 where
 * floor(2x) + floor(2z) is odd), alpha 1 where a surface is. */
const char *const kAmbientFragment = R"(#version 450 core
in vec3 world;
uniform vec3 albedo;
uniform float ambient;
uniform int ground;
out vec4 colour;
void main() {
    float a = ambient;
    if (ground != 0 && mod(floor(world.x * 2.0) + floor(world.z * 2.0), 2.0) != 0.0) a *= 0.9;
    colour = vec4(a * albedo, 1.0);
}
)";

/* One light, as src/render/shading_terms.h's irradiance(), on the front
 * side only; the plane normal from the position's screen derivatives
 * (towards the eye on a front face: window x cross window y). */
const char *const kLightFragment = R"(#version 450 core
in vec3 world;
uniform vec3 albedo, lpos, ldir, lcolor;
uniform int kind;
uniform float intensity, inv_range2, cos_outer, cos_inner;
out vec4 colour;
void main() {
    if (!gl_FrontFacing) discard;
    vec3 n = normalize(cross(dFdx(world), dFdy(world)));
    float a;
    if (kind == 2) {
        a = intensity * max(0.0, -dot(n, ldir));
    } else {
        vec3 d = lpos - world;
        float dist2 = dot(d, d);
        vec3 dir = d * inversesqrt(dist2);
        a = intensity * max(0.0, dot(n, dir)) / dist2;
        if (inv_range2 > 0.0) {
            float q = dist2 * inv_range2;
            float w = clamp(1.0 - q * q, 0.0, 1.0);
            a *= w * w;
        }
        if (kind == 1) {
            float c = -dot(dir, ldir);
            float s = cos_inner > cos_outer
                          ? clamp((c - cos_outer) / (cos_inner - cos_outer), 0.0, 1.0)
                          : (c >= cos_outer ? 1.0 : 0.0);
            a *= s * s;
        }
    }
    colour = vec4(a * lcolor * albedo, 0.0);
}
)";

} // namespace

class FrameDrawer {
public:
    FrameDrawer(const GlApi &gl, int width, int height, GLuint depth_stencil_rb,
                GLuint volume_program, GLint vp_location, GLint light_location)
        : gl_(gl), width_(width), height_(height), volume_program_(volume_program),
          volume_vp_(vp_location), volume_light_(light_location) {
        SV_GL(glGenFramebuffers(1, &fbo_));
        SV_GL(glBindFramebuffer(GL_FRAMEBUFFER, fbo_));
        SV_GL(glGenRenderbuffers(1, &colour_rb_));
        SV_GL(glBindRenderbuffer(GL_RENDERBUFFER, colour_rb_));
        SV_GL(glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA32F, width, height));
        SV_GL(glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                                        colour_rb_));
        SV_GL(glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT,
                                        GL_RENDERBUFFER, depth_stencil_rb));
        SV_GL(glDrawBuffer(GL_COLOR_ATTACHMENT0));
        SV_GL(glReadBuffer(GL_COLOR_ATTACHMENT0));
        const GLenum status = gl_.glCheckFramebufferStatus(GL_FRAMEBUFFER);
        check("glCheckFramebufferStatus");
        if (status != GL_FRAMEBUFFER_COMPLETE)
            throw std::runtime_error("Mesa frame: the RGBA32F framebuffer is incomplete");
        ambient_ = link(kAmbientFragment, "ambient");
        light_ = link(kLightFragment, "light");
    }
    FrameDrawer(const FrameDrawer &) = delete;
    FrameDrawer &operator=(const FrameDrawer &) = delete;
    ~FrameDrawer() {
        if (ambient_) gl_.glDeleteProgram(ambient_);
        if (light_) gl_.glDeleteProgram(light_);
        if (colour_rb_) gl_.glDeleteRenderbuffers(1, &colour_rb_);
        if (fbo_) gl_.glDeleteFramebuffers(1, &fbo_);
        while (gl_.glGetError() != GL_NO_ERROR) {
        }
    }

    MesaFrameResult draw(const MesaFrameJob &job);

private:
    void check(const char *call) const { check_gl(gl_, call); }
    GLuint link(const char *fragment, const char *what);
    GLint uniform(GLuint program, const char *name) const {
        const GLint at = gl_.glGetUniformLocation(program, name);
        check("glGetUniformLocation");
        return at;
    }
    void validate(const MesaFrameJob &job) const;
    /* Appends the light's stencil to OUT.stencils (and with DEPTH the
     * depth to OUT.depth), row 0 at the top: one read of both, packed. */
    void read_depth_stencil(MesaFrameResult &out, bool depth);

    const GlApi &gl_;
    int width_, height_;
    GLuint volume_program_;
    GLint volume_vp_, volume_light_;
    GLuint fbo_ = 0, colour_rb_ = 0, ambient_ = 0, light_ = 0;
};

GLuint FrameDrawer::link(const char *fragment, const char *what) {
    return link_program(gl_, kReceiverVertex, fragment, "Mesa frame", what);
}

void FrameDrawer::validate(const MesaFrameJob &job) const {
    if (job.width != width_ || job.height != height_)
        bad_job("frame size " + std::to_string(job.width) + "x" + std::to_string(job.height) +
                " differs from the context's " + std::to_string(width_) + "x" +
                std::to_string(height_));
    for (double m : job.view_proj)
        if (!std::isfinite(m)) bad_job("view_proj has a non-finite element");
    for (std::size_t s = 0; s < job.surfaces.size(); s++)
        validate_mesh(job.surfaces[s].mesh, "surface " + std::to_string(s));
    for (std::size_t l = 0; l < job.lights.size(); l++) {
        const MesaFrameLight &light = job.lights[l];
        if (light.kind < 0 || light.kind > 2) bad_job("light " + std::to_string(l) + ": kind");
        for (std::size_t v = 0; v < light.volumes.size(); v++)
            validate_volume(light.volumes[v],
                            "light " + std::to_string(l) + " volume " + std::to_string(v));
    }
}

void FrameDrawer::read_depth_stencil(MesaFrameResult &out, bool depth) {
    const std::size_t n = static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_);
    std::vector<uint32_t> packed(2 * n);
    SV_GL(glPixelStorei(GL_PACK_ALIGNMENT, 4));
    SV_GL(glReadPixels(0, 0, width_, height_, GL_DEPTH_STENCIL, GL_FLOAT_32_UNSIGNED_INT_24_8_REV,
                       packed.data()));
    std::vector<uint8_t> stencil(n);
    if (depth) out.depth.assign(n, 0.0f);
    const std::size_t w = static_cast<std::size_t>(width_);
    for (int row = 0; row < height_; ++row) {
        const std::size_t src = static_cast<std::size_t>(height_ - 1 - row) * w;
        const std::size_t dst = static_cast<std::size_t>(row) * w;
        for (std::size_t x = 0; x < w; x++) {
            /* Per pixel: the float depth, then the stencil in the low 8 bits. */
            stencil[dst + x] = static_cast<uint8_t>(packed[2 * (src + x) + 1] & 0xFFu);
            if (depth) std::memcpy(&out.depth[dst + x], &packed[2 * (src + x)], sizeof(float));
        }
    }
    out.stencils.push_back(std::move(stencil));
}

MesaFrameResult FrameDrawer::draw(const MesaFrameJob &job) {
    validate(job);
    GlObjects objects(gl_);
    std::vector<MesaMesh> meshes;
    for (const MesaFrameSurface &s : job.surfaces) meshes.push_back(s.mesh);
    const std::vector<GlDraw> receivers = upload_receivers(gl_, meshes, objects);
    /* Which surface each receiver draw is (upload skips empty meshes). */
    std::vector<std::size_t> surface_of;
    for (std::size_t s = 0; s < job.surfaces.size(); s++)
        if (job.surfaces[s].mesh.num_indices > 0) surface_of.push_back(s);
    std::vector<std::vector<GlDraw>> volumes;
    for (const MesaFrameLight &l : job.lights)
        volumes.push_back(upload_volumes(gl_, l.volumes, objects));

    float vp[16];
    for (int i = 0; i < 16; ++i) vp[i] = static_cast<float>(job.view_proj[i]);
    const GLint ambient_vp = uniform(ambient_, "VP"), ambient_albedo = uniform(ambient_, "albedo"),
                ambient_term = uniform(ambient_, "ambient"),
                ambient_ground = uniform(ambient_, "ground");
    const GLint light_vp = uniform(light_, "VP"), light_albedo = uniform(light_, "albedo"),
                light_pos = uniform(light_, "lpos"), light_dir = uniform(light_, "ldir"),
                light_colour = uniform(light_, "lcolor"), light_kind = uniform(light_, "kind"),
                light_intensity = uniform(light_, "intensity"),
                light_range = uniform(light_, "inv_range2"),
                light_outer = uniform(light_, "cos_outer"),
                light_inner = uniform(light_, "cos_inner");

    SV_GL(glBindFramebuffer(GL_FRAMEBUFFER, fbo_));
    SV_GL(glViewport(0, 0, width_, height_));
    SV_GL(glDisable(GL_DEPTH_CLAMP));
    SV_GL(glDisable(GL_CULL_FACE));
    SV_GL(glDisable(GL_SCISSOR_TEST));
    SV_GL(glDisable(GL_POLYGON_OFFSET_FILL));
    SV_GL(glDisable(GL_RASTERIZER_DISCARD));
    SV_GL(glFrontFace(GL_CCW));
    SV_GL(glEnable(GL_DEPTH_TEST));
    SV_GL(glFinish());

    MesaFrameResult out;
    const auto t_frame = std::chrono::steady_clock::now();
    auto pass_done = [&](double &seconds, std::chrono::steady_clock::time_point t0) {
        if (!job.time_each_pass) return;
        SV_GL(glFinish());
        seconds += seconds_since(t0);
    };

    /* Depth pre-pass with the ambient term. */
    auto t0 = std::chrono::steady_clock::now();
    const float clear_colour[4] = {0, 0, 0, 0};
    SV_GL(glClearBufferfv(GL_COLOR, 0, clear_colour));
    SV_GL(glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE));
    SV_GL(glDepthMask(GL_TRUE));
    SV_GL(glStencilMask(0xFF));
    SV_GL(glClearDepth(1.0));
    SV_GL(glClear(GL_DEPTH_BUFFER_BIT));
    SV_GL(glDepthFunc(GL_LESS));
    SV_GL(glDisable(GL_STENCIL_TEST));
    SV_GL(glDisable(GL_BLEND));
    SV_GL(glUseProgram(ambient_));
    SV_GL(glUniformMatrix4fv(ambient_vp, 1, GL_FALSE, vp));
    SV_GL(glUniform1f(ambient_term, job.ambient));
    for (std::size_t r = 0; r < receivers.size(); r++) {
        const MesaFrameSurface &s = job.surfaces[surface_of[r]];
        SV_GL(glUniform3f(ambient_albedo, s.albedo[0], s.albedo[1], s.albedo[2]));
        SV_GL(glUniform1i(ambient_ground, s.ground ? 1 : 0));
        SV_GL(glBindVertexArray(receivers[r].vao));
        SV_GL(glDrawElements(GL_TRIANGLES, receivers[r].count, GL_UNSIGNED_INT, nullptr));
    }
    pass_done(out.depth_seconds, t0);

    SV_GL(glDepthMask(GL_FALSE));
    for (std::size_t li = 0; li < job.lights.size(); li++) {
        const MesaFrameLight &l = job.lights[li];
        /* The light's volumes into a cleared stencil, no colour. */
        t0 = std::chrono::steady_clock::now();
        SV_GL(glClearStencil(0));
        SV_GL(glClear(GL_STENCIL_BUFFER_BIT));
        SV_GL(glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE));
        SV_GL(glDepthFunc(GL_LESS));
        SV_GL(glEnable(GL_STENCIL_TEST));
        SV_GL(glDisable(GL_BLEND));
        SV_GL(glUseProgram(volume_program_));
        SV_GL(glUniformMatrix4fv(volume_vp_, 1, GL_FALSE, vp));
        SV_GL(glUniform4f(volume_light_, l.shadow_light.x, l.shadow_light.y, l.shadow_light.z,
                          l.shadow_light.w));
        draw_volumes(gl_, volumes[li]);
        pass_done(out.stencil_seconds, t0);
        if (job.read_stencils) read_depth_stencil(out, li == 0);

        /* Its light where the stencil is 0, added. */
        t0 = std::chrono::steady_clock::now();
        SV_GL(glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_FALSE));
        SV_GL(glDepthFunc(GL_EQUAL));
        SV_GL(glStencilFuncSeparate(GL_FRONT_AND_BACK, GL_EQUAL, 0, 0xFF));
        SV_GL(glStencilOpSeparate(GL_FRONT_AND_BACK, GL_KEEP, GL_KEEP, GL_KEEP));
        SV_GL(glEnable(GL_BLEND));
        SV_GL(glBlendEquation(GL_FUNC_ADD));
        SV_GL(glBlendFunc(GL_ONE, GL_ONE));
        SV_GL(glUseProgram(light_));
        SV_GL(glUniformMatrix4fv(light_vp, 1, GL_FALSE, vp));
        SV_GL(glUniform3f(light_pos, l.position[0], l.position[1], l.position[2]));
        SV_GL(glUniform3f(light_dir, l.direction[0], l.direction[1], l.direction[2]));
        SV_GL(glUniform3f(light_colour, l.color[0], l.color[1], l.color[2]));
        SV_GL(glUniform1i(light_kind, l.kind));
        SV_GL(glUniform1f(light_intensity, l.intensity));
        SV_GL(glUniform1f(light_range, l.inv_range2));
        SV_GL(glUniform1f(light_outer, l.cos_outer));
        SV_GL(glUniform1f(light_inner, l.cos_inner));
        for (std::size_t r = 0; r < receivers.size(); r++) {
            const MesaFrameSurface &s = job.surfaces[surface_of[r]];
            SV_GL(glUniform3f(light_albedo, s.albedo[0], s.albedo[1], s.albedo[2]));
            SV_GL(glBindVertexArray(receivers[r].vao));
            SV_GL(glDrawElements(GL_TRIANGLES, receivers[r].count, GL_UNSIGNED_INT, nullptr));
        }
        pass_done(out.lighting_seconds, t0);
    }
    SV_GL(glFinish());
    out.total_seconds = seconds_since(t_frame);
    SV_GL(glDisable(GL_BLEND));
    SV_GL(glDisable(GL_STENCIL_TEST));
    SV_GL(glBindVertexArray(0));

    /* Read back, row 0 at the top. */
    const std::size_t n = static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_);
    std::vector<float> rgba(4 * n);
    SV_GL(glPixelStorei(GL_PACK_ALIGNMENT, 4));
    SV_GL(glReadPixels(0, 0, width_, height_, GL_RGBA, GL_FLOAT, rgba.data()));
    out.radiance.assign(3 * n, 0.0f);
    out.covered.assign(n, 0);
    const std::size_t w = static_cast<std::size_t>(width_);
    for (int row = 0; row < height_; ++row) {
        const std::size_t src = static_cast<std::size_t>(height_ - 1 - row) * w;
        const std::size_t dst = static_cast<std::size_t>(row) * w;
        for (std::size_t x = 0; x < w; x++) {
            const float *p = &rgba[4 * (src + x)];
            std::memcpy(&out.radiance[3 * (dst + x)], p, 3 * sizeof(float));
            out.covered[dst + x] = p[3] > 0.5f ? 1 : 0;
        }
    }
    return out;
}

void FrameDrawerDelete::operator()(FrameDrawer *d) const { delete d; }

FrameDrawerPtr make_frame_drawer(const GlApi &gl, int width, int height, GLuint depth_stencil_rb,
                                 GLuint volume_program, GLint vp_location, GLint light_location) {
    return FrameDrawerPtr(new FrameDrawer(gl, width, height, depth_stencil_rb, volume_program,
                                          vp_location, light_location));
}

MesaFrameResult draw_frame(FrameDrawer &d, const MesaFrameJob &job) { return d.draw(job); }

} // namespace sv::gl::detail
