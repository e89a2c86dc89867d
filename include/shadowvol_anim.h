/*
 * shadowvol: scenes in time from glTF (issue 13): the node hierarchy and
 * its animations (LINEAR, STEP and CUBICSPLINE samplers over translation,
 * rotation and scale), skins and CPU skinning of positions (a C reference
 * and SIMD kernels, bit-identical to it), KHR_lights_punctual lights and
 * perspective cameras on nodes. docs/ANIMATION.md has the whole story.
 *
 * The asset is loaded once; each frame asks for a Pose (one world matrix
 * per node) at a time, and then for the world positions of each surface,
 * the lights and the cameras at that pose. A surface's topology (welding,
 * triangles, SilEdges) is fixed for every frame; only positions (and so
 * planes) change.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SHADOWVOL_ANIM_H
#define SHADOWVOL_ANIM_H

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "shadowvol.h"
#include "shadowvol_gltf.h"   /* GltfError */
#include "shadowvol_mesh.h"   /* PreparedSurface */
#include "shadowvol_plan.h"   /* sv_deform_routine */
#include "shadowvol_planes.h" /* sv_planes_variant */
#include "shadowvol_skin.h"   /* the C kernels and their tables */
#include "shadowvol_scene.h"  /* Mat4d, Vec3d, SceneLight, Camera */

namespace sv {

struct AnimNode {
    std::string name;
    int parent = -1;
    std::vector<int> children;
    int mesh = -1, skin = -1, camera = -1, light = -1; /* glTF indices; -1: none */
    /* The file's local transform: a matrix (has_matrix; such a node cannot
     * be animated, glTF 2.0 section 3.5.2) or T * R * S. rotation is the
     * unit quaternion x y z w (the file's, normalized). */
    bool has_matrix = false;
    Mat4d matrix;
    double translation[3] = {0, 0, 0};
    double rotation[4] = {0, 0, 0, 1};
    double scale[3] = {1, 1, 1};
    /* The local matrix of the file's pose (matrix, or T * R * S), exactly
     * as load_gltf computes it. */
    Mat4d rest_local;
};

struct AnimSkin {
    std::string name;
    std::vector<int> joints;         /* node per joint */
    std::vector<Mat4d> inverse_bind; /* one per joint (identity when absent) */
    int skeleton = -1;
};

struct AnimChannel {
    int node = -1;
    enum class Path { translation, rotation, scale, weights } path = Path::translation;
    int sampler = -1;
};

struct AnimSampler {
    std::vector<float> input; /* key times in seconds, strictly increasing */
    /* components per key value (3: translation, scale; 4: rotation x y z w);
     * CUBICSPLINE: 3 values per key (in-tangent, value, out-tangent). */
    std::vector<float> output;
    enum class Interp { linear, step, cubicspline } interp = Interp::linear;
    int components = 0;
};

struct Animation {
    std::string name; /* the file's, or "animation#i" */
    /* Channels that drive a pose: "weights" channels (morph targets) are
     * not listed (a note says so). */
    std::vector<AnimChannel> channels;
    std::vector<AnimSampler> samplers;
    /* The earliest and the latest key time of its samplers. */
    double start = 0, end = 0;
};

/* One mesh instance of the scene, as load_gltf places it, in time. */
struct AnimatedSurface {
    std::string name; /* as GltfSurface::name */
    int mesh_index = -1, node_index = -1, skin = -1;
    bool declared_ground = false; /* as GltfSurface::declared_ground */
    /* Topology fixed for every frame: prepare_surface() run once on the
     * MESH-SPACE positions (so welding follows the loader's rule: vertices
     * whose mesh-space positions are bitwise equal weld), with the
     * triangles' winding flipped where the file's pose mirrors them (see
     * mirrored). Then positions and planes replaced by those of the file's
     * pose (pose_at(-1), identity root): `prepared` is the surface at rest,
     * ready for the routines. For another pose, replace its positions by
     * pose_surface()'s and re-derive its planes (prepared_at() does both). */
    PreparedSurface prepared;
    /* 3 per welded vertex, mesh space: the position of the welded vertex's
     * first input vertex (-0.0 stored as +0.0, as prepare_surface does). */
    std::vector<float> rest_positions;
    /* 0 (rigid), 4 (JOINTS_0/WEIGHTS_0) or 8 (also JOINTS_1/WEIGHTS_1). */
    int influences = 0;
    /* influences per welded vertex, the welded vertex's first input vertex's
     * (the loader's weld rule: the first vertex at a position decides).
     * joints index the skin's joint list (each < its size). weights are the
     * file's divided by their sum (in double, then rounded to float; a sum
     * of exactly 1 changes nothing), so the blend is affine; sums off by
     * more than 0.01 get a note. Unused slots have weight 0 and joint 0. */
    std::vector<uint16_t> joints;
    std::vector<float> weights;
    /* Winding flipped (a negative determinant at the file's pose), fixed for
     * every frame: rigid, det(world) < 0 flips every triangle; skinned, the
     * blended matrix of each triangle's first corner decides for that
     * triangle (load_gltf's rule). mirrored == (flipped_triangles > 0). */
    bool mirrored = false;
    std::size_t flipped_triangles = 0;

