/*
 * Seed 002 on skinned characters (skinned_normals.h): the four ways a
 * vertex gets its face normal, and the faces the program splits.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "skinned_normals.h"

#include <algorithm>
#include <map>
#include <stdexcept>

#include "extrude_internal.h"
#include "shadowvol_planes.h"
#include "shadowvol_skin.h"

namespace sv {

namespace {

/* The 3x3 part of joint J's matrix (column-major, 16 floats) times N,
 * weighted by W, added to OUT: float, one rounding an operation. */
void add_weighted_normal(const float *m, float w, const float n[3], float out[3]) {
    for (int r = 0; r < 3; r++) {
        const float v = (m[r] * n[0] + m[4 + r] * n[1]) + m[8 + r] * n[2];
        out[r] += w * v;
    }
}

/* The rest (mesh-space) face normals: the planes' a, b, c. */
std::vector<Plane> rest_planes(const AnimatedSurface &s) {
    std::vector<Plane> p((std::size_t)s.prepared.num_triangles());
    sv_derive_planes_c_ref(s.rest_positions.data(), s.prepared.indices.data(),
                           s.prepared.num_triangles(), p.data());
    return p;
}

} // namespace

const char *skinned_normals_name(SkinnedNormals n) {
    switch (n) {
    case SkinnedNormals::straightforward: return "straightforward";
    case SkinnedNormals::face_weights: return "face weights";
    case SkinnedNormals::recomputed: return "recomputed";
    case SkinnedNormals::neighbours: return "neighbours";
    }
    return "?";
}

bool skinned_normals_by_option(const std::string &name, SkinnedNormals &out) {
    for (SkinnedNormals n : kAllSkinnedNormals) {
        std::string option = skinned_normals_name(n);
        std::replace(option.begin(), option.end(), ' ', '-');
        if (option == name) {
            out = n;
            return true;
        }
    }
    return false;
}

SkinnedFrame skinned_frame(const AnimatedAsset &asset, const AnimatedSurface &s, const Pose &pose) {
    SkinnedFrame f;
    f.positions.resize(s.rest_positions.size());
    if (s.skin < 0 || s.influences == 0) {
        pose_surface(asset, s, pose, Mat4d{}, f.positions.data());
        return f;
    }
    f.joint_matrices.resize(16 * asset.skins[(std::size_t)s.skin].joints.size());
    joint_matrices(asset, s.skin, pose, Mat4d{}, f.joint_matrices.data());
    sv_skin_c_ref(f.joint_matrices.data(), s.rest_positions.data(), s.joints.data(),
                  s.weights.data(), s.influences, (size_t)s.num_vertices(), f.positions.data());
    return f;
}

SkinnedNormalData skinned_normal_data(const AnimatedSurface &s) {
    SkinnedNormalData d;
    d.rest_planes = rest_planes(s);
    const int faces = s.prepared.num_triangles(), inf = s.influences;
    const int *ix = s.prepared.indices.data();
    d.face_start.assign((std::size_t)faces + 1, 0);
    for (int t = 0; t < faces && s.skin >= 0 && inf > 0; t++) {
        std::map<int, float> w;
        for (int k = 0; k < 3; k++) {
            const std::size_t v = (std::size_t)ix[3 * t + k];
            for (int i = 0; i < inf; i++) {
                w[s.joints[v * (std::size_t)inf + (std::size_t)i]] +=
                    s.weights[v * (std::size_t)inf + (std::size_t)i];
            }
        }
        for (const auto &[j, wsum] : w) {
            if (wsum == 0.0f) continue;
            d.face_joints.push_back((uint16_t)j);
            d.face_weights.push_back(wsum / 3.0f);
        }
        d.face_start[(std::size_t)t + 1] = (int)d.face_joints.size();
    }
    return d;
}

void write_skinned_normals(const AnimatedSurface &s, const SkinnedFrame &frame,
                           SkinnedNormals normals, float *stream) {
    write_skinned_normals(s, skinned_normal_data(s), frame, normals, stream);
}

