/*
 * What the Mesa judges share (mesa_gl.h): GL error checks, job
 * validation, the upload of receivers and volumes, and the volumes drawn
 * into the stencil.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "mesa_gl.h"

#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>

namespace sv::gl::detail {

void check_gl(const GlApi &gl, const char *call) {
    const GLenum e = gl.glGetError();
    if (e == GL_NO_ERROR) return;
    std::string msg = std::string("OpenGL error ") + gl_error_name(e) + " after " + call;
    for (int i = 0; i < 16 && gl.glGetError() != GL_NO_ERROR; ++i) {
    }
    throw std::runtime_error(msg);
}

void bad_job(const std::string &what) { throw std::runtime_error("Mesa judge: bad job: " + what); }

namespace {

void check_indices(const int *indices, int num_indices, int num_vertices, const std::string &who) {
    if (num_indices < 0)
        bad_job(who + ": num_indices " + std::to_string(num_indices) + " is negative");
    if (num_indices % 3 != 0)
        bad_job(who + ": num_indices " + std::to_string(num_indices) + " is not a multiple of 3");
    if (num_indices > 0 && !indices)
        bad_job(who + ": indices is null with num_indices " + std::to_string(num_indices));
    for (int i = 0; i < num_indices; ++i)
        if (indices[i] < 0 || indices[i] >= num_vertices)
            bad_job(who + ": index " + std::to_string(i) + " = " + std::to_string(indices[i]) +
                    " is outside the " + std::to_string(num_vertices) + " vertices");
}

void check_vertices(const void *p, int n, const std::string &who) {
    if (n < 0) bad_job(who + ": vertex count " + std::to_string(n) + " is negative");
    if (n > 0 && !p) bad_job(who + ": vertices are null with a count of " + std::to_string(n));
}

} // namespace

void validate_mesh(const MesaMesh &m, const std::string &who) {
    check_vertices(m.positions, m.num_vertices, who);
    if (static_cast<size_t>(m.num_vertices) > SIZE_MAX / (3 * sizeof(float)))
        bad_job(who + ": too many vertices");
    check_indices(m.indices, m.num_indices, m.num_vertices, who);
}

void validate_volume(const MesaVolume &v, const std::string &who) {
    check_vertices(v.shadow_vertices, v.num_shadow_vertices, who);
    check_indices(v.indices, v.num_indices, v.num_shadow_vertices, who);
}

GlObjects::GlObjects(const GlApi &api) : gl(api) {}

GlObjects::~GlObjects() {
    if (!arrays.empty())
        gl.glDeleteVertexArrays(static_cast<GLsizei>(arrays.size()), arrays.data());
    if (!buffers.empty()) gl.glDeleteBuffers(static_cast<GLsizei>(buffers.size()), buffers.data());
    while (gl.glGetError() != GL_NO_ERROR) {
    }
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::vector<GlDraw> upload_receivers(const GlApi &gl, const std::vector<MesaMesh> &receivers,
                                     GlObjects &objects) {
    const GlApi &gl_ = gl; /* SV_GL's names */
    auto check = [&](const char *call) { check_gl(gl_, call); };
    std::vector<GlDraw> draws;
    for (const MesaMesh &m : receivers) {
        if (m.num_indices == 0) continue;
        GLuint vao = 0, bufs[2] = {0, 0};
        SV_GL(glGenVertexArrays(1, &vao));
        objects.arrays.push_back(vao);
        SV_GL(glGenBuffers(2, bufs));
        objects.buffers.insert(objects.buffers.end(), bufs, bufs + 2);
        SV_GL(glBindVertexArray(vao));
        SV_GL(glBindBuffer(GL_ARRAY_BUFFER, bufs[0]));
        SV_GL(glBufferData(GL_ARRAY_BUFFER,
                           static_cast<GLsizeiptr>(sizeof(float) * 3 *
                                                   static_cast<size_t>(m.num_vertices)),
                           m.positions, GL_STATIC_DRAW));
        SV_GL(glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr));
        SV_GL(glEnableVertexAttribArray(0));
        SV_GL(glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, bufs[1]));
        SV_GL(
            glBufferData(GL_ELEMENT_ARRAY_BUFFER,
                         static_cast<GLsizeiptr>(sizeof(int) * static_cast<size_t>(m.num_indices)),
                         m.indices, GL_STATIC_DRAW));
        draws.push_back({vao, m.num_indices, 0, false});
    }
    return draws;
}

