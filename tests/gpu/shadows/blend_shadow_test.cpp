// blend_shadow_test.cpp: BLEND surfaces cast shadows by coverage in the shadow maps (include/shadow_caster.glsl:
// a stochastic alpha test per shadow texel and draw). BLEND panes over a lit floor, 128x128 HDR frames
// (support/shadow_oracle.hpp gives the floor visibility s per pixel): two overlapping panes (alpha 0.5 and 0.6)
// under a point light (cube), one pane (alpha 0.5) under a low sun (cascades). The CPU oracle casts the ray from
// the floor point to the light through the panes: the expected visibility is the product of (1 - alpha) of the
// panes it crosses (1, 0.5, 0.4 or 0.2).
//  * Pixels whose oracle changes within kBand world units are skipped (the filter footprint blurs the edge).
//  * Unshadowed floor: s >= 0.98. Behind the panes: the mean of s over each class within 0.05 of its oracle
//    value (the coins average out), and the mean over each pixel's 3x3 neighbours of its class within 0.3 (one
//    pixel's filter sees only a few texels' coins: single pixels stray up to ~0.47 from the oracle).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <string>

#include "support/gpu_fixture.hpp"
#include "support/shadow_oracle.hpp"

namespace idk::test {
namespace {

constexpr uint32_t kSize = kShadowFrameSize;
constexpr double kBand = 0.15;  // world units around an oracle change (cube texel ~0.02 at the floor, PCF 0.04 x d)
const float kAlphas[2] = {0.5f, 0.6f};

// Visibility the oracle expects at p: the product of (1 - alpha) over the panes (quads 1, 2) the ray crosses.
double oracleVisibility(const std::vector<PlacedQuad>& quads, const glm::dvec3& p, const glm::dvec3& light) {
    double v = 1.0;
    for (size_t k = 1; k < quads.size(); ++k)
        if (occludedFrom({quads[k]}, p, light)) v *= 1.0 - quads[k].alpha;
    return v;
}

struct ClassStats {
    double expected = 0.0, sum = 0.0, worst = 0.0;
    uint32_t count = 0;
};

void checkBlendShadows(vk::Context& ctx, vk::ShaderLibrary& shaders, const scene::Light& light,
                       const std::function<glm::dvec3(const glm::dvec3&)>& target, const std::string& name,
                       int panes) {
    std::vector<PlacedQuad> quads{floorQuad(3.0f)};
    for (int k = 0; k < panes; ++k) {
        PlacedQuad q;
        q.centre = {0.5f * k, 1.2f - 0.4f * k, 0.3f * k};
        q.normal = {0.0f, 1.0f, 0.0f};
        q.halfSize = {0.6f, 0.6f};
        q.baseColor = {0.8f, 0.3f + 0.4f * k, 0.2f};
        q.alpha = kAlphas[k];
        q.alphaMode = scene::AlphaMode::Blend;
        q.doubleSided = true;
        quads.push_back(q);
    }
    scene::Scene scene = makePlacedQuadScene(quads);
    scene.lights.push_back(light);
    const scene::CameraView camera = shadowTestCamera({0.0f, 4.5f, 4.5f}, {0.2f, 0.0f, 0.3f});
    const ShadowFrames f = renderShadowFrames(ctx, shaders, scene, camera, name, shadowTestSettings(512));
    const PrimaryHits hits = primaryHits(quads, camera);

    std::map<double, ClassStats> classes;  // by expected visibility
    std::vector<double> visibility(size_t(kSize) * kSize, -1.0), oracle(size_t(kSize) * kSize, -1.0);
    for (uint32_t py = 1; py + 1 < kSize; ++py) {
        for (uint32_t px = 1; px + 1 < kSize; ++px) {
            const size_t i = size_t(py) * kSize + px;
            if (hits.quad[i] != 0 || !interiorPixel(hits, px, py)) continue;  // floor seen directly only
            const glm::dvec3 p = hits.point[i];
            const double expected = oracleVisibility(quads, p, target(p));
            bool edge = false;
            for (int dz = -1; dz <= 1 && !edge; ++dz)
                for (int dx = -1; dx <= 1 && !edge; ++dx) {
                    const glm::dvec3 q = p + glm::dvec3(dx * kBand, 0.0, dz * kBand);
                    edge = oracleVisibility(quads, q, target(q)) != expected;
                }
            if (edge) continue;
            const double unshadowed = rgbSum(f.unshadowed, i) - rgbSum(f.ambient, i);
            if (unshadowed <= 1e-3) continue;  // the light does not reach it
            const double s = (rgbSum(f.full, i) - rgbSum(f.ambient, i)) / unshadowed;
            ClassStats& c = classes[expected];
            c.expected = expected;
            c.sum += s;
            c.worst = std::max(c.worst, std::abs(s - expected));
            ++c.count;
            visibility[i] = s;
            oracle[i] = expected;
        }
    }
    uint32_t failures = 0;
    double worstLocal = 0.0;
    std::string first;
    for (uint32_t py = 1; py + 1 < kSize; ++py) {
        for (uint32_t px = 1; px + 1 < kSize; ++px) {
            const size_t i = size_t(py) * kSize + px;
            if (oracle[i] < 0.0) continue;
            double sum = 0.0;
            int n = 0;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const size_t j = size_t(int(py) + dy) * kSize + size_t(int(px) + dx);
                    if (oracle[j] == oracle[i]) sum += visibility[j], ++n;
                }
            const double local = std::abs(sum / n - oracle[i]);
            if (oracle[i] < 1.0) worstLocal = std::max(worstLocal, local);
            const bool bad = oracle[i] == 1.0 ? visibility[i] < 0.98 : local > 0.3;
            if (bad && failures++ == 0)
                first = "pixel (" + std::to_string(px) + ", " + std::to_string(py) + "): s " +
                        std::to_string(visibility[i]) + ", 3x3 mean off by " + std::to_string(local) + ", oracle " +
                        std::to_string(oracle[i]);
        }
    }
    std::printf("%s: worst 3x3 mean |s - oracle| behind the panes %.3f\n", name.c_str(), worstLocal);
    EXPECT_EQ(failures, 0u) << name << ": first " << first;
    ASSERT_EQ(classes.size(), panes == 2 ? 4u : 2u) << name << ": lit, each pane alone and both";
    for (const auto& [expected, c] : classes) {
        EXPECT_GT(c.count, 100u) << name << ": oracle " << expected;
        EXPECT_NEAR(c.sum / c.count, expected, 0.05) << name << ": mean visibility, oracle " << expected;
        std::printf("%s BLEND shadows: oracle %.2f, %u pixels, mean s %.4f, worst |s - oracle| %.3f\n", name.c_str(),
                    expected, c.count, c.sum / c.count, c.worst);
    }
}

class BlendShadowTest : public GpuTest {};

TEST_F(BlendShadowTest, PointCubeVisibilityBehindBlendPanesIsTheProductOfOneMinusAlpha) {
    const glm::vec3 position(0.3f, 3.2f, 0.4f);
    checkBlendShadows(ctx(), shaders(), pointLight(position, 20.0f),
                      [position](const glm::dvec3&) { return glm::dvec3(position); }, "blend_point", 2);
}

TEST_F(BlendShadowTest, SunCascadeVisibilityBehindABlendPaneIsOneMinusAlpha) {
    scene::Light sun;
    sun.name = "test sun";
    sun.type = scene::LightType::Directional;
    sun.intensity = 3.0f;
    sun.direction = glm::normalize(glm::vec3(0.6f, -1.0f, 0.3f));  // the shadow falls beside the pane
    const glm::dvec3 toSun = -glm::dvec3(sun.direction);
    checkBlendShadows(ctx(), shaders(), sun, [toSun](const glm::dvec3& p) { return p + 100.0 * toSun; }, "blend_sun", 1);
}

}  // namespace
}  // namespace idk::test