void write_skinned_normals(const AnimatedSurface &s, const SkinnedNormalData &data,
                           const SkinnedFrame &frame, SkinnedNormals normals, float *stream) {
    const PreparedSurface &p = s.prepared;
    const int faces = p.num_triangles();
    const int *ix = p.indices.data();
    const float *pos = frame.positions.data();
    const bool skinned = !frame.joint_matrices.empty();
    /* The neighbours' normal is the skinned face's own: the recomputed one. */
    if (normals == SkinnedNormals::neighbours) normals = SkinnedNormals::recomputed;
    const bool recomputed = normals == SkinnedNormals::recomputed || !skinned;
    std::vector<Plane> planes(recomputed ? (std::size_t)faces : 0);
    /* Every planes variant is bit-identical to sv_derive_planes_c_ref. */
    if (recomputed) sv_best_planes_variant()->derive_planes(pos, ix, faces, planes.data());
    const int inf = s.influences;
    const float *m = frame.joint_matrices.data();
    for (int t = 0; t < faces; t++) {
        float face_normal[3] = {0, 0, 0};
        if (recomputed) {
            const Plane &pl = planes[(std::size_t)t];
            face_normal[0] = pl.a, face_normal[1] = pl.b, face_normal[2] = pl.c;
        } else if (normals == SkinnedNormals::face_weights) {
            /* The face's weights (skinned_normal_data) on the rest normal. */
            const Plane &r = data.rest_planes[(std::size_t)t];
            const float n[3] = {r.a, r.b, r.c};
            for (int e = data.face_start[(std::size_t)t]; e < data.face_start[(std::size_t)t + 1];
                 e++) {
                add_weighted_normal(m + 16 * (std::size_t)data.face_joints[(std::size_t)e],
                                    data.face_weights[(std::size_t)e], n, face_normal);
            }
        }
        for (int k = 0; k < 3; k++) {
            const std::size_t v = (std::size_t)ix[3 * t + k];
            float *out = stream + (3 * (std::size_t)t + (std::size_t)k) * SV_EXTRUDE_STREAM_FLOATS;
            float n[3] = {face_normal[0], face_normal[1], face_normal[2]};
            if (normals == SkinnedNormals::straightforward && !recomputed) {
                /* The vertex's own weights on the rest face normal. */
                const Plane &r = data.rest_planes[(std::size_t)t];
                const float rn[3] = {r.a, r.b, r.c};
                n[0] = n[1] = n[2] = 0;
                for (int i = 0; i < inf; i++) {
                    const float wi = s.weights[v * (std::size_t)inf + (std::size_t)i];
                    if (wi != 0.0f) {
                        add_weighted_normal(
                            m + 16 * (std::size_t)s.joints[v * (std::size_t)inf + (std::size_t)i],
                            wi, rn, n);
                    }
                }
            }
            out[3] = n[0], out[4] = n[1], out[5] = n[2];
        }
    }
}

void write_caster_skinned_normals(const AnimatedSurface &s, const SkinnedNormalData &data,
                                  const SkinnedFrame &frame, SkinnedNormals normals,
                                  const PreparedSurface &caster, float *stream) {
    const int n = s.prepared.num_triangles(), total = caster.num_triangles();
    if (total < n || (total > n && (int)caster.triangle_source.size() != total)) {
        throw std::invalid_argument(
            "write_caster_skinned_normals: the caster is not the surface's or its two-sided one");
    }
    write_skinned_normals(s, data, frame, normals, stream);
    for (int t = n; t < total; t++) {
        const int src = caster.triangle_source[(std::size_t)t];
        if (src < 0 || src >= n) {
            throw std::invalid_argument("write_caster_skinned_normals: a reverse without a source");
        }
        /* Corner k of the reverse (c, b, a) is corner 2 - k of its source. */
        for (int k = 0; k < 3; k++) {
            const float *from = stream + (3 * (std::size_t)src + (std::size_t)(2 - k)) *
                                             SV_EXTRUDE_STREAM_FLOATS;
            float *to = stream + (3 * (std::size_t)t + (std::size_t)k) * SV_EXTRUDE_STREAM_FLOATS;
            to[3] = -from[3], to[4] = -from[4], to[5] = -from[5];
        }
    }
}

