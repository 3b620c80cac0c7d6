// pt_diffuse_transmission_test.cpp: KHR_materials_diffuse_transmission in the GPU path tracer against the CPU
// reference on a small authored scene: a thin double-sided leaf (a quad facing the camera) lit by a point light
// behind it, under a dim constant environment. At the same seed the GPU draws the CPU's samples: at least 90% of
// the pixels agree to 1e-3 relative and the means within 1%. The CPU reference itself against the formula: with
// the environment off, the leaf's centre seen from the front is the light's irradiance from behind times
// diffuseTransmission * color * W / pi (one NEE event, deterministic; W the Lambert lobes' albedo-scaled weight
// at normal view and light, support/plastic_weight.hpp); without the extension the front is
// black. A factor of 0 renders exactly (bit for bit) as the material without the extension, on the GPU. Textures
// (1x1, decoys in the unread channels): the CPU reference renders the textured leaf exactly as the factors the
// texels hold, and the GPU agrees with it as above.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "conformance/quad_scene.hpp"
#include "gpu/pathtrace/pt_image_util.hpp"
#include "pathtrace/cpu_path_tracer.hpp"
#include "pathtrace/pt_scene.hpp"
#include "support/gpu_fixture.hpp"
#include "support/layer_textures.hpp"
#include "support/plastic_weight.hpp"
#include "support/same_pixels.hpp"

