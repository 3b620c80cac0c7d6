// shadow_culling_test.cpp: GPU culling of the point-shadow cube faces (frame/shadow_culling.hpp). A scene of boxes
// scattered on all sides of two point lights (plus an alpha-MASK pane that casts nothing, which checks that the
// culled draws still find their instance's material) is rendered with --culling off, frustum and hiz: every face's
// GPU counters equal the CPU oracle's count for that face's frustum (render::cullOracle, exact), the faces really
// cull, and both cubes and the lit frame are byte-identical to the unculled ones. The same with a BLEND pane
// beside the first light, which casts by coverage: its cube differs from the scene's without it, and culling
// (BLEND casters included) leaves it unchanged.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <memory>
#include <string>

#include "render/cube_face_views.hpp"
#include "render/culling_math.hpp"
#include "render/draw_bounds.hpp"
#include "render/point_shadow_maps.hpp"
#include "render/renderer.hpp"
#include "scene/camera.hpp"
#include "support/cube_readback.hpp"
#include "support/gpu_fixture.hpp"
#include "support/placed_quads.hpp"

namespace idk::test {
namespace {

constexpr uint32_t kFrame = 64, kCube = 64;
const char* const kFaceNames[6] = {"+X", "-X", "+Y", "-Y", "+Z", "-Z"};

// A floor, a 5 x 3 x 5 lattice of small boxes around (0, 2, 0) with two lights inside it, and a MASK pane whose
// alpha falls below its cutoff; `blendPane`: also a BLEND pane beside the first light.
scene::Scene latticeScene(bool blendPane = false) {
    std::vector<PlacedQuad> quads;
    PlacedQuad floor;
    floor.centre = {0.0f, -0.5f, 0.0f};
    floor.normal = {0.0f, 1.0f, 0.0f};
    floor.halfSize = {12.0f, 12.0f};
    quads.push_back(floor);
    for (int x = -2; x <= 2; ++x)
        for (int y = 0; y < 3; ++y)
            for (int z = -2; z <= 2; ++z) {
                if (x == 0 && z == 0) continue;  // room for the lights
                const glm::vec3 colour(0.3f + 0.1f * float(x + 2), 0.5f, 0.3f + 0.1f * float(z + 2));
                auto faces = boxFaces({2.2f * float(x), 1.8f * float(y), 2.2f * float(z)}, glm::vec3(0.35f), colour);
                quads.insert(quads.end(), faces.begin(), faces.end());
            }
    PlacedQuad pane;
    pane.centre = {0.0f, 2.0f, 1.2f};
    pane.halfSize = {0.8f, 0.8f};
    pane.alpha = 0.3f;
    pane.alphaMode = scene::AlphaMode::Mask;  // glTF default cutoff 0.5: every fragment is cut away
    quads.push_back(pane);
    if (blendPane) {
        PlacedQuad glass;
        glass.centre = {-1.0f, 2.0f, 0.0f};
        glass.normal = {1.0f, 0.0f, 0.0f};
        glass.halfSize = {0.6f, 0.6f};
        glass.alpha = 0.6f;
        glass.alphaMode = scene::AlphaMode::Blend;
        quads.push_back(glass);
    }
    scene::Scene s = makePlacedQuadScene(quads);
    s.lights.push_back(pointLight({0.0f, 2.0f, 0.0f}, 300.0f));
    s.lights.push_back(pointLight({0.3f, 3.4f, -0.4f}, 200.0f));
    return s;
}

scene::CameraView camera() {
    scene::CameraView c;
    c.position = {7.0f, 6.0f, 9.0f};
    c.forward = glm::normalize(glm::vec3(0.0f, 1.5f, 0.0f) - c.position);
    const glm::vec3 right = glm::normalize(glm::cross(c.forward, glm::vec3(0, 1, 0)));
    c.up = glm::cross(right, c.forward);
    return c;
}

struct Result {
    // Kept alive while the results are compared: a later renderer's cubes cannot reuse this one's memory (whose
    // old texels would otherwise pass for a frame's output).
    std::unique_ptr<render::Renderer> renderer;
    render::FrameResult frame;
    std::vector<std::vector<float>> cubes;
};

Result render(vk::Context& ctx, vk::ShaderLibrary& shaders, const scene::Scene& scene, frame::CullingMode mode) {
    render::RenderSettings settings;
    settings.pointShadows.resolution = kCube;
    settings.culling.mode = mode;
    Result out;
    out.renderer = std::make_unique<render::Renderer>(ctx, shaders, settings);
    render::Renderer& r = *out.renderer;
    r.setScene(scene);
    out.frame = r.renderOffscreen(camera(), kFrame, kFrame);
    const render::PointShadowMaps* maps = r.pointShadowMaps();
    EXPECT_NE(maps, nullptr);
    if (maps)
        for (uint32_t c = 0; c < maps->casters().size(); ++c) out.cubes.push_back(readCube(ctx, maps->cube(c)));
    return out;
}

class ShadowCullingTest : public GpuTest {
protected:
    // Returns the unculled render (its cubes are compared with other scenes').
    Result checkScene(const scene::Scene& scene);
};

TEST_F(ShadowCullingTest, FaceCountsMatchTheOracleAndCubesAreUnchanged) { checkScene(latticeScene()); }

TEST_F(ShadowCullingTest, BlendCastersAreCulledAndCubesAreUnchanged) {
    const Result withBlend = checkScene(latticeScene(true));
    const Result without = render(ctx(), shaders(), latticeScene(), frame::CullingMode::Off);
    ASSERT_EQ(withBlend.cubes.size(), without.cubes.size());
    ASSERT_FALSE(without.cubes.empty());
    size_t shadowed = 0;  // texels of the first cube the BLEND pane covers
    for (size_t i = 0; i < without.cubes[0].size(); ++i) shadowed += withBlend.cubes[0][i] < without.cubes[0][i];
    EXPECT_GT(shadowed, 100u) << "the BLEND pane casts into the first cube";
}

Result ShadowCullingTest::checkScene(const scene::Scene& scene) {
    const render::GpuSceneData data = render::packGpuScene(scene, {});
    const std::vector<gpu::GpuCullDraw> records = render::packCullDraws(data, nullptr, true);  // BLEND casts
    const scene::Aabb box = render::sceneBounds(data, render::meshBounds(data));
    EXPECT_EQ(data.lights.size(), 2u);

    Result off = render(ctx(), shaders(), scene, frame::CullingMode::Off);
    EXPECT_EQ(off.cubes.size(), 2u);
    if (off.cubes.size() != 2u) return off;
    EXPECT_TRUE(off.frame.culling.empty());
    size_t covered = 0;
    for (float d : off.cubes[0]) covered += d < 1.0f;
    EXPECT_GT(covered, off.cubes[0].size() / 4) << "the lattice fills much of the first cube";

    for (frame::CullingMode mode : {frame::CullingMode::Frustum, frame::CullingMode::Hiz}) {
        const char* name = mode == frame::CullingMode::Frustum ? "frustum" : "hiz";
        const Result culled = render(ctx(), shaders(), scene, mode);
        // The camera's view(s) first, then 6 faces per cube.
        std::vector<passes::CullingViewStats> faces;
        for (const passes::CullingViewStats& v : culled.frame.culling)
            if (v.view.rfind("light ", 0) == 0) faces.push_back(v);
        EXPECT_EQ(faces.size(), 12u) << name;
        if (faces.size() != 12u) return off;
        for (uint32_t light = 0; light < 2; ++light) {
            const glm::vec2 planes = render::pointShadowPlanes(data.lights[light], box);
            for (uint32_t f = 0; f < 6; ++f) {
                const passes::CullingViewStats& s = faces[light * 6 + f];
                EXPECT_EQ(s.view, "light " + std::to_string(light) + " face " + kFaceNames[f]);
                const gpu::GpuCullView view = render::frustumView(
                    render::cubeFaceViewProjection(data.lights[light].position, f, planes.x, planes.y));
                const std::vector<bool> drawn = render::cullOracle(records, data.instances, view);
                uint32_t expected = 0, triangles = 0, tested = 0;
                for (size_t i = 0; i < records.size(); ++i) {
                    tested += (records[i].flags & gpu::kCullSkip) ? 0 : 1;
                    if (drawn[i]) ++expected, triangles += records[i].indexCount / 3;
                }
                EXPECT_EQ(s.instancesTested, tested) << name << " " << s.view;
                EXPECT_EQ(s.instancesDrawn, expected) << name << " " << s.view;
                EXPECT_EQ(s.trianglesDrawn, triangles) << name << " " << s.view;
                // A face sees a quarter-space of the lattice: well under half of it.
                EXPECT_LT(2 * s.instancesDrawn, s.instancesTested) << name << " " << s.view << ": the face culls";
                std::cout << "[ culling ] " << name << " " << s.view << ": " << s.instancesDrawn << " of "
                          << s.instancesTested << " drawn\n";
            }
        }
        EXPECT_EQ(culled.cubes.size(), off.cubes.size());
        for (size_t c = 0; c < off.cubes.size() && c < culled.cubes.size(); ++c) {
            EXPECT_EQ(culled.cubes[c].size(), off.cubes[c].size());
            if (culled.cubes[c].size() != off.cubes[c].size()) continue;
            size_t differing = 0;
            for (size_t i = 0; i < off.cubes[c].size(); ++i)
                differing += std::memcmp(&off.cubes[c][i], &culled.cubes[c][i], sizeof(float)) != 0;
            EXPECT_EQ(differing, 0u) << name << " cube " << c << ": texels that culling changed";
        }
        EXPECT_TRUE(off.frame.display == culled.frame.display) << name << ": the lit frames differ";
    }
    return off;
}

// The matrix form of cubeFaceClip: every point lies inside the frustum of the face of its major axis (+X for the
// largest positive x, ...), at clip w = its major-axis distance, with depth 0 at the near and 1 at the far plane.
TEST(CubeFaceViews, MajorAxisFaceContainsThePoint) {
    const glm::vec3 light(1.0f, -2.0f, 0.5f);
    const float nearPlane = 0.05f, farPlane = 50.0f;
    uint32_t seed = 12345;
    auto next = [&] {
        seed = seed * 1664525u + 1013904223u;
        return float(seed >> 8) / float(1u << 24) * 2.0f - 1.0f;
    };
    for (int n = 0; n < 1000; ++n) {
        const glm::vec3 r(10.0f * next(), 10.0f * next(), 10.0f * next());
        const int axis = std::abs(r.x) >= std::abs(r.y) && std::abs(r.x) >= std::abs(r.z) ? 0
                         : std::abs(r.y) >= std::abs(r.z)                                  ? 1
                                                                                           : 2;
        const uint32_t face = uint32_t(2 * axis + (r[axis] < 0.0f ? 1 : 0));
        const float ma = std::abs(r[axis]);
        if (ma < nearPlane) continue;
        const glm::vec4 clip = render::cubeFaceViewProjection(light, face, nearPlane, farPlane) * glm::vec4(light + r, 1);
        EXPECT_NEAR(clip.w, ma, 1e-4f);
        EXPECT_LE(std::abs(clip.x), clip.w * 1.0001f);
        EXPECT_LE(std::abs(clip.y), clip.w * 1.0001f);
        const float depth = clip.z / clip.w;
        EXPECT_GE(depth, -1e-5f);
        EXPECT_LE(depth, 1.0f);
        EXPECT_TRUE(gpu::boxInFrustum(render::frustumView(render::cubeFaceViewProjection(light, face, nearPlane,
                                                                                          farPlane)),
                                      light + r, glm::vec3(0.0f)));
        // The opposite face never contains it.
        const glm::vec4 opposite =
            render::cubeFaceViewProjection(light, face ^ 1u, nearPlane, farPlane) * glm::vec4(light + r, 1);
        EXPECT_LT(opposite.w, 0.0f);
    }
    // Near and far map to depth 0 and 1 (the pointShadowDepthCoefficients of include/shadows.glsl).
    const glm::vec4 nearClip = render::cubeFaceViewProjection(light, 0, nearPlane, farPlane) *
                               glm::vec4(light + glm::vec3(nearPlane, 0, 0), 1);
    const glm::vec4 farClip = render::cubeFaceViewProjection(light, 0, nearPlane, farPlane) *
                              glm::vec4(light + glm::vec3(farPlane, 0, 0), 1);
    EXPECT_NEAR(nearClip.z / nearClip.w, 0.0f, 1e-5f);
    EXPECT_NEAR(farClip.z / farClip.w, 1.0f, 1e-5f);
}

}  // namespace
}  // namespace idk::test
