// meshlets.cpp: meshoptimizer meshlets per mesh (see meshlets.hpp).
#include "render/meshlets.hpp"

#include <meshoptimizer.h>

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

namespace idk::render {

MeshletData buildMeshlets(const GpuSceneData& scene) {
    MeshletData out;
    std::vector<uint8_t> bytes;
    for (const gpu::GpuMesh& mesh : scene.meshes) {
        out.firstMeshlet.push_back(uint32_t(out.meshlets.size()));
        std::vector<uint32_t> indices(scene.indices.begin() + mesh.firstIndex,
                                      scene.indices.begin() + mesh.firstIndex + mesh.indexCount);
        if (indices.size() < 3) {
            out.meshletCount.push_back(0);
            continue;
        }
        const size_t vertexCount = size_t(*std::max_element(indices.begin(), indices.end())) + 1;
        if (mesh.baseVertex < 0 || size_t(mesh.baseVertex) + vertexCount > scene.vertices.size())
            throw std::runtime_error("meshlets: mesh " + std::to_string(out.firstMeshlet.size() - 1) +
                                     " indexes past the vertex buffer");
        const float* positions = &scene.vertices[size_t(mesh.baseVertex)].position.x;
        constexpr size_t kStride = sizeof(gpu::GpuVertex);
        meshopt_optimizeVertexCache(indices.data(), indices.data(), indices.size(), vertexCount);
        const size_t bound = meshopt_buildMeshletsBound(indices.size(), gpu::kMeshletMaxVertices,
                                                        gpu::kMeshletMaxTriangles);
        std::vector<meshopt_Meshlet> meshlets(bound);
        std::vector<uint32_t> vertices(bound * gpu::kMeshletMaxVertices);
        std::vector<uint8_t> triangles(bound * gpu::kMeshletMaxTriangles * 3);
        const size_t count = meshopt_buildMeshlets(meshlets.data(), vertices.data(), triangles.data(), indices.data(),
                                                   indices.size(), positions, vertexCount, kStride,
                                                   gpu::kMeshletMaxVertices, gpu::kMeshletMaxTriangles, 0.25f);
        for (size_t m = 0; m < count; ++m) {
            const meshopt_Meshlet& ml = meshlets[m];
            const meshopt_Bounds b = meshopt_computeMeshletBounds(&vertices[ml.vertex_offset],
                                                                  &triangles[ml.triangle_offset], ml.triangle_count,
                                                                  positions, vertexCount, kStride);
            gpu::GpuMeshlet g{};
            g.center = {b.center[0], b.center[1], b.center[2]};
            g.radius = b.radius;
            g.coneApex = {b.cone_apex[0], b.cone_apex[1], b.cone_apex[2]};
            g.coneAxis = {b.cone_axis[0], b.cone_axis[1], b.cone_axis[2]};
            g.coneCutoff = b.cone_cutoff;
            g.vertexOffset = uint32_t(out.vertices.size());
            g.triangleOffset = uint32_t(bytes.size());
            g.vertexCount = ml.vertex_count;
            g.triangleCount = ml.triangle_count;
            glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
            for (uint32_t k = 0; k < ml.vertex_count; ++k) {
                const glm::vec3& p = scene.vertices[size_t(mesh.baseVertex) + vertices[ml.vertex_offset + k]].position;
                lo = glm::min(lo, p);
                hi = glm::max(hi, p);
            }
            g.boxCenter = 0.5f * (lo + hi);
            g.boxExtent = 0.5f * (hi - lo);
            out.meshlets.push_back(g);
            out.vertices.insert(out.vertices.end(), vertices.begin() + ml.vertex_offset,
                                vertices.begin() + ml.vertex_offset + ml.vertex_count);
            bytes.insert(bytes.end(), triangles.begin() + ml.triangle_offset,
                         triangles.begin() + ml.triangle_offset + ml.triangle_count * 3);
        }
        out.meshletCount.push_back(uint32_t(out.meshlets.size()) - out.firstMeshlet.back());
    }
    bytes.resize((bytes.size() + 3) / 4 * 4, 0);
    out.triangles.resize(bytes.size() / 4);
    for (size_t w = 0; w < out.triangles.size(); ++w)
        out.triangles[w] = uint32_t(bytes[4 * w]) | uint32_t(bytes[4 * w + 1]) << 8 | uint32_t(bytes[4 * w + 2]) << 16 |
                           uint32_t(bytes[4 * w + 3]) << 24;
    return out;
}

}  // namespace idk::render
