/*
 * The GLSL judge of seed 002's vertex program (mesa_extrude.h): an OSMesa
 * core context, the program as a vertex shader over GL_POINTS with the
 * rasteriser discarding, its output captured by transform feedback.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "mesa_extrude.h"

#include "mesa_gl.h"

#include <cmath>
#include <cstdint>
#include <stdexcept>

namespace sv::gl {

namespace {

using namespace detail;

/* The seed's program (include/shadowvol_extrude.h has the CPU's): vLP from
 * the light to the point, its length by inversesqrt, facing by the dot
 * with the face normal, then kept, extruded by clamp0(range - |vLP|), or
 * to infinity. `finite` is the CPU's FINITE: a point light with a range. */
const char *const kExtrudeShader = R"(#version 450 core
layout(location = 0) in vec3 pos;
layout(location = 1) in vec3 nrm;
uniform vec4 light;
uniform float range;
uniform int finite;
out vec4 extruded;
void main() {
    vec3 d = pos * light.w - light.xyz;
    float len2 = dot(d, d);
    float inv = inversesqrt(len2);
    vec3 u = d * inv;
    float facing = dot(nrm, u);
    if (facing < 0.0 || !(len2 > 0.0)) {
        extruded = vec4(pos, 1.0);
    } else if (finite != 0) {
        float len = 1.0 / inv;
        float ext = max(range - len, 0.0);
        extruded = vec4(u * ext + pos, 1.0);
    } else {
        extruded = vec4(d, 0.0);
    }
    gl_Position = vec4(0.0, 0.0, 0.0, 1.0);
}
)";

const char *const kEmptyFragment = R"(#version 450 core
void main() {}
)";

/* Transform feedback and the rest this judge needs beyond the Mesa
 * judge's table. */
#define SV_GL_EXTRUDE_FUNCTIONS(X)                                                                 \
    X(glTransformFeedbackVaryings)                                                                 \
    X(glBindBufferBase)                                                                            \
    X(glBeginTransformFeedback)                                                                    \
    X(glEndTransformFeedback)                                                                      \
    X(glDrawArrays)                                                                                \
    X(glGetBufferSubData)

struct ExtrudeApi {
// NOLINTNEXTLINE(bugprone-macro-parentheses): NAME is a GL function's name, not an expression
#define SV_GL_DECLARE(name) decltype(&::name) name = nullptr;
    SV_GL_EXTRUDE_FUNCTIONS(SV_GL_DECLARE)
#undef SV_GL_DECLARE
};

/* FN = the GL function NAME, or a note of it in MISSING. */
template <class F> void load(F &fn, const char *name, std::string &missing) {
    fn = reinterpret_cast<F>(OSMesaGetProcAddress(name));
    if (!fn) missing += std::string(" ") + name;
}

/* One context for one run: made, used and destroyed. */
class ExtrudeContext {
public:
    ExtrudeContext() = default;
    ExtrudeContext(const ExtrudeContext &) = delete;
    ExtrudeContext &operator=(const ExtrudeContext &) = delete;
    ~ExtrudeContext() {
        if (!ctx_) return;
        OSMesaMakeCurrent(nullptr, nullptr, 0, 0, 0);
        OSMesaDestroyContext(ctx_);
    }

    bool init(std::string *why_not) {
        const int attribs[] = {OSMESA_FORMAT,
                               OSMESA_RGBA,
                               OSMESA_PROFILE,
                               OSMESA_CORE_PROFILE,
                               OSMESA_CONTEXT_MAJOR_VERSION,
                               4,
                               OSMESA_CONTEXT_MINOR_VERSION,
                               5,
                               0};
        ctx_ = OSMesaCreateContextAttribs(attribs, nullptr);
        if (!ctx_) {
            if (why_not) *why_not = "OSMesaCreateContextAttribs (GL 4.5 core) failed";
            return false;
        }
        if (!OSMesaMakeCurrent(ctx_, colour_, GL_UNSIGNED_BYTE, 1, 1)) {
            if (why_not) *why_not = "OSMesaMakeCurrent failed";
            return false;
        }
        std::string missing;
#define SV_GL_LOAD_GL(name) load(gl_.name, #name, missing);
#define SV_GL_LOAD_TF(name) load(tf_.name, #name, missing);
        SV_GL_FUNCTIONS(SV_GL_LOAD_GL)
        SV_GL_EXTRUDE_FUNCTIONS(SV_GL_LOAD_TF)
#undef SV_GL_LOAD_GL
#undef SV_GL_LOAD_TF
        if (!missing.empty()) {
            if (why_not) *why_not = "OSMesaGetProcAddress found no" + missing;
            return false;
        }
        return true;
    }