    int num_vertices() const { return (int)(rest_positions.size() / 3); }
};

/* A KHR_lights_punctual light on a node of the scene. `light` is in the
 * node's local frame: position (0, 0, 0), direction (0, 0, -1); range,
 * cone half-angles (degrees), colour and intensity (candela for point and
 * spot, lux for directional: glTF's units, as the file gives them). */
struct AnimLight {
    int node = -1;
    int index = -1; /* into the file's KHR_lights_punctual.lights */
    std::string name;
    SceneLight light;
};

/* A perspective camera on a node of the scene (orthographic cameras are
 * left out with a note). glTF cameras look down their node's -z, +y up. */
struct AnimCamera {
    int node = -1;
    int index = -1; /* into the file's cameras */
    std::string name;
    double yfov_radians = 0, znear = 0;
    double zfar = 0;   /* 0: infinite */
    double aspect = 0; /* 0: unset */
};

struct AnimatedAsset {
    std::string path;
    std::vector<AnimNode> nodes;
    std::vector<int> scene_roots;
    /* Every node, parents before children (depth-first pre-order from each
     * root in node order): the order pose_at() composes in. */
    std::vector<int> node_order;
    std::vector<AnimSkin> skins;
    std::vector<Animation> animations;
    /* In load_gltf's order (depth-first pre-order of the scene); instances
     * without triangles are left out with a note. May be empty. */
    std::vector<AnimatedSurface> surfaces;
    std::vector<AnimLight> lights;   /* scene order */
    std::vector<AnimCamera> cameras; /* scene order */
    std::vector<std::string> notes;
};

/* Loads a .gltf or .glb with every check load_gltf makes, plus those of
 * animations, skins, lights and cameras (docs/ANIMATION.md lists them).
 * Throws GltfError "<path>: <problem>". */
AnimatedAsset load_animated_gltf(const std::string &path);
/* The same from SIZE bytes in memory (a .glb or .gltf image), NAME standing
 * for the path in messages; buffers by external URI are refused. */
AnimatedAsset load_animated_gltf_memory(const unsigned char *bytes, std::size_t size,
                                        const std::string &name);

/* The animation called NAME_OR_INDEX (a name first; else a decimal index).
 * Throws GltfError "<path>: no animation ...; the animations are: 0 'Walk',
 * 1 'Run'" (or "the file has no animations"). */
int find_animation(const AnimatedAsset &asset, const std::string &name_or_index);

/* One world matrix per node. */
struct Pose {
    std::vector<Mat4d> world;
};

/* The pose of ANIMATION (-1: the file's node transforms, equal bit for bit
 * to load_gltf's world matrices) at TIME_SECONDS. The time is clamped to
 * [start, end] of the animation, and each sampler holds its first value
 * before its first key and its last value after its last key (glTF 2.0
 * section 3.11). Throws GltfError for an animation index out of range. */
Pose pose_at(const AnimatedAsset &asset, int animation, double time_seconds);

/* The value of one sampler at time T (components floats into OUT): exposed
 * for tests. Rotations (components == 4) come out as unit quaternions:
 * LINEAR by slerp on the shorter arc, CUBICSPLINE by the spec's Hermite
 * spline then normalized, STEP as stored then normalized. */
void sample(const AnimSampler &sampler, double t, double *out);

/* ---- Skinning ----------------------------------------------------------- */

/* The kernels and their contract (the order of operations every one keeps,
 * so that all give the C reference's bits): include/shadowvol_skin.h. */
using SkinningFn = sv_skin_fn;
/* name ("c_ref", "sse2", "avx2", "avx512"), isa (SV_ISA_* bits the CPU must
 * have), fn: sv_skin_variants()' entries. */
using SkinningKernel = sv_skin_variant;

/* Every kernel, from the C reference to the widest; check isa against
 * sv_cpu_isa() before calling. */
const SkinningKernel *skinning_kernels(int *count);
/* The last kernel sv_cpu_isa() allows (never NULL). */
const SkinningKernel *best_skinning_kernel();
/* The kernel called NAME, or NULL. */
const SkinningKernel *skinning_kernel_by_name(const char *name);

/* The 16-float joint matrices of SKIN at POSE with ROOT applied:
 * float(root * world(joint_j) * inverse_bind_j), products in double,
 * rounded once. 16 * joints floats into OUT. */
void joint_matrices(const AnimatedAsset &asset, int skin, const Pose &pose, const Mat4d &root,
                    float *out);

/* World positions of SURFACE at POSE, ROOT applied last (the scene's
 * placement), 3 floats per welded vertex into OUT.
 * Skinned: joint_matrices() then kernel K (NULL: best_skinning_kernel());
 * the node's own transform is ignored (glTF). Rigid: (root * world(node))
 * * p in double, rounded to float once (load_gltf's arithmetic; K unused). */
void pose_surface(const AnimatedAsset &asset, const AnimatedSurface &surface, const Pose &pose,
                  const Mat4d &root, float *out, const SkinningKernel *k = nullptr);

/* ---- Skinning and planes in one pass ------------------------------------
 * A skinned surface needs its triangle planes again every frame. This pass
 * writes the skinned positions (pose_surface()'s, the kernel's bits) and
 * the planes of sv_derive_planes_c_ref on them, BIT-IDENTICAL to "skin with
 * any kernel, then derive with any planes variant", in segments: each
 * skins the vertices the next run of triangles completes, then derives
 * those triangles' planes while the positions are in the first-level cache
 * (src/deform/skin_planes_kernels.c says when that helps and when it is
 * "skin, then planes" again; docs/PLANES.md has the measurements). */

/* Runs of about SEGMENT_TRIANGLES triangles (the last may be shorter; 0:
 * one segment) and, for each, the vertex count its corners need. Throws
 * PrepareError when an index is negative or not below NUM_VERTICES. */
struct SkinPlanesSchedule {
    std::vector<std::size_t> vertex_end;
    std::vector<int> triangle_end;
};
constexpr int kSkinPlanesSegmentTriangles = 256;
SkinPlanesSchedule skin_planes_schedule(const int *indices, int num_triangles,
                                        std::size_t num_vertices,
                                        int segment_triangles = kSkinPlanesSegmentTriangles);

/* name ("c_ref", "avx2", "avx512", "avx512_avx2"), isa, the skinning and
 * planes kernels it runs, fn: sv_skin_planes_variants()' entries. */
using SkinPlanesKernel = sv_skin_planes_variant;
const SkinPlanesKernel *skin_planes_kernels(int *count);
const SkinPlanesKernel *skin_planes_kernel_by_name(const char *name);

/* The one-pass kernels' arguments for SURFACE (skinned) with JOINT_MATRICES
 * (joint_matrices() at a pose), SCHEDULE and the outputs. */
sv_skin_planes_args skin_planes_args(const AnimatedSurface &surface, const float *joint_matrices,
                                     const SkinPlanesSchedule &schedule, float *out, Plane *planes);

/* pose_surface() and the planes of SURFACE (skinned, surface.skin >= 0) in
 * one pass by K, with SCHEDULE (built by skin_planes_schedule for the
 * surface's prepared indices). OUT: 3 floats per welded vertex; PLANES:
 * one per triangle. */
void pose_surface_with_planes(const AnimatedAsset &asset, const AnimatedSurface &surface,
                              const Pose &pose, const Mat4d &root, const SkinPlanesKernel &k,
                              const SkinPlanesSchedule &schedule, float *out, Plane *planes);

/* ---- The deforming pass chosen by measurement ----------------------------
 * Which skinning kernel, planes variant and one-pass kernel a skinned
 * surface of NUM_TRIANGLES triangles runs: the planner's choice for its
 * size class (include/shadowvol_plan.h: measured in this process, or this
 * CPU's wisdom file, which `shadowvol tune` writes), each name checked
 * against the tables and this CPU; else the static choice: the widest
 * skinning kernel, sv_best_planes_variant(), two passes. */
struct DeformPlan {
    const SkinningKernel *skinning = nullptr;
    const sv_planes_variant *planes = nullptr;
    const SkinPlanesKernel *skin_planes = nullptr; /* nullptr: two passes */
    /* The second pass by clusters (plane_clusters, built once per index
     * list) instead of PLANES; nullptr: PLANES. Chosen only by
     * measurement or wisdom, never statically. */
    const sv_planes_clustered_variant *clustered = nullptr;
    const char *source = "static"; /* "measured", "wisdom" or "static" (of skin_planes' choice) */
};
DeformPlan deform_plan_for(int num_triangles);

/* One variant's time in measure_deform_plan. */
struct DeformTiming {
    sv_deform_routine routine;
    std::string variant; /* skin_planes: a one-pass kernel, or "two_passes" (the chosen K then P);
                            derive_planes_clustered: a kernel, or "none" (the chosen P) */
    double ticks_per_triangle; /* the lowest of the rounds' medians */
};
/* Times every skinning kernel, planes variant, clustered planes kernel
 * and one-pass kernel this CPU runs on a generated skinned height field of size class SIZE_CLASS
 * (sv_size_class_triangles triangles, vertices in row order, 4 influences
 * of 24 joints), in rounds, each output checked bit for bit against the C
 * references; records the winners with sv_deform_choice_set (a kernel
 * keeps the static choice unless another is more than 3% faster; a
 * clustered kernel replaces the chosen planes variant only when more than
 * 3% faster (the clusters' building, once per index list, not counted);
 * the one-pass kernel is chosen only when more than 3% faster than the
 * chosen two passes). Throws std::runtime_error when a kernel disagrees with the
 * reference (nothing recorded) or SIZE_CLASS is out of range. */
std::vector<DeformTiming> measure_deform_plan(int size_class);

/* surface.prepared with its positions replaced by POSITIONS (3 per welded
 * vertex, e.g. from pose_surface) and every plane re-derived by
 * triangle_plane(): the surface at that pose. */
PreparedSurface prepared_at(const AnimatedSurface &surface, const float *positions);

/* ---- Lights and cameras ------------------------------------------------- */

/* Light LIGHT (an index into asset.lights) at POSE: position = M (0,0,0),
 * direction = M (0,0,-1) normalized, M = root * world(node). Range, cone
 * and intensity are not scaled (KHR_lights_punctual: a node's scale does
 * not change them). */
SceneLight light_at(const AnimatedAsset &asset, int light, const Pose &pose, const Mat4d &root);

/* Camera CAMERA (an index into asset.cameras) at POSE: eye = M (0,0,0),
 * target = eye + M (0,0,-1) normalized, up = M (0,1,0) normalized,
 * fov_y_degrees from yfov, near_distance = znear (zfar is not used: the
 * scene's projection is infinite). *aspect_out (when not NULL) gets the
 * file's aspect ratio, 0 when unset. */
Camera camera_at(const AnimatedAsset &asset, int camera, const Pose &pose, const Mat4d &root,
                 double *aspect_out);

} // namespace sv

#endif /* SHADOWVOL_ANIM_H */
