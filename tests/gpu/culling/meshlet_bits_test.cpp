// meshlet_bits_test.cpp: the mesh rung's per-meshlet two-phase occlusion (gbuffer_mesh.task.glsl): along camera
// paths that move and cut, on ToyCar and on two DamagedHelmets one behind the other, the culled frame equals the
// frustum-only mesh frame byte for byte (zero false culls) and stays within the mesh rung's 16 bytes of the unculled
// vertex-path frame (culling_frame_test.cpp says why), and after every frame each meshlet that holds a triangle the
// unculled frame shows (its surface-ID buffer: the ground truth) has its visibility bit set. Warm and still, the
// meshlet bits really cull: fewer meshlets and triangles than the frustum-only frame.
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <map>

#include "render/culling_math.hpp"
#include "render/meshlets.hpp"
#include "render/renderer.hpp"
#include "scene/camera.hpp"
#include "scene/gltf_loader.hpp"
#include "support/gpu_fixture.hpp"

namespace idk::test {
namespace {

constexpr uint32_t kSize = 96;

scene::CameraView lookAt(const scene::CameraView& base, glm::vec3 eye, glm::vec3 target) {
    scene::CameraView c = base;
    c.position = eye;
    c.forward = glm::normalize(target - eye);
    c.up = glm::cross(glm::normalize(glm::cross(c.forward, glm::vec3(0, 1, 0))), c.forward);
    return c;
}

// The default view, a step to the side (moving), a cut to the far side, a cut back, and the same view again (still:
// the bits of the frame before apply).
std::vector<scene::CameraView> path(const scene::Scene& s) {
    const scene::CameraView base = scene::defaultCamera(s);
    const glm::vec3 target = s.bounds.centre();
    const float distance = std::max(glm::length(base.position - target), 1e-3f);
    const glm::vec3 side = glm::normalize(glm::cross(base.forward, base.up));
    return {base, lookAt(base, base.position + 0.15f * distance * side, target),
            lookAt(base, 2.0f * target - base.position + 0.3f * distance * side, target), base, base};
}

// Per mesh: the meshlets (mesh-local index) holding each triangle, keyed by its sorted mesh-relative vertices.
using TriangleKey = std::array<uint32_t, 3>;
TriangleKey key(uint32_t a, uint32_t b, uint32_t c) {
    TriangleKey k{a, b, c};
    std::sort(k.begin(), k.end());
    return k;
}
std::vector<std::map<TriangleKey, std::vector<uint32_t>>> meshletsOfTriangles(const render::MeshletData& m) {
    std::vector<std::map<TriangleKey, std::vector<uint32_t>>> out(m.firstMeshlet.size());
    auto byte = [&](uint32_t i) { return (m.triangles[i / 4] >> (8 * (i % 4))) & 0xFFu; };
    for (size_t mesh = 0; mesh < out.size(); ++mesh)
        for (uint32_t local = 0; local < m.meshletCount[mesh]; ++local) {
            const gpu::GpuMeshlet& g = m.meshlets[m.firstMeshlet[mesh] + local];
            for (uint32_t t = 0; t < g.triangleCount; ++t) {
                const uint32_t b = g.triangleOffset + 3 * t;
                out[mesh][key(m.vertices[g.vertexOffset + byte(b)], m.vertices[g.vertexOffset + byte(b + 1)],
                              m.vertices[g.vertexOffset + byte(b + 2)])]
                    .push_back(local);
            }
        }
    return out;
}

class MeshletBitsTest : public GpuTest {
protected:
    void runPath(const scene::Scene& scene, const char* what) {
        render::Renderer off(ctx(), shaders()), frustum(ctx(), shaders()), hiz(ctx(), shaders());
        off.settings().culling.mode = frame::CullingMode::Off;
        frustum.settings().culling.mode = frame::CullingMode::Frustum;
        hiz.settings().culling.mode = frame::CullingMode::Hiz;
        frustum.settings().culling.geometry = hiz.settings().culling.geometry = frame::GeometryPath::Mesh;
        for (render::Renderer* r : {&off, &frustum, &hiz}) r->setScene(scene);
        const render::GpuSceneData& data = off.gpuScene()->data();
        const render::MeshletData meshlets = render::buildMeshlets(data);
        const std::vector<gpu::GpuCullDraw> records = render::packCullDraws(data, &meshlets);
        const auto triangles = meshletsOfTriangles(meshlets);
        uint32_t meshletCount = 0;
        for (const gpu::GpuCullDraw& d : records) meshletCount += (d.flags & gpu::kCullSkip) ? 0 : d.meshletCount;
        const std::vector<scene::CameraView> cameras = path(scene);
        passes::CullingViewStats lastFrustum, lastHiz;
        for (size_t c = 0; c < cameras.size(); ++c) {
            const std::vector<glm::uvec2> ids = off.renderSurfaceIds(cameras[c], kSize, kSize);
            const render::FrameResult a = off.renderOffscreen(cameras[c], kSize, kSize);
            const render::FrameResult f = frustum.renderOffscreen(cameras[c], kSize, kSize);
            const render::FrameResult h = hiz.renderOffscreen(cameras[c], kSize, kSize);
            ASSERT_EQ(h.display.size(), a.display.size());
            EXPECT_TRUE(h.display == f.display) << what << " camera " << c << ": meshlet occlusion changed the image";
            size_t differing = 0;
            for (size_t i = 0; i < a.display.size(); ++i) differing += a.display[i] != h.display[i];
            EXPECT_LE(differing, 16u) << what << " camera " << c;
            const std::vector<uint32_t> bits = hiz.cullingMeshletVisibility();
            ASSERT_EQ(bits.size(), size_t(std::max(render::meshletVisibilityWords(records), 1u)));
            size_t visibleTriangles = 0, uncovered = 0;
            std::vector<glm::uvec2> seen(ids);
            std::sort(seen.begin(), seen.end(), [](glm::uvec2 x, glm::uvec2 y) { return x.x != y.x ? x.x < y.x : x.y < y.y; });
            seen.erase(std::unique(seen.begin(), seen.end()), seen.end());
            for (const glm::uvec2& id : seen) {
                if (id.x >= records.size()) continue;  // background
                const gpu::GpuCullDraw& d = records[id.x];
                const uint32_t mesh = data.instances[id.x].mesh;
                const uint32_t* ix = &data.indices[d.firstIndex + 3 * id.y];
                const auto it = triangles[mesh].find(key(ix[0], ix[1], ix[2]));
                ASSERT_NE(it, triangles[mesh].end()) << what << ": draw " << id.x << " triangle " << id.y
                                                     << " is in no meshlet";
                ++visibleTriangles;
                const bool anySet = std::any_of(it->second.begin(), it->second.end(), [&](uint32_t local) {
                    return (bits[d.meshletVisibilityWord + local / 32] >> (local % 32)) & 1u;
                });
                uncovered += !anySet;
            }
            EXPECT_GT(visibleTriangles, 0u) << what << " camera " << c;
            EXPECT_EQ(uncovered, 0u) << what << " camera " << c << ": visible triangles whose meshlet bit is clear";
            ASSERT_FALSE(h.culling.empty());
            lastFrustum = f.culling[0];
            lastHiz = h.culling[0];
            std::cout << "[ meshlets ] " << what << " camera " << c << ": hiz " << lastHiz.meshletsDrawn << " ("
                      << lastHiz.trianglesDrawn << " triangles), frustum " << lastFrustum.meshletsDrawn << " ("
                      << lastFrustum.trianglesDrawn << ") of " << meshletCount << " meshlets, "
                      << visibleTriangles << " triangles visible\n";
        }
        // The last camera repeats the one before: the early phase draws last frame's meshlets, the late phase adds
        // none that the bits did not already hold, and the occluded ones stay undrawn.
        EXPECT_LT(lastHiz.meshletsDrawn, lastFrustum.meshletsDrawn) << what;
        EXPECT_LT(lastHiz.trianglesDrawn, lastFrustum.trianglesDrawn) << what;
    }
};

TEST_F(MeshletBitsTest, MeshletBitsHoldEveryVisibleTriangleAlongMovingAndCuttingPaths) {
    if (!ctx().capabilities().meshShaderExt) GTEST_SKIP() << "device lacks VK_EXT_mesh_shader: no meshlet bits";
    if (!ctx().capabilities().geometryShader) GTEST_SKIP() << "the surface-ID ground truth needs gl_PrimitiveID";
    const std::string root = std::string(IDK_SHARED_DIR) + "/scenes/";
    runPath(scene::loadGltf(root + "ToyCar/glTF/ToyCar.gltf"), "ToyCar");
    // Two helmets, the second straight behind the first along the default view: its instance stays visible (its
    // rim shows), most of its meshlets are hidden.
    scene::Scene helmets = scene::loadGltf(root + "DamagedHelmet/glTF-Binary/DamagedHelmet.glb");
    const scene::CameraView view = scene::defaultCamera(helmets);
    scene::Instance behind = helmets.instances.at(0);
    const glm::vec3 offset = 2.5f * (helmets.bounds.max - helmets.bounds.min).z * view.forward;
    behind.world = glm::translate(glm::mat4(1.0f), offset) * behind.world;
    helmets.instances.push_back(behind);
    helmets.bounds.extend(helmets.bounds.min + offset);
    helmets.bounds.extend(helmets.bounds.max + offset);
    runPath(helmets, "two DamagedHelmets");
}

}  // namespace
}  // namespace idk::test
