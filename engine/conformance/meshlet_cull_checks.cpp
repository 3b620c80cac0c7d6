// meshlet_cull_checks.cpp: "culling/meshlet task shader": the mesh rung's task shader (gbuffer/gbuffer_mesh.task.glsl,
// run inside a Renderer with --culling hiz --geometry mesh) against its CPU oracle (render::meshletOracle: the same
// sphere, normal-cone and vertex-box Hi-Z tests, shared/meshlet_culling.h, with the pyramid the late phase read,
// captured from the GPU) along a camera path that moves and cuts: after every frame the per-meshlet visibility bits
// are identical and the frame's meshlet and triangle counters are exact; the instance bits follow
// render::cullOracle. The scene (built here): a wall, spheres of 2000 triangles (single-sided, so the normal cone
// applies) behind it, above it and in front of it, scaled and rotated. The check can fail both ways: the path must
// cull meshlets by each test.
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <bit>
#include <cmath>

#include "conformance/conformance.hpp"
#include "conformance/placed_quads.hpp"
#include "render/culling_math.hpp"
#include "render/depth_pyramid.hpp"
#include "render/meshlets.hpp"
#include "render/renderer.hpp"
#include "scene/camera.hpp"
#include "shared/meshlet_culling.h"
#include "vk/context.hpp"

