// diffuse_transmission_ambient_test.cpp: the rasterizer's diffuse-transmission ambient (include/surface_lighting.glsl
// ambientTransmitted: the SH irradiance from behind) against the path tracers' lobe. A double-sided leaf with
// diffuseTransmission 1, turned 57 degrees from the camera (n.v ~0.54 at the centre, where the dielectric's albedo
// Es(n.v) is well above its normal-incidence value), under the constant environment (radiance 0.5), no lights.
// The light that comes through it from behind is the frame with diffuseTransmissionColor white minus the frame
// with it black (the reflected light is the same in both and cancels). Two black dielectrics (roughness 0.25,
// 0.6) and a half-metal (0.4, metallic 0.5, base 0.8):
//  * by hand: per pixel, (1 - metallic) 0.5 / pi times the path tracers' weight W(n.v, mu) mu (support/
//    plastic_weight.hpp) integrated over the hemisphere behind; the raster within 1e-3 (per unit 1 - metallic;
//    measured 4.7e-4, the half-float frames). For uniform light that integral is (1 - Es(n.v)) exactly, the
//    weight the raster now takes;
//  * the GPU path tracer (64 spp, ~150k samples per frame): the frame means within 1.5% (measured raster / path
//    tracer 0.995, 0.995, 0.990; the path tracer sits ~0.002 above the by-hand value in all three, also at 256 spp).
//    The raster's former weight, one minus the split-sum reflectance with the metal mixed in, gave 1.005, 0.999
//    and 0.618 (the half-metal's transmission 38% low), and missed the by-hand value by 1.0% and 0.4% on the
//    dielectrics.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "conformance/quad_scene.hpp"
#include "gpu/pathtrace/pt_image_util.hpp"
#include "render/path_tracer.hpp"
#include "render/renderer.hpp"
#include "scene/camera.hpp"
#include "support/gpu_fixture.hpp"
#include "support/plastic_weight.hpp"

