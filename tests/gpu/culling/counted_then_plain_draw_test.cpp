// counted_then_plain_draw_test.cpp: a spot light's shadow map drawn after GPU-culled point-shadow cube faces holds
// every caster. Scene: the closed room of vxgi_point_light_test (10 inward quads), a double-sided occluder quad as
// the LAST draw (index 10) hanging under a spot light that points at the floor, and a shadow-casting point light at
// (0.4, 0.3, -0.2) whose -Z cube face sees fewer draws than the scene has (it cannot see the occluder). Oracle: the
// same frame with --culling off (every pass draws every instance with plain indirect draws); the frame with
// --culling frustum and hiz must match it pixel for pixel within 1% (relative, per channel, plus 1e-4 absolute).
// Regression: lavapipe (Mesa 25.0) applied the last counted draw's count buffer to later plain
// vkCmdDrawIndexedIndirect calls in the same command buffer, so the spot map (light_shadow_maps.cpp) drew only the
// first N draws (N = the -Z face's culled count), lost the occluder, and the floor under it was lit: 660 of 4096
// pixels differed (frustum and hiz; radiance sum 3560.3 vs 3194.1) before passes/indirect_draw.hpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "render/renderer.hpp"
#include "support/gpu_fixture.hpp"
#include "support/placed_quads.hpp"

namespace idk::test {
namespace {

constexpr uint32_t kSize = 64;

PlacedQuad wall(glm::vec3 centre, glm::vec3 normal, glm::vec2 half) {
    return placedQuad(centre, normal, half, glm::vec3(0.6f));
}

scene::Scene roomWithOccluder() {
    std::vector<PlacedQuad> q;
    q.push_back(wall({0, -1, 0}, {0, 1, 0}, {1, 1}));
    q.push_back(wall({-1, 0, 0}, {1, 0, 0}, {1, 1}));
    q.push_back(wall({1, 0, 0}, {-1, 0, 0}, {1, 1}));
    q.push_back(wall({0, 0, -1}, {0, 0, 1}, {1, 1}));
    q.push_back(wall({0, 0, 1}, {0, 0, -1}, {1, 1}));
    q.push_back(wall({0, 1, 0}, {0, -1, 0}, {0.3f, 0.3f}));
    q.push_back(wall({-0.65f, 1, 0}, {0, -1, 0}, {0.35f, 1}));
    q.push_back(wall({0.65f, 1, 0}, {0, -1, 0}, {0.35f, 1}));
    q.push_back(wall({0, 1, -0.65f}, {0, -1, 0}, {0.3f, 0.35f}));
    q.push_back(wall({0, 1, 0.65f}, {0, -1, 0}, {0.3f, 0.35f}));
    q.push_back(placedQuad({0, 0, 0.3f}, {0, 1, 0}, {0.3f, 0.3f}, glm::vec3(0.6f), true));  // the occluder, last
    scene::Scene s = makePlacedQuadScene(q);
    for (scene::Material& m : s.materials) m.metallic = 0.0f;
    s.lights.push_back(pointLight({0.4f, 0.3f, -0.2f}, 1.5f));
    scene::Light spot;
    spot.name = "test spot";
    spot.type = scene::LightType::Spot;
    spot.intensity = 4.0f;
    spot.position = {0.0f, 0.9f, 0.3f};
    spot.direction = {0.0f, -1.0f, 0.0f};
    spot.innerConeAngle = 0.5f;
    spot.outerConeAngle = 0.6f;
    s.lights.push_back(spot);
    return s;
}

scene::CameraView camera() {
    scene::CameraView c;
    c.position = {0.0f, 0.6f, 0.95f};
    c.forward = glm::normalize(glm::vec3(0.0f, -1.0f, 0.1f) - c.position);
    c.up = glm::normalize(glm::cross(glm::cross(c.forward, glm::vec3(0, 1, 0)), c.forward));
    c.yfov = 1.4f;
    c.znear = 0.01f;
    return c;
}

render::FrameResult renderFrame(vk::Context& ctx, vk::ShaderLibrary& shaders, const scene::Scene& s,
                                frame::CullingMode mode) {
    render::RenderSettings settings;
    settings.output = render::OutputKind::Hdr;
    settings.environmentIntensity = 0.0f;
    settings.culling.mode = mode;
    render::Renderer renderer(ctx, shaders, settings);
    renderer.setScene(s);
    return renderer.renderOffscreen(camera(), kSize, kSize);
}

class CountedThenPlainDrawTest : public GpuTest {};

TEST_F(CountedThenPlainDrawTest, SpotShadowMapAfterCulledCubeFacesMatchesCullingOff) {
    const scene::Scene s = roomWithOccluder();
    const render::FrameResult off = renderFrame(ctx(), shaders(), s, frame::CullingMode::Off);
    double offSum = 0.0;
    for (size_t i = 0; i < off.image.pixels.size(); ++i) offSum += i % 4 == 3 ? 0.0 : off.image.pixels[i];
    ASSERT_GT(offSum, 0.0) << "the reference frame is lit";
    for (frame::CullingMode mode : {frame::CullingMode::Frustum, frame::CullingMode::Hiz}) {
        const char* name = mode == frame::CullingMode::Frustum ? "frustum" : "hiz";
        const render::FrameResult got = renderFrame(ctx(), shaders(), s, mode);
        // The condition of the bug: a counted cube-face draw with fewer draws than the scene has.
        size_t faces = 0, culledFaces = 0;
        for (const passes::CullingViewStats& v : got.culling) {
            if (v.view.rfind("light", 0) != 0) continue;
            ++faces;
            culledFaces += v.instancesDrawn < v.instancesTested;
        }
        EXPECT_EQ(faces, 6u) << name << ": one GPU-culled cube";
        EXPECT_GT(culledFaces, 0u) << name << ": no cube face culled a draw";
        ASSERT_EQ(got.image.pixels.size(), off.image.pixels.size());
        size_t differ = 0;
        double gotSum = 0.0;
        for (size_t i = 0; i < got.image.pixels.size(); i += 4) {
            bool same = true;
            for (size_t c = i; c < i + 3; ++c) {
                const float a = got.image.pixels[c], b = off.image.pixels[c];
                gotSum += a;
                same = same && std::abs(a - b) <= 1e-4f + 0.01f * std::abs(b);
            }
            differ += !same;
        }
        std::printf("%s: %zu of %zu pixels differ from --culling off (radiance sum %.3f, off %.3f)\n", name, differ,
                    got.image.pixels.size() / 4, gotSum, offSum);
        EXPECT_EQ(differ, 0u) << name;
    }
}

}  // namespace
}  // namespace idk::test
