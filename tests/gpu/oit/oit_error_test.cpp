// oit_error_test.cpp: the weighted blended OIT rung (`--oit weighted`) against the sorted "over" rung (the exact
// reference) on three overlapping coloured BLEND panes (alpha 0.5, 0.6, 0.4) above a lit floor, 128x128 HDR.
// Pixels are classified by the CPU ray through their centre (how many panes it crosses before the floor):
//  * no pane: identical (the rung leaves them alone);
//  * one pane: equal within 2e-3 relative (weighted blending is exact for a single layer; the RGBA16F sums round);
//  * two or three panes: the approximation's error, mean and worst relative RGB error printed, bounded (mean
//    below 25%): weighted blending averages the layers' colours instead of ordering them.
#include <gtest/gtest.h>

#include <algorithm>

#include "render/renderer.hpp"
#include "support/gpu_fixture.hpp"
#include "support/shadow_oracle.hpp"

namespace idk::test {
namespace {

constexpr uint32_t kSize = kShadowFrameSize;

core::ImageRgba32f renderOit(vk::Context& ctx, vk::ShaderLibrary& shaders, const scene::Scene& scene,
                             const scene::CameraView& camera, render::OitMode mode) {
    render::RenderSettings settings = shadowTestSettings(256);
    settings.oit = mode;
    render::Renderer renderer(ctx, shaders, settings);
    renderer.setScene(scene);
    return renderer.renderOffscreen(camera, kSize, kSize).image;
}

class OitErrorTest : public GpuTest {};

TEST_F(OitErrorTest, WeightedRungIsExactForOneLayerAndItsErrorIsReportedForMore) {
    std::vector<PlacedQuad> quads{floorQuad(3.0f)};
    const glm::vec3 colours[3] = {{0.9f, 0.1f, 0.1f}, {0.1f, 0.9f, 0.1f}, {0.1f, 0.2f, 0.9f}};
    const float alphas[3] = {0.5f, 0.6f, 0.4f};
    for (int k = 0; k < 3; ++k) {
        PlacedQuad q;
        q.centre = {-0.5f + 0.5f * k, 0.4f + 0.3f * k, -0.3f + 0.3f * k};
        q.normal = {0.0f, 1.0f, 0.0f};
        q.halfSize = {0.7f, 0.7f};
        q.baseColor = colours[k];
        q.alpha = alphas[k];
        q.alphaMode = scene::AlphaMode::Blend;
        q.doubleSided = true;
        quads.push_back(q);
    }
    scene::Scene scene = makePlacedQuadScene(quads);
    scene.lights.push_back(pointLight({0.5f, 3.0f, 1.0f}, 20.0f));
    scene::CameraView camera = shadowTestCamera({0.0f, 4.0f, 2.5f}, {0.0f, 0.3f, 0.0f});
    const core::ImageRgba32f sorted = renderOit(ctx(), shaders(), scene, camera, render::OitMode::Sorted);
    const core::ImageRgba32f weighted = renderOit(ctx(), shaders(), scene, camera, render::OitMode::Weighted);

    const glm::dmat4 inv = glm::inverse(glm::dmat4(scene::projectionMatrix(camera, 1.0f) * scene::viewMatrix(camera)));
    uint32_t counts[4] = {}, failures = 0;
    double sumMulti = 0.0, worstMulti = 0.0, worstSingle = 0.0;
    for (uint32_t py = 1; py + 1 < kSize; ++py) {
        for (uint32_t px = 1; px + 1 < kSize; ++px) {
            // Layers along the centre ray and its 8 neighbours' (edge pixels are mixed: skipped).
            int layers = -1;
            bool mixed = false;
            for (int dy = -1; dy <= 1 && !mixed; ++dy) {
                for (int dx = -1; dx <= 1 && !mixed; ++dx) {
                    glm::dvec2 ndc((px + dx + 0.5) / kSize * 2.0 - 1.0, (py + dy + 0.5) / kSize * 2.0 - 1.0);
                    glm::dvec4 a = inv * glm::dvec4(ndc, 0.0, 1.0), b = inv * glm::dvec4(ndc, 0.5, 1.0);
                    glm::dvec3 o = glm::dvec3(a) / a.w, d = glm::normalize(glm::dvec3(b) / b.w - o);
                    int n = 0;
                    double t = 0.0;
                    bool floor = false;
                    while (auto hit = castRay(quads, o, d, t, 1e9)) {
                        if (hit->quad == 0) {
                            floor = true;
                            break;
                        }
                        ++n;
                        t = hit->t + 1e-6;
                    }
                    if (!floor) n = -1;
                    if (layers == -1 && dx == -1 && dy == -1) layers = n;
                    mixed = n != layers;
                }
            }
            if (mixed || layers < 0) continue;
            const size_t i = size_t(py) * kSize + px;
            glm::dvec3 s(sorted.pixels[4 * i], sorted.pixels[4 * i + 1], sorted.pixels[4 * i + 2]);
            glm::dvec3 w(weighted.pixels[4 * i], weighted.pixels[4 * i + 1], weighted.pixels[4 * i + 2]);
            double rel = glm::length(w - s) / std::max(glm::length(s), 1e-4);
            ++counts[layers];
            if (layers == 0 && rel != 0.0) ++failures;
            if (layers == 1) {
                worstSingle = std::max(worstSingle, rel);
                failures += rel > 2e-3;
            }
            if (layers >= 2) {
                sumMulti += rel;
                worstMulti = std::max(worstMulti, rel);
            }
        }
    }
    const uint32_t multi = counts[2] + counts[3];
    EXPECT_EQ(failures, 0u) << "pixels with 0 or 1 layer that differ (worst single-layer " << worstSingle << ")";
    EXPECT_GT(counts[0], 1000u);
    EXPECT_GT(counts[1], 1000u);
    ASSERT_GT(multi, 300u);
    EXPECT_LT(sumMulti / multi, 0.25);
    std::printf("weighted OIT vs sorted: %u/%u/%u/%u pixels with 0/1/2/3 layers; 1 layer worst %.2e; 2-3 layers mean "
                "%.4f worst %.4f (relative RGB)\n",
                counts[0], counts[1], counts[2], counts[3], worstSingle, sumMulti / multi, worstMulti);
}

}  // namespace
}  // namespace idk::test