namespace idk::test {
namespace {

constexpr uint32_t kSize = 48;
constexpr float kTurn = 1.0f;  // radians about x
constexpr float kHalfSize = 1.2f;

class DiffuseTransmissionAmbientTest : public GpuTest {};

struct Leaf {
    float roughness = 0.5f;
    float metallic = 0.0f;
    glm::vec3 baseColor{0.0f};
};

scene::Scene turnedLeaf(const Leaf& leaf, float color) {
    conformance::QuadSpec q;
    q.halfSize = kHalfSize;
    q.baseColor = leaf.baseColor;
    q.roughness = leaf.roughness;
    q.metallic = leaf.metallic;
    q.doubleSided = true;
    const float a = kTurn;
    q.basis = glm::mat3(glm::vec3(1.0f, 0.0f, 0.0f), glm::vec3(0.0f, std::cos(a), std::sin(a)),
                        glm::vec3(0.0f, -std::sin(a), std::cos(a)));
    scene::Scene s = conformance::makeQuadScene({q});
    s.materials[0].diffuseTransmission = 1.0f;
    s.materials[0].diffuseTransmissionColor = glm::vec3(color);
    return s;
}

scene::CameraView camera() {
    scene::CameraView c;
    c.position = glm::vec3(0.0f, 0.0f, 2.0f);
    c.yfov = 0.5f;
    return c;
}

core::ImageRgba32f raster(vk::Context& ctx, vk::ShaderLibrary& shaders, const scene::Scene& s) {
    render::RenderSettings settings;
    settings.output = render::OutputKind::Hdr;
    settings.environment = std::filesystem::path();  // constant radiance 0.5
    render::Renderer renderer(ctx, shaders, settings);
    renderer.setScene(s);
    return renderer.renderOffscreen(camera(), kSize, kSize).image;
}

core::ImageRgba32f pathTrace(vk::Context& ctx, vk::ShaderLibrary& shaders, const scene::Scene& s) {
    render::PathTracerOptions options;
    options.environment = std::filesystem::path();  // constant radiance 0.5
    render::PathTracer tracer(ctx, shaders, s, options);
    render::PathTraceSettings settings;
    settings.spp = 64;
    settings.maxDepth = 4;
    return tracer.render(camera(), kSize, kSize, settings).image;
}

// The path tracers' lobe under the uniform radiance 0.5 from behind, by hand: (1 - metallic) 0.5 / pi times
// W(n.v, mu) mu integrated over the hemisphere behind (midpoint rule in mu, 2000 steps), per pixel centre (0 where
// the pixel does not see the leaf).
std::vector<double> oracle(const Leaf& leaf) {
    const PlasticSpec plastic{leaf.roughness, 1.5};
    const double gbufferMetallic = std::round(leaf.metallic * 255.0) / 255.0;  // the G-buffer's unorm8
    const glm::dvec3 normal(0.0, -std::sin(kTurn), std::cos(kTurn)), eye(0.0, 0.0, 2.0);
    const double t = std::tan(0.5 * double(camera().yfov));
    std::vector<double> out(size_t(kSize) * kSize, 0.0);
    for (uint32_t y = 0; y < kSize; ++y)
        for (uint32_t x = 0; x < kSize; ++x) {
            const glm::dvec3 d = glm::normalize(glm::dvec3((2.0 * (x + 0.5) / kSize - 1.0) * t,
                                                          (1.0 - 2.0 * (y + 0.5) / kSize) * t, -1.0));
            const glm::dvec3 p = eye + d * (-glm::dot(eye, normal) / glm::dot(d, normal));
            const glm::dvec3 along(0.0, std::cos(kTurn), std::sin(kTurn));
            if (std::abs(p.x) > kHalfSize || std::abs(glm::dot(p, along)) > kHalfSize) continue;
            const double mu0 = std::abs(glm::dot(normal, d));
            constexpr int kSteps = 2000;
            double integral = 0.0;  // of W mu over the hemisphere, / pi: 2 * integral of W mu dmu
            for (int i = 0; i < kSteps; ++i) {
                const double mu = (i + 0.5) / kSteps;
                integral += 2.0 * plasticDiffuseWeight(plastic, mu0, mu) * mu / kSteps;
            }
            out[size_t(y) * kSize + x] = (1.0 - gbufferMetallic) * 0.5 * integral;
        }
    return out;
}

TEST_F(DiffuseTransmissionAmbientTest, BackLitByAUniformEnvironmentMatchesThePathTracer) {
    for (const Leaf& leaf : {Leaf{0.25f}, Leaf{0.6f}, Leaf{0.4f, 0.5f, glm::vec3(0.8f)}}) {
        const core::ImageRgba32f white = raster(ctx(), shaders(), turnedLeaf(leaf, 1.0f));
        const core::ImageRgba32f black = raster(ctx(), shaders(), turnedLeaf(leaf, 0.0f));
        const double r = meanRadiance(white) - meanRadiance(black);
        const std::vector<double> expected = oracle(leaf);
        double worst = 0.0, expectedMean = 0.0;
        for (size_t i = 0; i < expected.size(); ++i) {
            expectedMean += expected[i] / double(expected.size());
            const double got = double(white.pixels[4 * i + 1]) - black.pixels[4 * i + 1];
            worst = std::max(worst, std::abs(got - expected[i]) / (1.0 - leaf.metallic));
        }
        const double p = meanRadiance(pathTrace(ctx(), shaders(), turnedLeaf(leaf, 1.0f))) -
                         meanRadiance(pathTrace(ctx(), shaders(), turnedLeaf(leaf, 0.0f)));
        std::printf("roughness %.2f metallic %.1f: transmitted ambient, frame mean: raster %.5f, path tracer %.5f "
                    "(raster / path tracer %.4f), by hand %.5f; raster vs by hand per pixel: worst %.2e\n",
                    leaf.roughness, leaf.metallic, r, p, r / p, expectedMean, worst);
        EXPECT_GT(p, 0.05) << leaf.roughness;  // the leaf covers most of the frame
        EXPECT_LT(worst, 1e-3) << "roughness " << leaf.roughness << " metallic " << leaf.metallic;
        EXPECT_NEAR(r / p, 1.0, 0.015) << "roughness " << leaf.roughness << " metallic " << leaf.metallic;
    }
}

}  // namespace
}  // namespace idk::test
