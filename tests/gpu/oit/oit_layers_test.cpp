// oit_layers_test.cpp: the fixed-layer OIT rung (`--oit layers`, 10 nearest fragments per pixel) against the
// sorted "over" rung (the exact reference) on a stack of 12 horizontal BLEND panes (alpha 0.5, shrinking upwards,
// so pixels see 0..12 layers) above a lit floor, 128x128 HDR. Pixels are classified by the CPU ray through their
// centre (how many panes it crosses; pixels whose 3x3 neighbourhood disagrees are edges, skipped):
//  * up to 10 layers: equal within 3e-3 relative RGB (both rungs composite the same shaded fragments in the same
//    order; the sorted rung rounds to RGBA16F after each blend, the layer rung stores half colours);
//  * 11 or 12 layers: the rung drops the farthest layers, so the difference is at most their share, the
//    transmittance of the nearest 10 (0.5^10) times the largest radiance behind them, plus the same rounding.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "render/renderer.hpp"
#include "shared/oit_types.h"
#include "support/gpu_fixture.hpp"
#include "support/shadow_oracle.hpp"

namespace idk::test {
namespace {

constexpr uint32_t kSize = kShadowFrameSize;
constexpr int kPanes = 12;
constexpr float kAlpha = 0.5f;

core::ImageRgba32f renderOit(vk::Context& ctx, vk::ShaderLibrary& shaders, const scene::Scene& scene,
                             const scene::CameraView& camera, render::OitMode mode) {
    render::RenderSettings settings = shadowTestSettings(256);
    settings.oit = mode;
    render::Renderer renderer(ctx, shaders, settings);
    renderer.setScene(scene);
    return renderer.renderOffscreen(camera, kSize, kSize).image;
}

// BLEND panes crossed by the ray through pixel (px, py) before the floor (quad 0); -1 if it misses the floor.
int layersAt(const std::vector<PlacedQuad>& quads, const glm::dmat4& inverseViewProjection, int px, int py) {
    glm::dvec2 ndc((px + 0.5) / kSize * 2.0 - 1.0, (py + 0.5) / kSize * 2.0 - 1.0);
    glm::dvec4 a = inverseViewProjection * glm::dvec4(ndc, 0.0, 1.0);
    glm::dvec4 b = inverseViewProjection * glm::dvec4(ndc, 0.5, 1.0);
    glm::dvec3 o = glm::dvec3(a) / a.w, d = glm::normalize(glm::dvec3(b) / b.w - o);
    int n = 0;
    double t = 0.0;
    while (auto hit = castRay(quads, o, d, t, 1e9)) {
        if (hit->quad == 0) return n;
        ++n;
        t = hit->t + 1e-6;
    }
    return -1;
}

glm::dvec3 rgb(const core::ImageRgba32f& img, size_t i) {
    return {img.pixels[4 * i], img.pixels[4 * i + 1], img.pixels[4 * i + 2]};
}

class OitLayersTest : public GpuTest {};

TEST_F(OitLayersTest, LayerRungIsExactUpToTenLayersAndLosesOnlyTheHiddenRestBeyond) {
    ASSERT_EQ(gpu::kOitLayerCount, 10u);  // the original's TRANSPARENT_LAYERS; the stack is built around it
    std::vector<PlacedQuad> quads{floorQuad(3.0f)};
    for (int k = 0; k < kPanes; ++k) {
        PlacedQuad q;
        q.centre = {0.0f, 0.2f + 0.1f * k, 0.0f};
        q.normal = {0.0f, 1.0f, 0.0f};
        q.halfSize = glm::vec2(1.3f - 0.085f * k);
        q.baseColor = {0.2f + 0.6f * float(k % 3 == 0), 0.2f + 0.6f * float(k % 3 == 1), 0.2f + 0.6f * float(k % 3 == 2)};
        q.alpha = kAlpha;
        q.alphaMode = scene::AlphaMode::Blend;
        q.doubleSided = true;
        quads.push_back(q);
    }
    scene::Scene scene = makePlacedQuadScene(quads);
    scene.lights.push_back(pointLight({0.5f, 3.0f, 1.0f}, 20.0f));
    scene::CameraView camera = shadowTestCamera({0.0f, 4.0f, 2.5f}, {0.0f, 0.3f, 0.0f});
    const core::ImageRgba32f sorted = renderOit(ctx(), shaders(), scene, camera, render::OitMode::Sorted);
    const core::ImageRgba32f layers = renderOit(ctx(), shaders(), scene, camera, render::OitMode::Layers);

    const glm::dmat4 inv = glm::inverse(glm::dmat4(scene::projectionMatrix(camera, 1.0f) * scene::viewMatrix(camera)));
    double brightest = 0.0;  // the largest radiance anywhere in the reference (bounds what hidden layers add)
    for (size_t i = 0; i < size_t(kSize) * kSize; ++i) brightest = std::max(brightest, glm::length(rgb(sorted, i)));
    const double hiddenShare = std::pow(1.0 - kAlpha, 10.0);
    uint32_t within = 0, beyond = 0, failures = 0, withMany = 0;
    double worstWithin = 0.0, worstBeyond = 0.0, sumBeyond = 0.0;
    for (int py = 1; py + 1 < int(kSize); ++py) {
        for (int px = 1; px + 1 < int(kSize); ++px) {
            const int n = layersAt(quads, inv, px, py);
            bool edge = n < 0;
            for (int dy = -1; dy <= 1 && !edge; ++dy)
                for (int dx = -1; dx <= 1 && !edge; ++dx) edge = layersAt(quads, inv, px + dx, py + dy) != n;
            if (edge) continue;
            const size_t i = size_t(py) * kSize + px;
            const glm::dvec3 s = rgb(sorted, i), l = rgb(layers, i);
            const double diff = glm::length(l - s);
            if (n <= 10) {
                const double rel = diff / std::max(glm::length(s), 1e-4);
                worstWithin = std::max(worstWithin, rel);
                failures += rel > 3e-3;
                ++within;
                withMany += n >= 8;
            } else {
                worstBeyond = std::max(worstBeyond, diff);
                sumBeyond += diff;
                failures += diff > hiddenShare * brightest + 3e-3 * glm::length(s);
                ++beyond;
            }
        }
    }
    EXPECT_EQ(failures, 0u) << "worst relative error up to 10 layers " << worstWithin << ", worst difference beyond "
                            << worstBeyond << " (bound " << hiddenShare * brightest << ")";
    EXPECT_GT(within, 3000u);
    EXPECT_GT(withMany, 200u);  // the exact region includes deep stacks (8-10 layers)
    ASSERT_GT(beyond, 100u);
    std::printf("layer OIT vs sorted: %u pixels with <= 10 layers (%u with 8-10), worst relative RGB %.2e; %u with "
                "11-12 layers, mean |diff| %.2e worst %.2e (bound 0.5^10 x %.3f = %.2e)\n",
                within, withMany, worstWithin, beyond, sumBeyond / beyond, worstBeyond, brightest,
                hiddenShare * brightest);
}

}  // namespace
}  // namespace idk::test
