/*
 * The GL entry points the Mesa judges use (internal to src/judge): loaded
 * through OSMesaGetProcAddress into a table, so nothing links against
 * libGL, and shared by the stencil judge (mesa_stencil.cpp) and the whole
 * frame drawn by Mesa (mesa_frame.cpp).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_GLJUDGE_MESA_GL_H
#define SV_GLJUDGE_MESA_GL_H

/* Prototypes of every GL entry point (never called directly: the functions
 * come from OSMesaGetProcAddress, and decltype(&::glX) below only reads a
 * prototype's type, so nothing links against libGL). */
#define GL_GLEXT_PROTOTYPES 1
#include <GL/osmesa.h>

#include <chrono>
#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "mesa_frame.h"
#include "mesa_stencil.h"

namespace sv::gl::detail {

/* The GL functions the judge uses. */
#define SV_GL_FUNCTIONS(X)                                                                         \
    X(glGetError)                                                                                  \
    X(glGetString)                                                                                 \
    X(glGetIntegerv)                                                                               \
    X(glViewport)                                                                                  \
    X(glEnable)                                                                                    \
    X(glDisable)                                                                                   \
    X(glClear)                                                                                     \
    X(glClearDepth)                                                                                \
    X(glClearStencil)                                                                              \
    X(glDepthFunc)                                                                                 \
    X(glDepthMask)                                                                                 \
    X(glColorMask)                                                                                 \
    X(glStencilMask)                                                                               \
    X(glStencilFuncSeparate)                                                                       \
    X(glStencilOpSeparate)                                                                         \
    X(glFrontFace)                                                                                 \
    X(glFinish)                                                                                    \
    X(glReadPixels)                                                                                \
    X(glPixelStorei)                                                                               \
    X(glDrawBuffer)                                                                                \
    X(glReadBuffer)                                                                                \
    X(glGenFramebuffers)                                                                           \
    X(glBindFramebuffer)                                                                           \
    X(glDeleteFramebuffers)                                                                        \
    X(glGenRenderbuffers)                                                                          \
    X(glBindRenderbuffer)                                                                          \
    X(glDeleteRenderbuffers)                                                                       \
    X(glRenderbufferStorage)                                                                       \
    X(glFramebufferRenderbuffer)                                                                   \
    X(glCheckFramebufferStatus)                                                                    \
    X(glCreateShader)                                                                              \
    X(glShaderSource)                                                                              \
    X(glCompileShader)                                                                             \
    X(glGetShaderiv)                                                                               \
    X(glGetShaderInfoLog)                                                                          \
    X(glDeleteShader)                                                                              \
    X(glCreateProgram)                                                                             \
    X(glAttachShader)                                                                              \
    X(glLinkProgram)                                                                               \
    X(glGetProgramiv)                                                                              \
    X(glGetProgramInfoLog)                                                                         \
    X(glDeleteProgram)                                                                             \
    X(glUseProgram)                                                                                \
    X(glGetUniformLocation)                                                                        \
    X(glUniformMatrix4fv)                                                                          \
    X(glUniform4f)                                                                                 \
    X(glGenVertexArrays)                                                                           \
    X(glBindVertexArray)                                                                           \
    X(glDeleteVertexArrays)                                                                        \
    X(glGenBuffers)                                                                                \
    X(glBindBuffer)                                                                                \
    X(glBufferData)                                                                                \
    X(glDeleteBuffers)                                                                             \
    X(glVertexAttribPointer)                                                                       \
    X(glEnableVertexAttribArray)                                                                   \
    X(glDrawElements)                                                                              \
    X(glBlendFunc)                                                                                 \
    X(glBlendEquation)                                                                             \
    X(glClearBufferfv)                                                                             \
    X(glUniform1i)                                                                                 \
    X(glUniform1f)                                                                                 \
    X(glUniform3f)

struct GlApi {
// NOLINTNEXTLINE(bugprone-macro-parentheses): NAME is a GL function's name, not an expression
#define SV_GL_DECLARE(name) decltype(&::name) name = nullptr;
    SV_GL_FUNCTIONS(SV_GL_DECLARE)
#undef SV_GL_DECLARE
};

inline const char *gl_error_name(GLenum e) {
    switch (e) {
    case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
    case GL_STACK_OVERFLOW: return "GL_STACK_OVERFLOW";
    case GL_STACK_UNDERFLOW: return "GL_STACK_UNDERFLOW";
    default: return "unknown GL error";
    }
}

/* Every GL call goes through this, in a class with members gl_ (GlApi)
 * and check(const char *): the call, then glGetError, naming the call in
 * the exception. */
#define SV_GL(call)                                                                                \
    do {                                                                                           \
        gl_.call;                                                                                  \
        check(#call);                                                                              \
    } while (0)

/* Throws std::runtime_error naming CALL when GL reports an error (and
 * drains the rest, so the next call starts clean). */
void check_gl(const GlApi &gl, const char *call);

/* A job that does not fit: std::runtime_error "Mesa judge: bad job: ...". */
[[noreturn]] void bad_job(const std::string &what);
/* Checked on the CPU before any GL call reads them: counts not negative,
 * pointers present, every index a multiple of 3 within the vertices (GL
 * would read past the buffer, perhaps crash llvmpipe). WHO names it. */
void validate_mesh(const MesaMesh &m, const std::string &who);
void validate_volume(const MesaVolume &v, const std::string &who);

/* GL objects that live for one run: deleted on every way out. */
struct GlObjects {
    const GlApi &gl;
    std::vector<GLuint> buffers, arrays;
    explicit GlObjects(const GlApi &api);
    GlObjects(const GlObjects &) = delete;
    GlObjects &operator=(const GlObjects &) = delete;
    ~GlObjects();
};

/* One glDrawElements: a VAO, its count and offset into the element buffer. */
struct GlDraw {
    GLuint vao;
    GLsizei count;
    std::size_t offset_bytes;
    bool zfail;
};

/* Uploaded before any timed pass, so the times are drawing only.
 * Receivers: one VAO each, vec3 positions (the shader sees (x, y, z, 1)).
 * Volumes: one VAO per distinct shadow vertex buffer (many volumes of one
 * mesh share it), their indices in one buffer. */
std::vector<GlDraw> upload_receivers(const GlApi &gl, const std::vector<MesaMesh> &receivers,
                                     GlObjects &objects);
std::vector<GlDraw> upload_volumes(const GlApi &gl, const std::vector<MesaVolume> &volumes,
                                   GlObjects &objects);
/* The volumes into the stencil (the volume program bound, depth read-only,
 * the stencil test on): two-sided wrap-around counts, z-pass or z-fail per
 * draw. */
void draw_volumes(const GlApi &gl, const std::vector<GlDraw> &draws);

double seconds_since(std::chrono::steady_clock::time_point t0);

/* A compiled shader, or std::runtime_error with its log ("... the WHAT
 * shader: ..."). */
GLuint compile_shader(const GlApi &gl, GLenum type, const char *source, const char *what);
/* A program of the two shaders' SOURCES, linked (the shaders deleted once
 * attached), or std::runtime_error with its log ("JUDGE: linking the WHAT
 * program: ..."). BEFORE_LINK, where given, runs between attaching and
 * linking (transform feedback's varyings are named then). */
GLuint link_program(const GlApi &gl, const char *vertex, const char *fragment, const char *judge,
                    const char *what, const std::function<void(GLuint)> &before_link = {});

/* The whole frame (mesa_frame.cpp): its colour buffer, programs and
 * passes, made on a context's first run_frame and kept with it. */
class FrameDrawer;
struct FrameDrawerDelete {
    void operator()(FrameDrawer *d) const; /* the context current */
};
using FrameDrawerPtr = std::unique_ptr<FrameDrawer, FrameDrawerDelete>;
/* DEPTH_STENCIL_RB: the context's GL_DEPTH32F_STENCIL8 renderbuffer;
 * VOLUME_PROGRAM with its VP and light uniforms: the stencil judge's. */
FrameDrawerPtr make_frame_drawer(const GlApi &gl, int width, int height, GLuint depth_stencil_rb,
                                 GLuint volume_program, GLint vp_location, GLint light_location);
MesaFrameResult draw_frame(FrameDrawer &d, const MesaFrameJob &job);

} // namespace sv::gl::detail

#endif
