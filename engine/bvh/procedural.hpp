// procedural.hpp: generated meshes for BVH tests and benchmarks: the "atrium" stress scene (a Sponza-like hall of
// huge axis-aligned wall/floor triangles mixed with many small ones; rotated 45 degrees on all axes it is the
// readme's "Rotated Sponza" case), closed meshes (icosphere, cube) for watertightness tests, random triangle soups.
// Indexed, so the triangles of a closed mesh share bit-identical vertices.
#pragma once

#include "bvh/geometry.hpp"

#include <cstdint>
#include <vector>

namespace idk::bvh {

struct IndexedMesh {
    std::vector<glm::vec3> positions;
    std::vector<glm::uvec3> indices;

    std::vector<Triangle> triangles() const;
    void append(const IndexedMesh& other);
    void transform(const glm::mat4& m);  // positions only
};

// Closed sphere from a subdivided icosahedron (20 * 4^subdivisions triangles, consistently wound outwards).
IndexedMesh makeIcosphere(uint32_t subdivisions, float radius = 1.0f, glm::vec3 center = glm::vec3(0.0f));

// Closed axis-aligned box whose faces are split into segments x segments quads (12 * segments^2 triangles).
IndexedMesh makeBox(glm::vec3 min, glm::vec3 max, uint32_t segments = 1);

struct AtriumOptions {
    uint32_t storeys = 3;
    uint32_t statueSubdivisions = 4;  // the icosphere on the pedestal in the middle
    uint32_t plants = 40;             // small spheres on the galleries
};

// A 60 x 24 x 24 hall (x, y up, z) of about 39k triangles: two triangles per outer wall, floor and roof, gallery
// slabs around a central void, segmented columns, balusters, a tessellated statue and plants.
IndexedMesh makeAtrium(const AtriumOptions& options = {});

// Rotation by `degrees` about x, then y, then z, around the centre of the mesh's bounding box: the matrix, and the
// mesh transformed by it.
glm::mat4 rotationAboutCenter(const IndexedMesh& mesh, float degrees);
void rotateAboutCenter(IndexedMesh& mesh, float degrees);

// `count` triangles with vertices around random centres in [0, 1]^3, edge lengths spread over three decades.
std::vector<Triangle> makeRandomTriangles(uint32_t count, uint32_t seed);

}  // namespace idk::bvh
