// shadow_oracle_test.cpp: point-light cube shadows in the deferred lighting against a CPU ray-cast oracle, on
// scenes of quads built in code (support/placed_quads.hpp, support/shadow_oracle.hpp), 128x128 HDR frames,
// constant environment (ambient).
// Per floor pixel: s = (full - ambient) / (unshadowed - ambient) in RGB sums, from three frames of the same scene:
// with shadows, with the light at intensity 0 (ambient only), with shadows off (PointShadowSettings::maxLights = 0).
//  * Occluder test (a light above a floor and a box): where the CPU ray from the floor point to the light hits the
//    box, s <= 0.02 (only ambient); where it does not, s >= 0.98 (no acne). Excluded: pixels next to a box
//    silhouette, and floor points within kBandTexels shadow texels (world size 2 |p - light| / resolution, divided
//    by the cosine of incidence, at least 1/4) of the CPU shadow boundary: the 3x3 PCF kernel plus bilinear
//    footprint (2.5 texels) and the normal offset (up to 4 texels) blur the edge. The contact region behind the
//    box is NOT excluded, so peter-panning there fails the test.
//  * Mask test: the same check under two alpha-MASK panes, one below its cutoff (cut away: casts nothing).
//  * Acne test (a room corner lit at grazing angles, nothing in between): s >= 0.99 on every lit pixel except
//    within kCornerBand of a concave edge, where a PCF tap may see the adjacent wall.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "support/gpu_fixture.hpp"
#include "support/shadow_oracle.hpp"

namespace idk::test {
namespace {

constexpr double kBandTexels = 5.0;
constexpr uint32_t kResolution = 512;

ShadowFrames renderFrames(vk::Context& ctx, vk::ShaderLibrary& shaders, const scene::Scene& scene,
                          const scene::CameraView& c, const std::string& name) {
    return renderShadowFrames(ctx, shaders, scene, c, name, shadowTestSettings(kResolution));
}

scene::CameraView lookAt(glm::vec3 eye, glm::vec3 target) { return shadowTestCamera(eye, target); }

// A point light seen by the oracle: shadow rays aim at it; a cube texel is 2 |p - light| / resolution wide.
OracleLight pointOracle(glm::vec3 position) {
    const glm::dvec3 L(position);
    return {[L](const glm::dvec3&) { return L; },
            [L](const glm::dvec3& p) { return 2.0 * glm::length(L - p) / kResolution; }};
}

FloorCounts checkFloor(const ShadowFrames& f, const std::vector<PlacedQuad>& visible,
                       const std::vector<PlacedQuad>& occluders, const scene::CameraView& camera, glm::vec3 light) {
    return checkShadowFloor(f, visible, occluders, camera, pointOracle(light), kBandTexels);
}

class ShadowOracleTest : public GpuTest {};

TEST_F(ShadowOracleTest, FloorIsDarkExactlyWhereTheCpuRayToTheLightHitsTheBox) {
    std::vector<PlacedQuad> quads{floorQuad(3.0f)};
    for (const PlacedQuad& f : boxFaces({0.0f, 0.0f, 0.0f}, {0.5f, 0.5f, 0.5f}, glm::vec3(0.6f))) quads.push_back(f);
    const glm::vec3 lightPos(-1.2f, 2.2f, -0.8f);
    scene::Scene scene = makePlacedQuadScene(quads);
    scene.lights.push_back(pointLight(lightPos, 20.0f));
    scene::CameraView camera = lookAt({0.8f, 4.0f, 4.2f}, {0.6f, 0.0f, 0.4f});
    ShadowFrames f = renderFrames(ctx(), shaders(), scene, camera, "occluder");
    FloorCounts c = checkFloor(f, quads, quads, camera, lightPos);
    EXPECT_EQ(c.failures, 0u) << "first: " << c.first;
    EXPECT_GT(c.dark, 1000u) << "occluded floor pixels tested";
    EXPECT_GT(c.lit, 3000u) << "lit floor pixels tested";
    EXPECT_LT(c.band, c.dark) << "the excluded edge band stays thinner than the umbra";
    std::printf("shadow oracle: %u occluded, %u lit floor pixels, %u in the edge band\n", c.dark, c.lit, c.band);
}

// Alpha MASK in the shadow pass: a pane whose alpha (0.3) is below its cutoff (0.5) is cut away entirely and
// casts nothing; one above it (0.9) casts a full shadow.
TEST_F(ShadowOracleTest, MaskedPaneBelowItsCutoffCastsNoShadow) {
    std::vector<PlacedQuad> quads{floorQuad(3.0f), {}, {}};
    for (int k : {1, 2}) {
        quads[k].centre = {k == 1 ? -0.9f : 0.9f, 0.8f, 0.0f};
        quads[k].normal = {0.0f, 1.0f, 0.0f};
        quads[k].halfSize = {0.6f, 0.6f};
        quads[k].alphaMode = scene::AlphaMode::Mask;
        quads[k].alpha = k == 1 ? 0.3f : 0.9f;
        quads[k].doubleSided = true;
    }
    const glm::vec3 lightPos(0.0f, 2.5f, 0.0f);
    scene::Scene scene = makePlacedQuadScene(quads);
    scene.lights.push_back(pointLight(lightPos, 20.0f));
    scene::CameraView camera = lookAt({0.0f, 4.5f, 4.0f}, {0.0f, 0.0f, 0.2f});
    ShadowFrames f = renderFrames(ctx(), shaders(), scene, camera, "mask");
    std::vector<PlacedQuad> seen{quads[0], quads[2]};  // the cut pane is invisible and casts nothing
    FloorCounts c = checkFloor(f, seen, {quads[2]}, camera, lightPos);
    EXPECT_EQ(c.failures, 0u) << "first: " << c.first;
    EXPECT_GT(c.dark, 500u);
    EXPECT_GT(c.lit, 3000u);
    std::printf("mask oracle: %u occluded, %u lit floor pixels, %u in the edge band\n", c.dark, c.lit, c.band);
}

TEST_F(ShadowOracleTest, GrazingLightOnARoomCornerCastsNoAcne) {
    std::vector<PlacedQuad> quads{floorQuad(2.0f), {}, {}};
    quads[1].centre = {0.0f, 1.0f, -2.0f};  // back wall
    quads[1].halfSize = {2.0f, 1.0f};
    quads[2].centre = {-2.0f, 1.0f, 0.0f};  // left wall
    quads[2].normal = {1.0f, 0.0f, 0.0f};
    quads[2].halfSize = {2.0f, 1.0f};
    const glm::vec3 lightPos(-1.7f, 0.2f, -1.7f);  // 0.2-0.3 from every surface: incidence up to ~86 degrees
    scene::Scene scene = makePlacedQuadScene(quads);
    scene.lights.push_back(pointLight(lightPos, 3.0f));
    scene::CameraView camera = lookAt({2.6f, 2.4f, 2.6f}, {-0.8f, 0.4f, -0.8f});
    ShadowFrames f = renderFrames(ctx(), shaders(), scene, camera, "corner");
    PrimaryHits hits = primaryHits(quads, camera);

    constexpr double kCornerBand = 0.03;  // world units from the wall/floor junctions
    const AcneCounts c = checkNoAcne(f, hits, [](const glm::dvec3&) { return kCornerBand; });
    EXPECT_EQ(c.failures, 0u) << "first: " << c.first;
    EXPECT_GT(c.tested, 6000u);
    std::printf("acne test: %u pixels, lowest visibility %.4f\n", c.tested, c.worst);
}

}  // namespace
}  // namespace idk::test