namespace idk::conformance {
namespace {

constexpr glm::uvec2 kSize{97, 61};  // odd, not a power of two: every pyramid level has a clipped edge

// A UV sphere of radius 1: 40 x 25 quads, outward normals, counter-clockwise seen from outside.
scene::Primitive sphere(uint32_t material) {
    constexpr uint32_t kSlices = 40, kStacks = 25;
    scene::Primitive p;
    for (uint32_t j = 0; j <= kStacks; ++j)
        for (uint32_t i = 0; i <= kSlices; ++i) {
            const float theta = 3.14159265f * float(j) / kStacks, phi = 6.2831853f * float(i) / kSlices;
            const glm::vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
            p.positions.push_back(n);
            p.normals.push_back(n);
            p.uv0.push_back({float(i) / kSlices, float(j) / kStacks});
        }
    for (uint32_t j = 0; j < kStacks; ++j)
        for (uint32_t i = 0; i < kSlices; ++i) {
            const uint32_t a = j * (kSlices + 1) + i, b = a + kSlices + 1;
            p.indices.insert(p.indices.end(), {a, a + 1, b, a + 1, b + 1, b});
        }
    p.material = material;
    return p;
}

scene::Scene meshletScene() {
    scene::Scene s = makePlacedQuadScene({placedQuad({0, 2, 0}, {0, 0, 1}, {8, 2}, {0.7f, 0.6f, 0.5f})});
    scene::Material m;
    m.name = "sphere";
    m.baseColorFactor = glm::vec4(0.3f, 0.5f, 0.8f, 1.0f);
    s.materials.push_back(m);
    scene::Mesh mesh;
    mesh.name = "sphere";
    mesh.primitives.push_back(sphere(uint32_t(s.materials.size() - 1)));
    s.meshes.push_back(std::move(mesh));
    const scene::Instance wall = s.instances.at(0);
    auto place = [&](glm::vec3 at, glm::vec3 scale, float angle) {
        scene::Instance i = wall;
        i.mesh = uint32_t(s.meshes.size() - 1);
        i.world = glm::scale(glm::rotate(glm::translate(glm::mat4(1.0f), at), angle, glm::vec3(0.3f, 1.0f, 0.2f)), scale);
        s.instances.push_back(i);
        s.bounds.extend(at - glm::vec3(2.0f * std::max(scale.x, std::max(scale.y, scale.z))));
        s.bounds.extend(at + glm::vec3(2.0f * std::max(scale.x, std::max(scale.y, scale.z))));
    };
    for (int x = 0; x < 5; ++x)
        for (int z = 0; z < 3; ++z) place({-6.0f + 3.0f * float(x), 1.0f + 0.8f * float(z), -2.0f - 3.0f * float(z)},
                                          glm::vec3(1.0f), 0.4f * float(x + z));
    place({-4.0f, 4.7f, -2.5f}, glm::vec3(0.8f), 1.0f);                 // peeking over the wall
    place({3.0f, 4.3f, -3.0f}, glm::vec3(1.2f, 0.7f, 1.0f), 0.5f);      // non-uniform scale: no cone test
    place({0.0f, 1.0f, 4.0f}, glm::vec3(1.0f), 2.0f);                   // in front of the wall
    s.lights.clear();
    return s;
}

scene::CameraView lookAt(glm::vec3 eye, glm::vec3 target) {
    scene::CameraView c;
    c.position = eye;
    c.forward = glm::normalize(target - eye);
    c.up = glm::cross(glm::normalize(glm::cross(c.forward, glm::vec3(0, 1, 0))), c.forward);
    return c;
}

void meshletTaskShader(CheckEnv& env, Verdict& v) {
    if (!env.ctx.capabilities().meshShaderExt) {
        v.skip("device lacks VK_EXT_mesh_shader: no task shader to check");
        return;
    }
    const scene::Scene scene = meshletScene();
    render::RenderSettings settings;
    settings.culling.mode = frame::CullingMode::Hiz;
    settings.culling.geometry = frame::GeometryPath::Mesh;
    settings.temporal.aa = frame::AntiAliasing::None;  // no jitter: the oracle's view is the unjittered camera
    render::Renderer renderer(env.ctx, env.shaders, settings);
    renderer.setScene(scene);
    renderer.captureCullingPyramid(true);
    const render::GpuSceneData& data = renderer.gpuScene()->data();
    const render::MeshletData meshlets = render::buildMeshlets(data);
    const std::vector<gpu::GpuCullDraw> draws = render::packCullDraws(data, &meshlets);
    const std::vector<scene::CameraView> path = {
        lookAt({0, 3, 12}, {0, 2, 0}),  lookAt({1, 3.2f, 11}, {0, 2, -1}), lookAt({2, 3.4f, 10}, {0, 2, -2}),  // moving
        lookAt({-14, 4, -4}, {0, 2, -4}),                                                                    // cut
        lookAt({-14, 4, -4}, {0, 2, -4}),                                                                    // still
        lookAt({0, 3, 12}, {0, 2, 0}),                                                                       // cut back
        lookAt({0.8f, 1.2f, 6.2f}, {0, 1, 4})};  // cut: close to the front sphere, which straddles the frustum
    std::vector<uint32_t> meshletBits = renderer.cullingMeshletVisibility();  // empty before the first frame
    std::vector<uint32_t> instanceBits;
    uint32_t hizCulled = 0, coneCulled = 0, frustumCulled = 0;
    for (size_t c = 0; c < path.size(); ++c) {
        const std::string what = "camera " + std::to_string(c);
        const render::FrameResult frame = renderer.renderOffscreen(path[c], kSize.x, kSize.y);
        if (meshletBits.empty()) meshletBits.assign(std::max(render::meshletVisibilityWords(draws), 1u), 0u);
        if (instanceBits.empty()) instanceBits.assign(draws.size(), 0u);
        const glm::mat4 viewProjection =
            scene::projectionMatrix(path[c], float(kSize.x) / float(kSize.y)) * scene::viewMatrix(path[c]);
        const gpu::GpuCullView view = render::frustumView(viewProjection, kSize);
        const std::vector<float> pyramid = renderer.cullingEarlyPyramid();
        if (!v.expectEq(pyramid.size(), size_t(gpu::hizLevelOffset(kSize, gpu::hizLevelCount(kSize))),
                        what + ": captured pyramid size"))
            return;
        // Early: the draws visible last frame that are in the frustum, their meshlets with a set bit.
        const std::vector<uint32_t> instancesBefore = instanceBits;
        const std::vector<bool> early = render::cullOracle(draws, data.instances, view, gpu::kCullEarly, &instanceBits);
        const std::vector<bool> none(draws.size(), false);
        const render::MeshletCounts e = render::meshletOracle(draws, data.instances, meshlets.meshlets, view,
                                                              path[c].position, gpu::kCullEarly, early, none, meshletBits);
        // Late: every draw that passes, those drawn early relaunched for their remaining meshlets.
        const std::vector<bool> late = render::cullOracle(draws, data.instances, view, gpu::kCullLate, &instanceBits,
                                                          &pyramid, true);
        std::vector<bool> relaunched(draws.size());
        for (size_t i = 0; i < draws.size(); ++i) relaunched[i] = late[i] && instancesBefore[i] != 0;
        const render::MeshletCounts l = render::meshletOracle(draws, data.instances, meshlets.meshlets, view,
                                                              path[c].position, gpu::kCullLate, late, relaunched,
                                                              meshletBits, &pyramid);
        v.expect(renderer.cullingVisibility() == instanceBits, what + ": instance bits differ from the oracle's");
        const std::vector<uint32_t> gpuBits = renderer.cullingMeshletVisibility();
        size_t differing = 0;
        for (size_t w = 0; w < gpuBits.size() && w < meshletBits.size(); ++w)
            differing += size_t(std::popcount(gpuBits[w] ^ meshletBits[w]));
        v.expectEq(gpuBits.size(), meshletBits.size(), what + ": meshlet bit words");
        v.expectEq(differing, size_t(0), what + ": meshlet bits differing from the oracle's");
        if (!v.expect(!frame.culling.empty(), what + ": no culling counters")) return;
        const passes::CullingViewStats& got = frame.culling[0];
        v.expectEq(got.meshletsTested, e.tested + l.tested, what + ": meshlets tested");
        v.expectEq(got.meshletsDrawn, e.drawn + l.drawn, what + ": meshlets drawn");
        v.expectEq(got.trianglesDrawn, e.triangles + l.triangles, what + ": triangles drawn");
        meshletBits = gpuBits;  // the next frame starts from the GPU's bits (equal unless already reported)
        instanceBits = renderer.cullingVisibility();
        // Which test culled what (late phase, launched draws): each must cull something along the path.
        for (size_t i = 0; i < draws.size(); ++i) {
            if (!late[i]) continue;
            const gpu::GpuCullDraw& d = draws[i];
            for (uint32_t k = 0; k < d.meshletCount; ++k) {
                const gpu::GpuMeshlet& m = meshlets.meshlets[d.firstMeshlet + k];
                glm::vec3 centre, extent;
                gpu::meshletBox(m, data.instances[i].model, centre, extent);
                gpu::GpuMeshlet noCone = m;
                noCone.coneCutoff = 1.0f;
                const bool inView = gpu::meshletInView(m, d.flags, data.instances[i].model, view, path[c].position);
                const bool inFrustum = gpu::meshletInView(noCone, d.flags, data.instances[i].model, view, path[c].position);
                frustumCulled += !inFrustum;
                coneCulled += inFrustum && !inView;
                hizCulled += inView && !render::hizBoxVisible(pyramid, view, centre, extent);
            }
        }
    }
    v.expect(frustumCulled > 0 && coneCulled > 0 && hizCulled > 0,
             "the path culls meshlets by each test (frustum " + std::to_string(frustumCulled) + ", cone " +
                 std::to_string(coneCulled) + ", Hi-Z " + std::to_string(hizCulled) + ")");
    renderer.captureCullingPyramid(false);
}

}  // namespace

std::vector<Check> meshletCullChecks() {
    return {{"culling/meshlet task shader", "", "exact (meshlet and instance bits, counters)", meshletTaskShader}};
}

}  // namespace idk::conformance