std::vector<GlDraw> upload_volumes(const GlApi &gl, const std::vector<MesaVolume> &volumes,
                                   GlObjects &objects) {
    const GlApi &gl_ = gl; /* SV_GL's names */
    auto check = [&](const char *call) { check_gl(gl_, call); };
    std::vector<GlDraw> draws;
    size_t total_volume_indices = 0;
    for (const MesaVolume &v : volumes) total_volume_indices += static_cast<size_t>(v.num_indices);
    if (total_volume_indices == 0) return draws;
    std::vector<int> all_indices;
    all_indices.reserve(total_volume_indices);
    GLuint index_buffer = 0;
    SV_GL(glGenBuffers(1, &index_buffer));
    objects.buffers.push_back(index_buffer);
    std::map<std::pair<const Vec4 *, int>, GLuint> vaos;
    for (const MesaVolume &v : volumes) {
        if (v.num_indices == 0) continue;
        auto key = std::make_pair(v.shadow_vertices, v.num_shadow_vertices);
        auto it = vaos.find(key);
        if (it == vaos.end()) {
            GLuint vao = 0, vbo = 0;
            SV_GL(glGenVertexArrays(1, &vao));
            objects.arrays.push_back(vao);
            SV_GL(glGenBuffers(1, &vbo));
            objects.buffers.push_back(vbo);
            SV_GL(glBindVertexArray(vao));
            SV_GL(glBindBuffer(GL_ARRAY_BUFFER, vbo));
            SV_GL(glBufferData(GL_ARRAY_BUFFER,
                               static_cast<GLsizeiptr>(sizeof(Vec4) *
                                                       static_cast<size_t>(v.num_shadow_vertices)),
                               v.shadow_vertices, GL_STATIC_DRAW));
            SV_GL(glVertexAttribPointer(0, 4, GL_FLOAT, GL_FALSE, sizeof(Vec4), nullptr));
            SV_GL(glEnableVertexAttribArray(0));
            SV_GL(glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, index_buffer));
            it = vaos.emplace(key, vao).first;
        }
        draws.push_back({it->second, v.num_indices, sizeof(int) * all_indices.size(), v.zfail});
        all_indices.insert(all_indices.end(), v.indices, v.indices + v.num_indices);
    }
    /* Filled through a target that is not VAO state (the element binding
     * belongs to the VAOs above, and the core profile has no VAO 0 to bind
     * it to). */
    SV_GL(glBindVertexArray(0));
    SV_GL(glBindBuffer(GL_COPY_WRITE_BUFFER, index_buffer));
    SV_GL(glBufferData(GL_COPY_WRITE_BUFFER,
                       static_cast<GLsizeiptr>(sizeof(int) * all_indices.size()),
                       all_indices.data(), GL_STATIC_DRAW));
    return draws;
}

void draw_volumes(const GlApi &gl, const std::vector<GlDraw> &draws) {
    const GlApi &gl_ = gl; /* SV_GL's names */
    auto check = [&](const char *call) { check_gl(gl_, call); };
    SV_GL(glStencilFuncSeparate(GL_FRONT_AND_BACK, GL_ALWAYS, 0, 0xFF));
    GLuint bound_vao = 0;
    int mode = -1; /* 0 z-pass, 1 z-fail */
    for (const GlDraw &d : draws) {
        if (d.vao != bound_vao) {
            SV_GL(glBindVertexArray(d.vao));
            bound_vao = d.vao;
        }
        if (mode != static_cast<int>(d.zfail)) {
            mode = static_cast<int>(d.zfail);
            if (d.zfail) {
                /* (sfail, dpfail, dppass): count where the depth test fails. */
                SV_GL(glStencilOpSeparate(GL_BACK, GL_KEEP, GL_INCR_WRAP, GL_KEEP));
                SV_GL(glStencilOpSeparate(GL_FRONT, GL_KEEP, GL_DECR_WRAP, GL_KEEP));
            } else {
                SV_GL(glStencilOpSeparate(GL_FRONT, GL_KEEP, GL_KEEP, GL_INCR_WRAP));
                SV_GL(glStencilOpSeparate(GL_BACK, GL_KEEP, GL_KEEP, GL_DECR_WRAP));
            }
        }
        SV_GL(glDrawElements(GL_TRIANGLES, d.count, GL_UNSIGNED_INT,
                             reinterpret_cast<const void *>(d.offset_bytes)));
    }
}

GLuint link_program(const GlApi &gl, const char *vertex, const char *fragment, const char *judge,
                    const char *what, const std::function<void(GLuint)> &before_link) {
    const GlApi &gl_ = gl; /* SV_GL's names */
    auto check = [&](const char *call) { check_gl(gl_, call); };
    const std::string w(what);
    const GLuint vs = compile_shader(gl, GL_VERTEX_SHADER, vertex, (w + " vertex").c_str());
    const GLuint fs = compile_shader(gl, GL_FRAGMENT_SHADER, fragment, (w + " fragment").c_str());
    const GLuint p = gl.glCreateProgram();
    check("glCreateProgram");
    SV_GL(glAttachShader(p, vs));
    SV_GL(glAttachShader(p, fs));
    if (before_link) before_link(p);
    SV_GL(glLinkProgram(p));
    SV_GL(glDeleteShader(vs));
    SV_GL(glDeleteShader(fs));
    GLint linked = 0;
    SV_GL(glGetProgramiv(p, GL_LINK_STATUS, &linked));
    if (!linked) {
        char log[2048] = {};
        gl.glGetProgramInfoLog(p, sizeof log, nullptr, log);
        gl.glDeleteProgram(p);
        throw std::runtime_error(std::string(judge) + ": linking the " + w + " program: " + log);
    }
    return p;
}

GLuint compile_shader(const GlApi &gl, GLenum type, const char *source, const char *what) {
    const GlApi &gl_ = gl; /* SV_GL's names */
    auto check = [&](const char *call) { check_gl(gl_, call); };
    GLuint s = gl.glCreateShader(type);
    check("glCreateShader");
    SV_GL(glShaderSource(s, 1, &source, nullptr));
    SV_GL(glCompileShader(s));
    GLint ok = 0;
    SV_GL(glGetShaderiv(s, GL_COMPILE_STATUS, &ok));
    if (!ok) {
        char log[2048] = {};
        gl.glGetShaderInfoLog(s, sizeof log, nullptr, log);
        gl.glDeleteShader(s);
        throw std::runtime_error(std::string("Mesa judge: compiling the ") + what +
                                 " shader: " + log);
    }
    return s;
}

} // namespace sv::gl::detail
