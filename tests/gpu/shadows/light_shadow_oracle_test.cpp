// light_shadow_oracle_test.cpp: directional-light cascades and spot-light maps in the deferred lighting against
// the CPU ray-cast oracle (support/shadow_oracle.hpp), on the scenes of shadow_oracle_test.cpp:
//  * Directional occluder: a low sun over a floor and a box; where the CPU ray from a floor point towards the sun
//    hits the box, s <= 0.02, elsewhere s >= 0.98, outside kBandTexels texels of the cascade used at the point
//    (its world size found with the renderer's own fit, render/shadow_cascades.hpp).
//  * Spot occluder: the same for a 40-degree spot (one perspective map); floor outside the cone is skipped.
//  * Grazing sun on a room corner (83 and 76 degrees of incidence on floor and back wall, nothing occludes):
//    s >= 0.99 everywhere except within a few texels of a concave junction.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "render/shadow_cascades.hpp"
#include "shared/shadow_types.h"
#include "support/gpu_fixture.hpp"
#include "support/shadow_oracle.hpp"

namespace idk::test {
namespace {

constexpr double kBandTexels = 5.0;
constexpr uint32_t kResolution = 512;
constexpr uint32_t kCascades = 4;

scene::Light sunLight(glm::vec3 direction, float lux) {
    scene::Light l;
    l.name = "test sun";
    l.type = scene::LightType::Directional;
    l.intensity = lux;
    l.direction = glm::normalize(direction);
    return l;
}

scene::Light spotLight(glm::vec3 position, glm::vec3 target, float candela, float inner, float outer) {
    scene::Light l;
    l.name = "test spot";
    l.type = scene::LightType::Spot;
    l.intensity = candela;
    l.position = position;
    l.direction = glm::normalize(target - position);
    l.innerConeAngle = inner;
    l.outerConeAngle = outer;
    return l;
}

// World size of a shadow texel at p: the first cascade that holds p with the lookup's margin, as the shader picks.
double cascadeTexel(const std::vector<render::ShadowProjection>& cascades, const glm::dvec3& p) {
    for (const render::ShadowProjection& c : cascades) {
        glm::dvec4 clip = glm::dmat4(c.viewProjection) * glm::dvec4(p, 1.0);
        glm::dvec2 uv = glm::dvec2(clip) / clip.w * 0.5 + 0.5;
        double m = gpu::kShadowMapMargin / kResolution;
        if (uv.x >= m && uv.y >= m && uv.x <= 1.0 - m && uv.y <= 1.0 - m) return c.texelScale;
    }
    return 1e9;  // beyond the cascades: the band check then excludes the pixel
}

OracleLight sunOracle(const scene::Scene& scene, const scene::CameraView& camera, glm::vec3 direction) {
    auto cascades = std::make_shared<std::vector<render::ShadowProjection>>(render::directionalCascades(
        camera, 1.0f, scene.bounds, glm::normalize(direction), kCascades, kResolution, 0.0f));
    const glm::dvec3 toSun = -glm::normalize(glm::dvec3(direction));
    return {[toSun](const glm::dvec3& p) { return p + 100.0 * toSun; },
            [cascades](const glm::dvec3& p) { return cascadeTexel(*cascades, p); }};
}

class LightShadowOracleTest : public GpuTest {};

TEST_F(LightShadowOracleTest, DirectionalCascadesDarkenExactlyWhereTheCpuRayToTheSunHitsTheBox) {
    std::vector<PlacedQuad> quads{floorQuad(3.0f)};
    for (const PlacedQuad& f : boxFaces({0.0f, 0.0f, 0.0f}, {0.5f, 0.5f, 0.5f}, glm::vec3(0.6f))) quads.push_back(f);
    const glm::vec3 direction(0.8f, -0.55f, 0.5f);
    scene::Scene scene = makePlacedQuadScene(quads);
    scene.lights.push_back(sunLight(direction, 3.0f));
    scene::CameraView camera = shadowTestCamera({0.8f, 4.0f, 4.2f}, {0.6f, 0.0f, 0.4f});
    ShadowFrames f = renderShadowFrames(ctx(), shaders(), scene, camera, "sun", shadowTestSettings(kResolution));
    FloorCounts c = checkShadowFloor(f, quads, quads, camera, sunOracle(scene, camera, direction), kBandTexels);
    EXPECT_EQ(c.failures, 0u) << "first: " << c.first;
    EXPECT_GT(c.dark, 1000u) << "occluded floor pixels tested";
    EXPECT_GT(c.lit, 3000u) << "lit floor pixels tested";
    EXPECT_LT(c.band, c.dark) << "the excluded edge band stays thinner than the umbra";
    std::printf("sun oracle: %u occluded, %u lit floor pixels, %u in the edge band\n", c.dark, c.lit, c.band);
}

TEST_F(LightShadowOracleTest, SpotMapDarkensExactlyWhereTheCpuRayToTheSpotHitsTheBox) {
    std::vector<PlacedQuad> quads{floorQuad(3.0f)};
    for (const PlacedQuad& f : boxFaces({0.0f, 0.0f, 0.0f}, {0.5f, 0.5f, 0.5f}, glm::vec3(0.6f))) quads.push_back(f);
    const glm::vec3 position(-1.2f, 2.2f, -0.8f), target(0.4f, 0.0f, 0.4f);
    const float outer = 0.7f;  // 40 degrees
    scene::Scene scene = makePlacedQuadScene(quads);
    scene.lights.push_back(spotLight(position, target, 30.0f, 0.5f, outer));
    scene::CameraView camera = shadowTestCamera({0.8f, 4.0f, 4.2f}, {0.6f, 0.0f, 0.4f});
    ShadowFrames f = renderShadowFrames(ctx(), shaders(), scene, camera, "spot", shadowTestSettings(kResolution));
    // A spot-map texel at view depth z is 2 tan(half) z / resolution wide, z <= |p - light|.
    const double half = std::atan(std::tan(outer) / (1.0 - 2.0 * gpu::kShadowMapMargin / kResolution));
    const glm::dvec3 L(position);
    OracleLight light{[L](const glm::dvec3&) { return L; },
                      [L, half](const glm::dvec3& p) { return 2.0 * std::tan(half) * glm::length(L - p) / kResolution; }};
    FloorCounts c = checkShadowFloor(f, quads, quads, camera, light, kBandTexels, true);
    EXPECT_EQ(c.failures, 0u) << "first: " << c.first;
    EXPECT_GT(c.dark, 500u) << "occluded floor pixels tested";
    EXPECT_GT(c.lit, 2000u) << "lit floor pixels tested";
    EXPECT_LT(c.band, c.dark) << "the excluded edge band stays thinner than the umbra";
    std::printf("spot oracle: %u occluded, %u lit, %u outside the cone, %u in the edge band\n", c.dark, c.lit,
                c.unlit, c.band);
}

TEST_F(LightShadowOracleTest, GrazingSunOnARoomCornerCastsNoAcne) {
    std::vector<PlacedQuad> quads{floorQuad(2.0f), {}, {}};
    quads[1].centre = {0.0f, 1.0f, -2.0f};  // back wall
    quads[1].halfSize = {2.0f, 1.0f};
    quads[2].centre = {-2.0f, 1.0f, 0.0f};  // left wall
    quads[2].normal = {1.0f, 0.0f, 0.0f};
    quads[2].halfSize = {2.0f, 1.0f};
    // Towards -x, slightly down and back: incidence 83 degrees on the floor, 76 on the back wall, 16 on the left
    // wall; every ray towards the sun leaves the room without hitting a wall.
    const glm::vec3 direction(-1.0f, -0.12f, -0.25f);
    scene::Scene scene = makePlacedQuadScene(quads);
    scene.lights.push_back(sunLight(direction, 3.0f));
    scene::CameraView camera = shadowTestCamera({2.6f, 2.4f, 2.6f}, {-0.8f, 0.4f, -0.8f});
    ShadowFrames f = renderShadowFrames(ctx(), shaders(), scene, camera, "sun_corner",
                                        shadowTestSettings(kResolution));
    OracleLight oracle = sunOracle(scene, camera, direction);
    PrimaryHits hits = primaryHits(quads, camera);

    const AcneCounts c = checkNoAcne(f, hits, [&](const glm::dvec3& p) {
        EXPECT_FALSE(occludedFrom(quads, p, oracle.target(p))) << "the scene must have no shadow";
        return 4.0 * oracle.texel(p);  // PCF taps near a junction may see the other wall
    });
    EXPECT_EQ(c.failures, 0u) << "first: " << c.first;
    EXPECT_GT(c.tested, 6000u);
    std::printf("sun acne test: %u pixels, lowest visibility %.4f\n", c.tested, c.worst);
}

}  // namespace
}  // namespace idk::test