namespace idk::test {
namespace {

constexpr uint32_t kSize = 48;
constexpr float kLightZ = -0.5f;
constexpr float kIntensity = 2.0f;

class PtDiffuseTransmissionTest : public GpuTest {};

scene::Scene leafScene(float factor) {
    conformance::QuadSpec leaf;
    leaf.halfSize = 0.6f;
    leaf.baseColor = glm::vec3(0.3f, 0.6f, 0.2f);
    leaf.roughness = 0.5f;
    leaf.doubleSided = true;
    scene::Scene s = conformance::makeQuadScene({leaf});
    s.materials[0].diffuseTransmission = factor;
    s.materials[0].diffuseTransmissionColor = glm::vec3(0.9f, 0.6f, 0.2f);
    scene::Light light;
    light.type = scene::LightType::Point;
    light.position = glm::vec3(0.0f, 0.0f, kLightZ);
    light.intensity = kIntensity;
    s.lights.push_back(light);
    return s;
}

scene::CameraView frontCamera() {
    scene::CameraView c;
    c.position = glm::vec3(0.0f, 0.0f, 2.0f);
    c.yfov = 0.5f;
    return c;
}

pathtrace::PtSettings settings() {
    pathtrace::PtSettings s;
    s.spp = 8;
    s.seed = 31;
    s.maxDepth = 4;
    s.rouletteDepth = 3;
    return s;
}

TEST_F(PtDiffuseTransmissionTest, GpuGivesTheCpuSamplesOnABackLitLeaf) {
    const scene::Scene sc = leafScene(0.7f);
    const glm::vec3 environment(0.1f);
    const pathtrace::PathTraceScene pts = pathtrace::buildPathTraceScene(sc, nullptr, 1.0f, environment);
    const core::ImageRgba32f cpu = pathtrace::renderReference(pts, frontCamera(), kSize, kSize, settings());
    const double meanGpu = meanRadiance(
        expectGpuDrawsTheCpuSamples(ctx(), shaders(), sc, pts, frontCamera(), kSize, settings(), cpu, "back-lit leaf"));

    // A factor of 0 is the material without the extension, bit for bit (the colour is never read).
    scene::Scene off = leafScene(0.0f), plain = leafScene(0.0f);
    plain.materials[0].diffuseTransmissionColor = glm::vec3(1.0f);
    const pathtrace::PathTraceScene offPts = pathtrace::buildPathTraceScene(off, nullptr, 1.0f, environment);
    const pathtrace::PathTraceScene plainPts = pathtrace::buildPathTraceScene(plain, nullptr, 1.0f, environment);
    render::PathTracerOptions options;
    options.traversal = render::PtTraversal::Bvh;
    render::PathTracer offTracer(ctx(), shaders(), off, offPts, options);
    render::PathTracer plainTracer(ctx(), shaders(), plain, plainPts, options);
    const core::ImageRgba32f a = offTracer.render(frontCamera(), kSize, kSize, settings()).image;
    const core::ImageRgba32f b = plainTracer.render(frontCamera(), kSize, kSize, settings()).image;
    EXPECT_EQ(a.pixels, b.pixels);
    // The transmitted light is real: the leaf with the extension is brighter than without.
    EXPECT_GT(meanGpu, 1.5 * meanRadiance(a));
}

TEST_F(PtDiffuseTransmissionTest, TexturesGiveTheirFactorsOnGpuAndCpu) {
    using namespace layer_textures;
    const uint8_t factorCode = 153, colorCode[3] = {230, 120, 60};
    scene::Scene factors = leafScene(linearOf(factorCode));
    factors.materials[0].diffuseTransmissionColor =
        glm::vec3(srgbOf(colorCode[0]), srgbOf(colorCode[1]), srgbOf(colorCode[2]));
    scene::Scene textured = leafScene(1.0f);
    textured.materials[0].diffuseTransmissionColor = glm::vec3(1.0f);
    textured.materials[0].diffuseTransmissionTexture = addTexture(textured, {{kDecoy, kDecoy, kDecoy, factorCode}});
    textured.materials[0].diffuseTransmissionColorTexture =
        addTexture(textured, {{colorCode[0], colorCode[1], colorCode[2], kDecoy}});
    const glm::vec3 environment(0.1f);
    const pathtrace::PathTraceScene fPts = pathtrace::buildPathTraceScene(factors, nullptr, 1.0f, environment);
    const pathtrace::PathTraceScene tPts = pathtrace::buildPathTraceScene(textured, nullptr, 1.0f, environment);
    const core::ImageRgba32f cpuFactors = pathtrace::renderReference(fPts, frontCamera(), kSize, kSize, settings());
    const core::ImageRgba32f cpuTextured = pathtrace::renderReference(tPts, frontCamera(), kSize, kSize, settings());
    const double cpuDiff = rmse(cpuFactors, cpuTextured);
    std::printf("textured leaf: CPU textured vs factors RMSE %.2e (mean %.5f)\n", cpuDiff, meanRadiance(cpuFactors));
    EXPECT_LT(cpuDiff, 1e-5 * meanRadiance(cpuFactors));
    expectGpuDrawsTheCpuSamples(ctx(), shaders(), textured, tPts, frontCamera(), kSize, settings(), cpuTextured,
                                "textured leaf");
}

TEST_F(PtDiffuseTransmissionTest, CpuReferenceMatchesTheFormulaAtTheLeafCentre) {
    const pathtrace::PathTraceScene pts = pathtrace::buildPathTraceScene(leafScene(0.7f), nullptr, 1.0f,
                                                                         glm::vec3(0.0f));
    pathtrace::PtSettings s = settings();
    s.spp = 4;
    const core::ImageRgba32f img = pathtrace::renderReference(pts, frontCamera(), kSize, kSize, s);
    // Four centre pixels (the image centre is their shared corner), averaged: the leaf point (0, 0, 0) seen head on
    // (wo = +z), the light straight behind at distance |kLightZ| (wi = -z).
    double got[3] = {0.0, 0.0, 0.0};
    for (uint32_t y = kSize / 2 - 1; y <= kSize / 2; ++y)
        for (uint32_t x = kSize / 2 - 1; x <= kSize / 2; ++x)
            for (int c = 0; c < 3; ++c) got[c] += 0.25 * img.pixels[4 * (size_t(y) * kSize + x) + c];
    const double irradiance = kIntensity / (kLightZ * kLightZ);
    const double pass = plasticDiffuseWeight({0.5f, 1.5}, 1.0, 1.0);
    const double color[3] = {0.9, 0.6, 0.2};
    for (int c = 0; c < 3; ++c) {
        const double expected = irradiance * 0.7 * color[c] * pass / 3.14159265358979;
        std::printf("leaf centre channel %d: CPU %.5f, formula %.5f\n", c, got[c], expected);
        EXPECT_NEAR(got[c], expected, 0.01 * expected);  // the pixels' footprint: cos and 1/d^2 within 0.2%
    }
    // Without the extension nothing reaches the front.
    const pathtrace::PathTraceScene none = pathtrace::buildPathTraceScene(leafScene(0.0f), nullptr, 1.0f,
                                                                          glm::vec3(0.0f));
    EXPECT_EQ(meanRadiance(pathtrace::renderReference(none, frontCamera(), kSize, kSize, s)), 0.0);
}

}  // namespace
}  // namespace idk::test
