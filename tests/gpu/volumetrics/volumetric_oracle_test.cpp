// volumetric_oracle_test.cpp: volumetric lighting against a CPU ray march of the same medium and lights. Scene: a
// floor, a box and a point light above it (its cube shadow hides part of the medium), 128x128 HDR frames with no
// environment light. Per pixel the CPU predicts frame_off * T + L along the pixel's centre ray (T = exp(-sigma d)
// to the surface, L = sum over 512 midpoint steps of T(t) sigma I / r^2 HG(cos) V, V = the CPU ray test from the
// step to the light through the box) and the GPU frame with volumetrics on must match it: mean relative error
// below 3% and 95th percentile below 12% at half and at quarter resolution (errors stated; the largest are at the
// box's silhouette, where the upsample mixes depths, and at the edges of the shadow in the medium). The same
// prediction without V must be clearly worse: the medium's shadows are really there.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "render/renderer.hpp"
#include "support/gpu_fixture.hpp"
#include "support/shadow_oracle.hpp"

namespace idk::test {
namespace {

constexpr uint32_t kSize = kShadowFrameSize;
constexpr float kDensity = 0.3f, kAnisotropy = 0.3f;

core::ImageRgba32f renderFrame(vk::Context& ctx, vk::ShaderLibrary& shaders, const scene::Scene& scene,
                               const scene::CameraView& camera, bool volumetrics, uint32_t scale) {
    render::RenderSettings settings = shadowTestSettings(512);
    settings.environmentIntensity = 0.0f;
    settings.volumetrics.enabled = volumetrics;
    settings.volumetrics.density = kDensity;
    settings.volumetrics.anisotropy = kAnisotropy;
    settings.volumetrics.scale = scale;
    render::Renderer renderer(ctx, shaders, settings);
    renderer.setScene(scene);
    return renderer.renderOffscreen(camera, kSize, kSize).image;
}

double hg(double c, double g) { return (1 - g * g) / (4 * 3.14159265358979 * std::pow(1 + g * g - 2 * g * c, 1.5)); }

struct Errors {
    double mean = 0.0, p95 = 0.0;
};

Errors compare(const core::ImageRgba32f& on, const std::vector<glm::dvec3>& predicted) {
    std::vector<double> rel;
    for (size_t i = 0; i < predicted.size(); ++i) {
        glm::dvec3 g(on.pixels[4 * i], on.pixels[4 * i + 1], on.pixels[4 * i + 2]);
        rel.push_back(glm::length(g - predicted[i]) / std::max(glm::length(predicted[i]), 1e-3));
    }
    Errors e;
    for (double r : rel) e.mean += r / rel.size();
    std::sort(rel.begin(), rel.end());
    e.p95 = rel[rel.size() * 95 / 100];
    return e;
}

class VolumetricOracleTest : public GpuTest {};

TEST_F(VolumetricOracleTest, InScatteringMatchesACpuRayMarchWithShadows) {
    std::vector<PlacedQuad> quads{floorQuad(8.0f)};
    for (const PlacedQuad& f : boxFaces({0.3f, 0.0f, 0.0f}, {0.5f, 0.5f, 0.5f}, glm::vec3(0.6f))) quads.push_back(f);
    scene::Scene scene = makePlacedQuadScene(quads);
    const glm::dvec3 light(-0.6, 1.6, -0.2);
    const double intensity = 10.0;
    scene.lights.push_back(pointLight(glm::vec3(light), float(intensity)));
    scene::CameraView camera = shadowTestCamera({1.5f, 3.2f, 3.6f}, {0.0f, 0.0f, 0.0f});

    const core::ImageRgba32f off = renderFrame(ctx(), shaders(), scene, camera, false, 2);
    // The CPU prediction, with and without the medium's shadows.
    const glm::dmat4 inv = glm::inverse(glm::dmat4(scene::projectionMatrix(camera, 1.0f) * scene::viewMatrix(camera)));
    std::vector<glm::dvec3> predicted(kSize * kSize), unshadowed(kSize * kSize), withoutMedium(kSize * kSize);
    for (uint32_t py = 0; py < kSize; ++py) {
        for (uint32_t px = 0; px < kSize; ++px) {
            glm::dvec2 ndc((px + 0.5) / kSize * 2.0 - 1.0, (py + 0.5) / kSize * 2.0 - 1.0);
            glm::dvec4 a = inv * glm::dvec4(ndc, 0.0, 1.0), b = inv * glm::dvec4(ndc, 0.5, 1.0);
            glm::dvec3 o = glm::dvec3(a) / a.w, d = glm::normalize(glm::dvec3(b) / b.w - o);
            auto hit = castRay(quads, o, d, 0.0, 1e9);
            ASSERT_TRUE(hit.has_value()) << "every pixel sees the floor or the box";
            const glm::dvec3 eye(camera.position);
            const double len = glm::length(o + hit->t * d - eye);
            constexpr int kSteps = 512;
            glm::dvec3 lit(0.0), all(0.0);
            for (int k = 0; k < kSteps; ++k) {
                double t = (k + 0.5) * len / kSteps;
                glm::dvec3 x = eye + d * t, toLight = light - x;
                double r2 = glm::dot(toLight, toLight);
                glm::dvec3 l = toLight / std::sqrt(r2);
                double add = kDensity * std::exp(-kDensity * t) * (len / kSteps) * intensity / r2 * hg(glm::dot(l, d), kAnisotropy);
                all += glm::dvec3(add);
                if (!occludedFrom(quads, x, light)) lit += glm::dvec3(add);
            }
            const size_t i = size_t(py) * kSize + px;
            const glm::dvec3 surface(off.pixels[4 * i], off.pixels[4 * i + 1], off.pixels[4 * i + 2]);
            predicted[i] = surface * std::exp(-kDensity * len) + lit;
            withoutMedium[i] = surface;
            unshadowed[i] = surface * std::exp(-kDensity * len) + all;
        }
    }
    for (uint32_t scale : {2u, 4u}) {
        const core::ImageRgba32f on = renderFrame(ctx(), shaders(), scene, camera, true, scale);
        std::filesystem::path dir = std::filesystem::path(IDK_BINARY_DIR) / "volumetric_oracle_test";
        std::filesystem::create_directories(dir);
        core::writeImage((dir / ("on_scale" + std::to_string(scale) + ".exr")).string(), on);
        Errors e = compare(on, predicted), u = compare(on, unshadowed), none = compare(on, withoutMedium);
        EXPECT_LT(e.mean, 0.02) << "scale " << scale;
        EXPECT_LT(e.p95, 0.05) << "scale " << scale;
        EXPECT_GT(none.mean, 0.2) << "the medium changes the frame a lot";
        EXPECT_GT(u.mean, 2.0 * e.mean) << "scale " << scale << ": ignoring the medium's shadows must be worse";
        std::printf("volumetrics 1/%u: mean relative error %.4f, p95 %.4f (without the medium's shadows: mean %.4f)\n",
                    scale, e.mean, e.p95, u.mean);
    }
}

}  // namespace
}  // namespace idk::test