    void check(const char *call) const { check_gl(gl_, call); }

    std::string describe() {
        auto str = [&](GLenum name) {
            const GLubyte *s = gl_.glGetString(name);
            return s ? std::string(reinterpret_cast<const char *>(s)) : std::string("?");
        };
        return str(GL_RENDERER) + ", " + str(GL_VERSION);
    }

    void run(const float *stream, int n, const sv_extrude_light &light, std::vector<Vec4> &out) {
        const GLuint program = link_program(
            gl_, kExtrudeShader, kEmptyFragment, "GLSL judge", "extrusion", [&](GLuint p) {
                const char *varyings[] = {"extruded"};
                tf_.glTransformFeedbackVaryings(p, 1, varyings, GL_INTERLEAVED_ATTRIBS);
                check("glTransformFeedbackVaryings");
            });
        SV_GL(glUseProgram(program));
        const Vec4 &l = light.position;
        SV_GL(glUniform4f(gl_.glGetUniformLocation(program, "light"), l.x, l.y, l.z, l.w));
        /* The CPU's FINITE (shadowvol_extrude.h). */
        const bool finite = l.w != 0.0f && light.range > 0.0f && std::isfinite(light.range);
        SV_GL(glUniform1f(gl_.glGetUniformLocation(program, "range"), light.range));
        SV_GL(glUniform1i(gl_.glGetUniformLocation(program, "finite"), finite ? 1 : 0));

        GLuint vao = 0, buffers[2] = {0, 0};
        SV_GL(glGenVertexArrays(1, &vao));
        SV_GL(glBindVertexArray(vao));
        SV_GL(glGenBuffers(2, buffers));
        SV_GL(glBindBuffer(GL_ARRAY_BUFFER, buffers[0]));
        const GLsizeiptr stride = SV_EXTRUDE_STREAM_FLOATS * sizeof(float);
        SV_GL(glBufferData(GL_ARRAY_BUFFER, stride * n, stream, GL_STATIC_DRAW));
        SV_GL(glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, (GLsizei)stride, nullptr));
        SV_GL(glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, (GLsizei)stride,
                                    reinterpret_cast<const void *>(3 * sizeof(float))));
        SV_GL(glEnableVertexAttribArray(0));
        SV_GL(glEnableVertexAttribArray(1));
        const GLsizeiptr out_bytes = (GLsizeiptr)sizeof(Vec4) * n;
        SV_GL(glBindBuffer(GL_TRANSFORM_FEEDBACK_BUFFER, buffers[1]));
        SV_GL(glBufferData(GL_TRANSFORM_FEEDBACK_BUFFER, out_bytes, nullptr, GL_STATIC_READ));
        tf_.glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, buffers[1]);
        check("glBindBufferBase");
        SV_GL(glEnable(GL_RASTERIZER_DISCARD));
        tf_.glBeginTransformFeedback(GL_POINTS);
        check("glBeginTransformFeedback");
        tf_.glDrawArrays(GL_POINTS, 0, n);
        check("glDrawArrays");
        tf_.glEndTransformFeedback();
        check("glEndTransformFeedback");
        SV_GL(glDisable(GL_RASTERIZER_DISCARD));
        out.assign((std::size_t)n, Vec4{0, 0, 0, 0});
        tf_.glGetBufferSubData(GL_TRANSFORM_FEEDBACK_BUFFER, 0, out_bytes, out.data());
        check("glGetBufferSubData");
        SV_GL(glDeleteBuffers(2, buffers));
        SV_GL(glDeleteVertexArrays(1, &vao));
        SV_GL(glDeleteProgram(program));
    }

private:
    OSMesaContext ctx_ = nullptr;
    uint8_t colour_[4] = {0, 0, 0, 0}; /* OSMesa's 1x1 window buffer */
    GlApi gl_;
    ExtrudeApi tf_;
};

} // namespace

bool mesa_extrude(const float *stream, int n, const sv_extrude_light &light, std::vector<Vec4> &out,
                  std::string *why_not, std::string *renderer) {
    if (n < 0) throw std::invalid_argument("GLSL judge: a negative vertex count");
    ExtrudeContext ctx;
    if (!ctx.init(why_not)) return false;
    if (renderer) *renderer = ctx.describe();
    if (n == 0) {
        out.clear();
        return true;
    }
    ctx.run(stream, n, light, out);
    return true;
}

bool mesa_extrude_available_at_build() { return true; }

} // namespace sv::gl
