// meshlets_test.cpp: meshlets built by render::buildMeshlets on real meshes (Duck, DamagedHelmet): every
// triangle of every mesh appears in exactly one meshlet with its winding, within the vertex/triangle limits;
// each meshlet's sphere and box hold its vertices; and the normal-cone test the task shader applies never culls a
// meshlet that has a front-facing triangle (random eyes, 200 per meshlet).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <map>
#include <random>

#include "render/gpu_scene.hpp"
#include "render/meshlets.hpp"
#include "scene/gltf_loader.hpp"

namespace idk::test {
namespace {

using Triangle = std::array<uint32_t, 3>;

// The same triangle whatever vertex it starts at (winding kept).
Triangle canonical(Triangle t) {
    while (t[0] != std::min({t[0], t[1], t[2]})) t = {t[1], t[2], t[0]};
    return t;
}

void checkScene(const char* path) {
    const scene::Scene s = scene::loadGltf(std::string(IDK_SHARED_DIR) + "/scenes/" + path);
    const render::GpuSceneData data = render::packGpuScene(s, {});
    const render::MeshletData m = render::buildMeshlets(data);
    ASSERT_EQ(m.firstMeshlet.size(), data.meshes.size());
    auto byte = [&](uint32_t i) { return (m.triangles[i / 4] >> (8 * (i % 4))) & 0xFFu; };
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    uint32_t coneCulls = 0, meshletCount = 0;
    for (size_t k = 0; k < data.meshes.size(); ++k) {
        const gpu::GpuMesh& mesh = data.meshes[k];
        std::map<Triangle, int> expected, got;
        for (uint32_t t = 0; t + 2 < mesh.indexCount; t += 3)
            ++expected[canonical({data.indices[mesh.firstIndex + t], data.indices[mesh.firstIndex + t + 1],
                                  data.indices[mesh.firstIndex + t + 2]})];
        for (uint32_t i = 0; i < m.meshletCount[k]; ++i) {
            const gpu::GpuMeshlet& ml = m.meshlets[m.firstMeshlet[k] + i];
            ++meshletCount;
            ASSERT_LE(ml.vertexCount, gpu::kMeshletMaxVertices);
            ASSERT_LE(ml.triangleCount, gpu::kMeshletMaxTriangles);
            std::vector<Triangle> tris;
            for (uint32_t t = 0; t < ml.triangleCount; ++t) {
                Triangle tri;
                for (uint32_t c = 0; c < 3; ++c) {
                    const uint32_t local = byte(ml.triangleOffset + 3 * t + c);
                    ASSERT_LT(local, ml.vertexCount);
                    tri[c] = m.vertices[ml.vertexOffset + local];
                }
                ++got[canonical(tri)];
                tris.push_back(tri);
            }
            auto position = [&](uint32_t v) { return data.vertices[size_t(mesh.baseVertex) + v].position; };
            for (const Triangle& t : tris)
                for (uint32_t v : t) {
                    ASSERT_LE(glm::distance(position(v), ml.center), ml.radius * (1.0f + 1e-4f) + 1e-6f);
                    const glm::vec3 slack = glm::abs(ml.boxCenter) * 1e-6f + 1e-6f;  // centre +- extent rounding
                    ASSERT_TRUE(glm::all(glm::lessThanEqual(glm::abs(position(v) - ml.boxCenter), ml.boxExtent + slack)))
                        << path << ": a vertex outside its meshlet's box";
                }
            // Eyes around the meshlet at 0.5 .. 4 radii (and some on the cone's axis behind the apex).
            for (int e = 0; e < 200; ++e) {
                glm::vec3 dir(u(rng), u(rng), u(rng));
                if (e % 4 == 0) dir = -ml.coneAxis + 0.1f * dir;
                const glm::vec3 eye = ml.center + glm::normalize(dir + glm::vec3(1e-6f)) * ml.radius * (2.5f + 2.0f * u(rng));
                if (ml.coneCutoff >= 1.0f || glm::dot(glm::normalize(ml.coneApex - eye), ml.coneAxis) < ml.coneCutoff)
                    continue;
                ++coneCulls;
                for (const Triangle& t : tris) {
                    const glm::vec3 a = position(t[0]), b = position(t[1]), c = position(t[2]);
                    const glm::vec3 n = glm::cross(b - a, c - a);  // counter-clockwise front
                    ASSERT_GE(glm::dot(n, a - eye), -1e-5f * glm::length(n) * glm::length(a - eye))
                        << path << ": cone-culled meshlet has a front-facing triangle";
                }
            }
        }
        EXPECT_EQ(got, expected) << path << " mesh " << k << ": meshlet triangles differ from the index buffer";
    }
    std::cout << "[ meshlets ] " << path << ": " << meshletCount << " meshlets, " << coneCulls << " cone culls checked\n";
    EXPECT_GT(coneCulls, 0u) << "the eyes should exercise the cone test";
}

TEST(Meshlets, CoverEveryTriangleOnceAndConesNeverCullFrontFaces) {
    checkScene("Duck/glTF-Quantized/Duck.gltf");
    checkScene("DamagedHelmet/glTF-Binary/DamagedHelmet.glb");
}

}  // namespace
}  // namespace idk::test