void write_neighbour_stream(const int *indices, int faces, const float *positions, float *out) {
    for (std::size_t t = 0; t < (std::size_t)std::max(faces, 0); t++) {
        float corners[9];
        for (std::size_t k = 0; k < 3; k++) {
            const float *p = positions + 3 * (std::size_t)indices[3 * t + k];
            corners[3 * k] = p[0], corners[3 * k + 1] = p[1], corners[3 * k + 2] = p[2];
        }
        for (std::size_t k = 0; k < 3; k++)
            std::copy(corners, corners + 9, out + (3 * t + k) * kNeighbourStreamFloats);
    }
}

std::vector<float> neighbour_stream(const ShadowMesh &mesh) {
    const std::size_t n = (std::size_t)mesh.num_vertices();
    std::vector<float> out(n * kNeighbourStreamFloats);
    for (std::size_t j = 0; j < n; j++) {
        const float *face = mesh.stream.data() + (j - j % 3) * SV_EXTRUDE_STREAM_FLOATS;
        for (std::size_t k = 0; k < 3; k++) {
            for (std::size_t c = 0; c < 3; c++)
                out[j * kNeighbourStreamFloats + 3 * k + c] =
                    face[k * SV_EXTRUDE_STREAM_FLOATS + c];
        }
    }
    return out;
}

void extrude_neighbours(const float *stream, int n, const sv_extrude_light &light, Vec4 *out) {
    const Vec4 &L = light.position;
    const int finite = sv_extrude_finite(&L, light.range);
    for (int j = 0; j < n; j++) {
        const float *c = stream + (std::size_t)j * kNeighbourStreamFloats;
        const float *a = c, *b = c + 3, *d = c + 6;
        const float e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
        const float e2[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
        const float nrm[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                              e1[0] * e2[1] - e1[1] * e2[0]};
        const float to0[3] = {a[0] * L.w - L.x, a[1] * L.w - L.y, a[2] * L.w - L.z};
        const int face_keeps = ((nrm[0] * to0[0] + nrm[1] * to0[1]) + nrm[2] * to0[2]) < 0.0f;
        out[j] = sv_extrude_vertex_facing(c + 3 * (j % 3), nullptr, face_keeps, &L, light.range,
                                          finite, 0);
    }
}

int64_t split_faces(const AnimatedSurface &s, const SkinnedFrame &frame, SkinnedNormals normals,
                    const sv_extrude_light &light) {
    const PreparedSurface &p = s.prepared;
    const int faces = p.num_triangles();
    const int *ix = p.indices.data();
    const float *pos = frame.positions.data();
    std::vector<float> stream((std::size_t)faces * 3 * SV_EXTRUDE_STREAM_FLOATS);
    for (std::size_t j = 0; j < 3 * (std::size_t)faces; j++) {
        const std::size_t v = (std::size_t)ix[j];
        float *out = &stream[j * SV_EXTRUDE_STREAM_FLOATS];
        out[0] = pos[3 * v], out[1] = pos[3 * v + 1], out[2] = pos[3 * v + 2];
    }
    const int n = 3 * faces;
    std::vector<Vec4> out((std::size_t)n);
    if (normals == SkinnedNormals::neighbours) {
        ShadowMesh m;
        m.stream.assign(stream.begin(), stream.end());
        extrude_neighbours(neighbour_stream(m).data(), n, light, out.data());
    } else {
        write_skinned_normals(s, frame, normals, stream.data());
        sv_extrude_c_ref(stream.data(), n, &light, out.data());
    }
    int64_t split = 0;
    for (int t = 0; t < faces; t++) {
        bool kept[3];
        for (int k = 0; k < 3; k++) {
            const float *v =
                &stream[(3 * (std::size_t)t + (std::size_t)k) * SV_EXTRUDE_STREAM_FLOATS];
            const Vec4 &o = out[3 * (std::size_t)t + (std::size_t)k];
            kept[k] = o.w == 1.0f && o.x == v[0] && o.y == v[1] && o.z == v[2];
        }
        split += kept[0] != kept[1] || kept[1] != kept[2];
    }
    return split;
}

} // namespace sv
