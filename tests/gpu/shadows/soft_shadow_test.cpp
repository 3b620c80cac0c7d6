// soft_shadow_test.cpp: soft ray-traced shadows of a sphere light (`--shadows raytraced --light-radius 0.3
// --soft-shadow-rays N`: rt_shadows/mask_body.h traces N rays per pixel, rt_shadows/denoise.comp filters along the
// surfaces) against a CPU oracle: per floor pixel, the fraction of 2304 stratified directions uniform in the
// sphere's cone (seen from the floor point) that reach the sphere past an opaque square occluder
// (support/shadow_oracle.hpp sphereVisibility: castRay, exact for quads). 128x128 HDR frames, floor visibility s per
// pixel from support/shadow_oracle.hpp. Asserted, for 64 rays (and, looser, for 8 rays, where the raw estimate's standard
// deviation would be up to 0.18 per pixel and the filter carries the result):
//  * umbra (oracle 0) and fully lit (oracle 1) pixels: |s - oracle| <= 0.05 (0.15): only the filter's reach
//    into them from the penumbra moves them;
//  * penumbra: every pixel within 0.1 (0.2), the mean absolute error below 0.02 (0.04); the penumbra's pixel
//    count (0.05 < v < 0.95) within 10% (15%) of the oracle's (the filter widens it by about its sigma).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "support/gpu_fixture.hpp"
#include "support/shadow_oracle.hpp"

namespace idk::test {
namespace {

constexpr uint32_t kSize = kShadowFrameSize;
constexpr float kRadius = 0.3f;

struct Limits {
    double hard, penumbraWorst, penumbraMean, width;
};

void checkSoftShadows(vk::Context& ctx, vk::ShaderLibrary& shaders, uint32_t rays, const Limits& limits) {
    PlacedQuad occluder;
    occluder.centre = {0.0f, 0.8f, 0.0f};
    occluder.normal = {0.0f, 1.0f, 0.0f};
    occluder.halfSize = {0.5f, 0.5f};
    occluder.doubleSided = true;
    const std::vector<PlacedQuad> quads{floorQuad(3.0f), occluder};
    const glm::vec3 light(0.2f, 2.4f, 0.1f);
    scene::Scene scene = makePlacedQuadScene(quads);
    scene.lights.push_back(pointLight(light, 20.0f));
    const scene::CameraView camera = shadowTestCamera({0.0f, 4.0f, 3.5f}, {0.0f, 0.0f, 0.2f});
    render::RenderSettings settings = shadowTestSettings(512);
    settings.lightShadows.rayTraced = true;
    settings.lightShadows.lightRadius = kRadius;
    settings.lightShadows.softShadowRays = rays;
    const ShadowFrames f = renderShadowFrames(ctx, shaders, scene, camera, "soft_sphere_" + std::to_string(rays), settings);
    const PrimaryHits hits = primaryHits(quads, camera);

    uint32_t umbra = 0, lit = 0, penumbra = 0, gpuPenumbra = 0, oraclePenumbra = 0, failures = 0;
    double sumPenumbra = 0.0, worstPenumbra = 0.0, worstHard = 0.0;
    for (uint32_t py = 1; py + 1 < kSize; ++py) {
        for (uint32_t px = 1; px + 1 < kSize; ++px) {
            const size_t i = size_t(py) * kSize + px;
            if (hits.quad[i] != 0 || !interiorPixel(hits, px, py)) continue;
            const double unshadowed = rgbSum(f.unshadowed, i) - rgbSum(f.ambient, i);
            if (unshadowed <= 1e-3) continue;
            const double s = (rgbSum(f.full, i) - rgbSum(f.ambient, i)) / unshadowed;
            const double oracle = sphereVisibility({occluder}, hits.point[i], glm::dvec3(light), kRadius, 48);
            const double err = std::abs(s - oracle);
            gpuPenumbra += s > 0.05 && s < 0.95;
            oraclePenumbra += oracle > 0.05 && oracle < 0.95;
            if (oracle == 0.0 || oracle == 1.0) {
                (oracle == 0.0 ? umbra : lit) += 1;
                worstHard = std::max(worstHard, err);
                failures += err > limits.hard;
            } else {
                ++penumbra;
                sumPenumbra += err;
                worstPenumbra = std::max(worstPenumbra, err);
                failures += err > limits.penumbraWorst;
            }
        }
    }
    EXPECT_EQ(failures, 0u) << "worst umbra/lit error " << worstHard << ", worst penumbra error " << worstPenumbra;
    EXPECT_GT(umbra, 200u);
    EXPECT_GT(lit, 1000u);
    ASSERT_GT(penumbra, 300u);
    EXPECT_LT(sumPenumbra / penumbra, limits.penumbraMean);
    EXPECT_NEAR(double(gpuPenumbra) / oraclePenumbra, 1.0, limits.width) << "penumbra pixels " << gpuPenumbra << " vs "
                                                                 << oraclePenumbra;
    std::printf("soft shadows (radius %.2f, %u rays, denoised): %u umbra, %u lit (worst %.3f); %u penumbra pixels, mean |s - "
                "oracle| %.4f, worst %.3f; penumbra width %u vs oracle %u pixels\n",
                kRadius, rays, umbra, lit, worstHard, penumbra, sumPenumbra / penumbra, worstPenumbra, gpuPenumbra,
                oraclePenumbra);
}

class SoftShadowTest : public GpuTest {};

TEST_F(SoftShadowTest, SphereLightPenumbraMatchesTheCpuAverageOfManyRays) {
    checkSoftShadows(ctx(), shaders(), 64, {0.05, 0.1, 0.02, 0.1});
}

TEST_F(SoftShadowTest, EightRaysDenoisedStayCloseToTheCpuAverage) {
    checkSoftShadows(ctx(), shaders(), 8, {0.15, 0.2, 0.04, 0.15});
}

}  // namespace
}  // namespace idk::test
