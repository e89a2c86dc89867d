// shadowvol model generator: the project's own stand-in for the paper's
// (non-public) 1344-triangle player character, and larger closed meshes for
// scaling runs. Standard library only; deterministic output.
//
// The character is box-modelled on a quad mesh: a subdivided box (the torso,
// 6 x 8 x 4 cells = 208 quads) from which five 2x2-cell patches are extruded
// (neck + head, two arms, two legs). Extruding a patch whose boundary has 8
// edges by k segments keeps the mesh closed, 2-manifold and consistently
// wound, and adds 8k quads: 58 segments in all (head 10, arms 12 + 12, legs
// 12 + 12) give 208 + 464 = 672 quads, i.e. 1344 triangles, 2016 edges and
// 674 vertices (genus 0: V - E + F = 2).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace svgen {

struct Vec3 {
    double x, y, z;
};

// A closed quad mesh; quads counter-clockwise seen from outside.
struct QuadMesh {
    std::vector<Vec3> vertices;
    std::vector<std::array<std::uint32_t, 4>> quads;
};

// An indexed triangle mesh as it is written: float32 positions (x, y, z per
// vertex), three indices per triangle, counter-clockwise seen from outside.
struct TriMesh {
    std::vector<float> positions;
    std::vector<std::uint32_t> indices;
    std::size_t num_vertices() const { return positions.size() / 3; }
    std::size_t num_triangles() const { return indices.size() / 3; }
};

// The character as a quad mesh (672 quads, 674 vertices).
QuadMesh build_character_quads();

// Each quad subdivided n x n (bilinearly; shared edges share their new
// vertices, so the result stays closed and manifold), then split into two
// triangles along its shorter diagonal. n = 1: 1344 triangles; in general
// 1344 * n * n.
TriMesh triangulate(const QuadMesh &mesh, int n);

// The character with each quad subdivided n x n (n = 1: the 1344-triangle
// model).
TriMesh build_character(int n = 1);

// The file name the generator uses for a mesh: character_<triangles>.glb.
std::string model_file_name(const TriMesh &mesh);

// The mesh as a glTF 2.0 binary (.glb): one buffer, POSITION (float32 VEC3
// with min/max) and indices (unsigned short when every index fits, else
// unsigned int), one TRIANGLES primitive, one node, one scene.
std::vector<std::uint8_t> write_glb(const TriMesh &mesh, const std::string &name);

// The demo scene (scene_gen.cpp; models/README.md): ground, terrain patch,
// pillars, wall, the skinned character with its walk, lights and camera.
struct DemoSceneInfo {
    int terrain_quads = 0; // per side
    int terrain_triangles = 0;
    int character_triangles = 0;
    int joints = 0;
    double walk_seconds = 0;
};
DemoSceneInfo demo_scene_info();
std::vector<std::uint8_t> write_demo_scene_glb();

} // namespace svgen
