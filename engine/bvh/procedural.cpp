// procedural.cpp: the generated meshes of procedural.hpp (deterministic: fixed seeds, no global state).
#include "bvh/procedural.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <tuple>

namespace idk::bvh {

std::vector<Triangle> IndexedMesh::triangles() const {
    std::vector<Triangle> out;
    out.reserve(indices.size());
    for (const glm::uvec3& i : indices) out.push_back({positions[i.x], positions[i.y], positions[i.z]});
    return out;
}

void IndexedMesh::append(const IndexedMesh& other) {
    const uint32_t base = uint32_t(positions.size());
    positions.insert(positions.end(), other.positions.begin(), other.positions.end());
    for (const glm::uvec3& i : other.indices) indices.push_back(i + base);
}

void IndexedMesh::transform(const glm::mat4& m) {
    for (glm::vec3& p : positions) p = glm::vec3(m * glm::vec4(p, 1.0f));
}

IndexedMesh makeIcosphere(uint32_t subdivisions, float radius, glm::vec3 center) {
    const float t = (1.0f + std::sqrt(5.0f)) * 0.5f;
    std::vector<glm::vec3> unit{{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                                {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    for (glm::vec3& p : unit) p = glm::normalize(p);
    std::vector<glm::uvec3> faces{{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                                  {11, 10, 2}, {10, 7, 6}, {7, 1, 8},   {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                                  {3, 8, 9},  {4, 9, 5},  {2, 4, 11},  {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
    for (uint32_t level = 0; level < subdivisions; ++level) {
        std::map<std::pair<uint32_t, uint32_t>, uint32_t> midpoints;
        auto midpoint = [&](uint32_t a, uint32_t b) {
            const auto key = std::minmax(a, b);
            auto [it, inserted] = midpoints.try_emplace({key.first, key.second}, uint32_t(unit.size()));
            if (inserted) unit.push_back(glm::normalize(unit[a] + unit[b]));
            return it->second;
        };
        std::vector<glm::uvec3> next;
        next.reserve(faces.size() * 4);
        for (const glm::uvec3& f : faces) {
            const uint32_t ab = midpoint(f.x, f.y), bc = midpoint(f.y, f.z), ca = midpoint(f.z, f.x);
            next.push_back({f.x, ab, ca});
            next.push_back({f.y, bc, ab});
            next.push_back({f.z, ca, bc});
            next.push_back({ab, bc, ca});
        }
        faces.swap(next);
    }
    IndexedMesh mesh;
    for (const glm::vec3& p : unit) mesh.positions.push_back(center + radius * p);
    mesh.indices = std::move(faces);
    return mesh;
}

IndexedMesh makeBox(glm::vec3 min, glm::vec3 max, uint32_t segments) {
    segments = std::max(1u, segments);
    IndexedMesh mesh;
    std::map<std::tuple<float, float, float>, uint32_t> vertexIds;  // shared edges get the same vertex
    auto vertex = [&](glm::vec3 p) {
        auto [it, inserted] = vertexIds.try_emplace({p.x, p.y, p.z}, uint32_t(mesh.positions.size()));
        if (inserted) mesh.positions.push_back(p);
        return it->second;
    };
    auto coord = [&](int axis, uint32_t i) {
        return i == segments ? max[axis] : min[axis] + (max[axis] - min[axis]) * (float(i) / float(segments));
    };
    for (int axis = 0; axis < 3; ++axis) {
        const int u = (axis + 1) % 3, v = (axis + 2) % 3;
        for (int side = 0; side < 2; ++side) {
            for (uint32_t i = 0; i < segments; ++i) {
                for (uint32_t j = 0; j < segments; ++j) {
                    glm::vec3 q[4];
                    const uint32_t du[4] = {0, 1, 1, 0}, dv[4] = {0, 0, 1, 1};
                    for (int k = 0; k < 4; ++k) {
                        q[k][axis] = side == 0 ? min[axis] : max[axis];
                        q[k][u] = coord(u, i + du[k]);
                        q[k][v] = coord(v, j + dv[k]);
                    }
                    uint32_t id[4];
                    for (int k = 0; k < 4; ++k) id[k] = vertex(q[k]);
                    if (side == 0) {  // outward winding
                        mesh.indices.push_back({id[0], id[2], id[1]});
                        mesh.indices.push_back({id[0], id[3], id[2]});
                    } else {
                        mesh.indices.push_back({id[0], id[1], id[2]});
                        mesh.indices.push_back({id[0], id[2], id[3]});
                    }
                }
            }
        }
    }
    return mesh;
}

namespace {

// Two triangles per quad p0 p1 p2 p3 (in order around the quad).
void addQuad(IndexedMesh& mesh, glm::vec3 p0, glm::vec3 p1, glm::vec3 p2, glm::vec3 p3) {
    const uint32_t base = uint32_t(mesh.positions.size());
    mesh.positions.insert(mesh.positions.end(), {p0, p1, p2, p3});
    mesh.indices.push_back({base, base + 1, base + 2});
    mesh.indices.push_back({base, base + 2, base + 3});
}

// A horizontal rectangle [x0, x1] x [z0, z1] at height y, two triangles.
void addFloor(IndexedMesh& mesh, float x0, float x1, float z0, float z1, float y) {
    addQuad(mesh, {x0, y, z0}, {x1, y, z0}, {x1, y, z1}, {x0, y, z1});
}

}  // namespace

IndexedMesh makeAtrium(const AtriumOptions& options) {
    IndexedMesh mesh;
    const float hallX = 30.0f, hallZ = 12.0f, voidX = 20.0f, voidZ = 6.0f;
    const float storeyHeight = 8.0f;
    const uint32_t storeys = std::max(1u, options.storeys);
    const float height = storeyHeight * float(storeys);

    // Ground, roof and four outer walls: the huge axis-aligned triangles of Sponza's floor and walls.
    addFloor(mesh, -hallX, hallX, -hallZ, hallZ, 0.0f);
    addFloor(mesh, -hallX, hallX, -hallZ, hallZ, height);
    addQuad(mesh, {-hallX, 0, -hallZ}, {hallX, 0, -hallZ}, {hallX, height, -hallZ}, {-hallX, height, -hallZ});
    addQuad(mesh, {-hallX, 0, hallZ}, {hallX, 0, hallZ}, {hallX, height, hallZ}, {-hallX, height, hallZ});
    addQuad(mesh, {-hallX, 0, -hallZ}, {-hallX, 0, hallZ}, {-hallX, height, hallZ}, {-hallX, height, -hallZ});
    addQuad(mesh, {hallX, 0, -hallZ}, {hallX, 0, hallZ}, {hallX, height, hallZ}, {hallX, height, -hallZ});

    for (uint32_t s = 0; s < storeys; ++s) {
        const float y0 = storeyHeight * float(s);
        // Columns around the void, four segments per storey height.
        for (int side = -1; side <= 1; side += 2) {
            for (int i = 0; i <= 8; ++i) {
                const float x = -voidX + 5.0f * float(i);
                mesh.append(makeBox({x - 0.3f, y0, side * voidZ - 0.3f}, {x + 0.3f, y0 + storeyHeight - 0.4f, side * voidZ + 0.3f}, 4));
            }
            for (int i = 1; i <= 2; ++i) {
                const float z = -voidZ + 4.0f * float(i);
                mesh.append(makeBox({side * voidX - 0.3f, y0, z - 0.3f}, {side * voidX + 0.3f, y0 + storeyHeight - 0.4f, z + 0.3f}, 4));
            }
        }
        if (s == 0) continue;
        // Gallery slab: a ring around the void, top and bottom faces (large triangles) plus its inner edge.
        for (float y : {y0 - 0.4f, y0}) {
            addFloor(mesh, -hallX, hallX, -hallZ, -voidZ, y);
            addFloor(mesh, -hallX, hallX, voidZ, hallZ, y);
            addFloor(mesh, -hallX, -voidX, -voidZ, voidZ, y);
            addFloor(mesh, voidX, hallX, -voidZ, voidZ, y);
        }
        addQuad(mesh, {-voidX, y0 - 0.4f, -voidZ}, {voidX, y0 - 0.4f, -voidZ}, {voidX, y0, -voidZ}, {-voidX, y0, -voidZ});
        addQuad(mesh, {-voidX, y0 - 0.4f, voidZ}, {voidX, y0 - 0.4f, voidZ}, {voidX, y0, voidZ}, {-voidX, y0, voidZ});
        addQuad(mesh, {-voidX, y0 - 0.4f, -voidZ}, {-voidX, y0 - 0.4f, voidZ}, {-voidX, y0, voidZ}, {-voidX, y0, -voidZ});
        addQuad(mesh, {voidX, y0 - 0.4f, -voidZ}, {voidX, y0 - 0.4f, voidZ}, {voidX, y0, voidZ}, {voidX, y0, -voidZ});
        // Balusters every 0.5 m along the void edge and a hand rail.
        for (float x = -voidX + 0.25f; x < voidX; x += 0.5f) {
            for (float z : {-voidZ - 0.2f, voidZ + 0.2f}) mesh.append(makeBox({x - 0.05f, y0, z - 0.05f}, {x + 0.05f, y0 + 1.0f, z + 0.05f}));
        }
        for (float z = -voidZ + 0.25f; z < voidZ; z += 0.5f) {
            for (float x : {-voidX - 0.2f, voidX + 0.2f}) mesh.append(makeBox({x - 0.05f, y0, z - 0.05f}, {x + 0.05f, y0 + 1.0f, z + 0.05f}));
        }
        mesh.append(makeBox({-voidX - 0.3f, y0 + 1.0f, -voidZ - 0.3f}, {voidX + 0.3f, y0 + 1.1f, -voidZ - 0.1f}, 8));
        mesh.append(makeBox({-voidX - 0.3f, y0 + 1.0f, voidZ + 0.1f}, {voidX + 0.3f, y0 + 1.1f, voidZ + 0.3f}, 8));
        // Plants: small spheres along the galleries.
        const uint32_t perGallery = options.plants / (storeys - 1);  // s >= 1 here, so storeys >= 2
        for (uint32_t p = 0; p < perGallery; ++p) {
            const float x = -hallX + 2.0f + (2.0f * hallX - 4.0f) * (float(p) + 0.5f) / float(perGallery);
            mesh.append(makeIcosphere(2, 0.5f, {x, y0 + 0.5f, (p % 2 == 0 ? -1.0f : 1.0f) * (hallZ - 2.0f)}));
        }
    }
    // Pedestal and statue in the middle of the void.
    mesh.append(makeBox({-1.5f, 0.0f, -1.5f}, {1.5f, 1.5f, 1.5f}, 2));
    mesh.append(makeIcosphere(options.statueSubdivisions, 1.5f, {0.0f, 3.0f, 0.0f}));
    return mesh;
}

glm::mat4 rotationAboutCenter(const IndexedMesh& mesh, float degrees) {
    Box box;
    for (const glm::vec3& p : mesh.positions) box.grow(p);
    const glm::vec3 center = 0.5f * (box.min + box.max);
    const float r = glm::radians(degrees);
    glm::mat4 m = glm::translate(glm::mat4(1.0f), center);
    m = glm::rotate(m, r, glm::vec3(0, 0, 1));
    m = glm::rotate(m, r, glm::vec3(0, 1, 0));
    m = glm::rotate(m, r, glm::vec3(1, 0, 0));
    return glm::translate(m, -center);
}

void rotateAboutCenter(IndexedMesh& mesh, float degrees) { mesh.transform(rotationAboutCenter(mesh, degrees)); }

std::vector<Triangle> makeRandomTriangles(uint32_t count, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f), signedUnit(-1.0f, 1.0f), decades(-3.0f, 0.0f);
    std::vector<Triangle> out(count);
    for (Triangle& tri : out) {
        const glm::vec3 c(unit(rng), unit(rng), unit(rng));
        const float size = 0.2f * std::pow(10.0f, decades(rng));
        for (glm::vec3* v : {&tri.v0, &tri.v1, &tri.v2}) *v = c + size * glm::vec3(signedUnit(rng), signedUnit(rng), signedUnit(rng));
    }
    return out;
}

}  // namespace idk::bvh
