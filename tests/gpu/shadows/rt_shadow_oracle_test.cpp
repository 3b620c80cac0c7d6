// rt_shadow_oracle_test.cpp: ray-traced hard shadows (`--shadows raytraced`) against the CPU ray-cast oracle
// (support/shadow_oracle.hpp), for a point, a spot and a directional light over a floor and a box: where the CPU
// ray from a floor point to the light hits the box, s <= 0.02, elsewhere s >= 0.98. The excluded band is
// kBandWorld wide (the shadow ray leaves the G-buffer's reconstructed point, offset 1e-4 of its distance along the
// normal; nothing is filtered). Both rungs of the "ray traversal" ladder (our BVH; VK_KHR_ray_query, on a second
// context forced to it, where the device has it) must render bit-identical frames.
#include <gtest/gtest.h>

#include <cstring>

#include "support/gpu_fixture.hpp"
#include "support/shadow_oracle.hpp"
#include "vk/acceleration_structure.hpp"
#include "vk/features.hpp"

namespace idk::test {
namespace {

constexpr double kBandWorld = 0.005;

enum class Kind { Point, Spot, Sun };

struct Case {
    scene::Scene scene;
    std::vector<PlacedQuad> quads;
    OracleLight light;
    scene::CameraView camera = shadowTestCamera({0.8f, 4.0f, 4.2f}, {0.6f, 0.0f, 0.4f});
};

Case makeCase(Kind kind) {
    Case c;
    c.quads = {floorQuad(3.0f)};
    for (const PlacedQuad& f : boxFaces({0.0f, 0.0f, 0.0f}, {0.5f, 0.5f, 0.5f}, glm::vec3(0.6f))) c.quads.push_back(f);
    c.scene = makePlacedQuadScene(c.quads);
    const glm::vec3 position(-1.2f, 2.2f, -0.8f);
    scene::Light l = pointLight(position, kind == Kind::Spot ? 30.0f : 20.0f);
    if (kind == Kind::Spot) {
        l.type = scene::LightType::Spot;
        l.direction = glm::normalize(glm::vec3(0.4f, 0.0f, 0.4f) - position);
        l.innerConeAngle = 0.5f;
        l.outerConeAngle = 0.7f;
    }
    const glm::dvec3 L(position);
    c.light.target = [L](const glm::dvec3&) { return L; };
    if (kind == Kind::Sun) {
        l.type = scene::LightType::Directional;
        l.intensity = 3.0f;
        l.direction = glm::normalize(glm::vec3(0.8f, -0.55f, 0.5f));
        const glm::dvec3 toSun = -glm::dvec3(l.direction);
        c.light.target = [toSun](const glm::dvec3& p) { return p + 100.0 * toSun; };
    }
    c.light.texel = [](const glm::dvec3&) { return kBandWorld; };
    c.scene.lights.push_back(l);
    return c;
}

render::RenderSettings rtSettings() {
    render::RenderSettings s = shadowTestSettings(512);
    s.lightShadows.rayTraced = true;
    return s;
}

class RtShadowOracleTest : public GpuTest {};

TEST_F(RtShadowOracleTest, HardShadowsOfEveryLightTypeMatchTheCpuOracle) {
    if (ctx().capabilities().cpuDevice) {
        EXPECT_EQ(ctx().ladder("ray traversal").chosen, vk::Rung::Fallback) << "a CPU device takes our BVH";
    }
    for (Kind kind : {Kind::Point, Kind::Spot, Kind::Sun}) {
        Case c = makeCase(kind);
        const char* name = kind == Kind::Point ? "rt_point" : kind == Kind::Spot ? "rt_spot" : "rt_sun";
        ShadowFrames f = renderShadowFrames(ctx(), shaders(), c.scene, c.camera, name, rtSettings());
        FloorCounts n = checkShadowFloor(f, c.quads, c.quads, c.camera, c.light, 1.0, kind == Kind::Spot);
        EXPECT_EQ(n.failures, 0u) << name << " first: " << n.first;
        EXPECT_GT(n.dark, 500u) << name;
        EXPECT_GT(n.lit, 2000u) << name;
        EXPECT_LT(n.band, n.dark / 4) << name << ": the band is a hair's width";
        std::printf("%s: %u occluded, %u lit, %u outside the cone, %u in the band\n", name, n.dark, n.lit, n.unlit,
                    n.band);
    }
}

TEST_F(RtShadowOracleTest, RayQueryAndBvhRungsRenderIdenticalFrames) {
    if (!vk::rayQuerySupported(ctx())) GTEST_SKIP() << "device lacks VK_KHR_ray_query: only our BVH runs";
    vk::ContextDesc desc = ctx().desc();
    desc.forcedRungs.push_back({"ray-traversal", vk::Rung::Native});
    uint32_t nativeErrors = 0;
    for (Kind kind : {Kind::Point, Kind::Sun}) {
        Case c = makeCase(kind);
        ShadowFrames bvh = renderShadowFrames(ctx(), shaders(), c.scene, c.camera, "rt_rung_bvh", rtSettings());
        ShadowFrames rq;
        {
            vk::Context rqCtx(desc);
            ASSERT_EQ(rqCtx.ladder("ray traversal").chosen, vk::Rung::Native);
            vk::ShaderLibrary rqShaders(rqCtx);
            rq = renderShadowFrames(rqCtx, rqShaders, c.scene, c.camera, "rt_rung_rq", rtSettings());
            rqCtx.waitIdle();
            nativeErrors += rqCtx.validationErrors();
        }
        ASSERT_EQ(bvh.full.pixels.size(), rq.full.pixels.size());
        size_t differing = 0;
        for (size_t i = 0; i < bvh.full.pixels.size(); ++i)
            differing += std::memcmp(&bvh.full.pixels[i], &rq.full.pixels[i], sizeof(float)) != 0;
        EXPECT_EQ(differing, 0u) << "channels that differ between the rungs";
        FloorCounts n = checkShadowFloor(rq, c.quads, c.quads, c.camera, c.light, 1.0);
        EXPECT_EQ(n.failures, 0u) << "ray query vs CPU oracle, first: " << n.first;
    }
    EXPECT_EQ(nativeErrors, 0u) << "validation errors on the ray-query context";
}

}  // namespace
}  // namespace idk::test
