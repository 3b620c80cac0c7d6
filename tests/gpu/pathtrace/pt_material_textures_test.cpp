// pt_material_textures_test.cpp: the textures of KHR_materials_specular, _clearcoat and _sheen in both path
// tracers (pathtrace::evaluateMaterial, pathtrace/wf_shading.h), on scenes/material_spheres.gltf
// (support/layer_textures.hpp), 64x64, 8 spp under its point light and a constant environment:
//  * constant textures equal to the factors render what the factors alone render: at the same seed the CPU
//    images agree pixel for pixel (99% within 1e-4 relative: a rounding may flip a discrete choice; measured
//    100%), the GPU images 99% within 1e-3 (its sRGB views decode to ~1e-3 of the exact curve; measured 97.5% at
//    1e-4), each texel channel read from the right channel (the others hold a decoy value);
//  * GPU vs CPU on the textured scene: at least 90% of the pixels equal to 1e-3 relative, means within 1%
//    (the bar of pt_material_ext_test.cpp);
//  * the textures are real: the textured scene differs from the one without its extension textures by more
//    than 5% of the mean radiance.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "gpu/pathtrace/pt_image_util.hpp"
#include "pathtrace/cpu_path_tracer.hpp"
#include "pathtrace/pt_scene.hpp"
#include "support/gpu_fixture.hpp"
#include "support/layer_textures.hpp"

namespace idk::test {
namespace {

constexpr uint32_t kSize = 64;
const glm::vec3 kEnvironment(0.6f, 0.7f, 0.8f);

class PtMaterialTexturesTest : public GpuTest {};

pathtrace::PtSettings settings() {
    pathtrace::PtSettings s;
    s.spp = 8;
    s.seed = 91;
    s.maxDepth = 4;
    s.rouletteDepth = 3;
    return s;
}

// Fraction of pixels whose RGB agree within tol * (1 + |b|).
double agreeing(const core::ImageRgba32f& a, const core::ImageRgba32f& b, float tol) {
    size_t same = 0;
    const size_t pixels = a.pixels.size() / 4;
    for (size_t p = 0; p < pixels; ++p) {
        bool close = true;
        for (int k = 0; k < 3; ++k)
            close &= std::abs(a.pixels[4 * p + k] - b.pixels[4 * p + k]) <= tol * (1.0f + std::abs(b.pixels[4 * p + k]));
        same += close;
    }
    return double(same) / double(pixels);
}

core::ImageRgba32f cpuImage(const scene::Scene& s) {
    const pathtrace::PathTraceScene pts = pathtrace::buildPathTraceScene(s, nullptr, 1.0f, kEnvironment);
    EXPECT_TRUE(pts.warnings.empty()) << pts.warnings.front();
    return pathtrace::renderReference(pts, scene::defaultCamera(s), kSize, kSize, settings());
}

core::ImageRgba32f gpuImage(vk::Context& ctx, vk::ShaderLibrary& shaders, const scene::Scene& s) {
    const pathtrace::PathTraceScene pts = pathtrace::buildPathTraceScene(s, nullptr, 1.0f, kEnvironment);
    render::PathTracerOptions options;
    options.traversal = render::PtTraversal::Bvh;
    render::PathTracer tracer(ctx, shaders, s, pts, options);
    return tracer.render(scene::defaultCamera(s), kSize, kSize, settings()).image;
}

TEST_F(PtMaterialTexturesTest, ConstantTexturesRenderLikeTheirFactorsAndTheGpuMatchesTheCpu) {
    const scene::Scene factors = layer_textures::quantizedSpheres();
    const scene::Scene textured = layer_textures::texturedSpheres();
    ASSERT_EQ(textured.textures.size(), 6u);  // 2 specular + 2 clearcoat + 2 sheen

    const core::ImageRgba32f cpuFactors = cpuImage(factors), cpuTextured = cpuImage(textured);
    const double cpuSame = agreeing(cpuTextured, cpuFactors, 1e-4f);
    const core::ImageRgba32f gpuFactors = gpuImage(ctx(), shaders(), factors);
    const core::ImageRgba32f gpuTextured = gpuImage(ctx(), shaders(), textured);
    EXPECT_EQ(nonFiniteCount(gpuTextured), 0u);
    // The GPU decodes the colour textures through sRGB views (lavapipe: within ~1e-3 of the exact curve that the
    // factors were rounded with), hence the GPU's bar of 1e-3.
    const double gpuSame = agreeing(gpuTextured, gpuFactors, 1e-3f);
    const double gpuCpu = agreeing(gpuTextured, cpuTextured, 1e-3f);
    const double meanCpu = meanRadiance(cpuTextured), meanGpu = meanRadiance(gpuTextured);
    std::printf("extension textures: textured = factors on %.2f%% (CPU) and %.2f%% (GPU) of the pixels; GPU = CPU "
                "on %.2f%%; mean GPU %.5f CPU %.5f\n",
                100.0 * cpuSame, 100.0 * gpuSame, 100.0 * gpuCpu, meanGpu, meanCpu);
    EXPECT_GE(cpuSame, 0.99);
    EXPECT_GE(gpuSame, 0.99);
    EXPECT_NEAR(meanRadiance(cpuTextured), meanRadiance(cpuFactors), 1e-3 * meanRadiance(cpuFactors));
    EXPECT_GT(gpuCpu, 0.90);
    EXPECT_NEAR(meanGpu, meanCpu, 0.01 * meanCpu);

    // The textures carry the extensions: without them (factors 1, 1, 1, 1, 1, 1) the image is another one.
    scene::Scene untextured = textured;
    for (scene::Material& m : untextured.materials) {
        m.specularTexture = m.specularColorTexture = m.clearcoatTexture = m.clearcoatRoughnessTexture =
            m.sheenColorTexture = m.sheenRoughnessTexture = std::nullopt;
    }
    const double change = rmse(cpuImage(untextured), cpuTextured);
    std::printf("extension textures: RMSE with vs without them %.5f (%.1f%% of the mean)\n", change,
                100.0 * change / meanCpu);
    EXPECT_GT(change, 0.05 * meanCpu);
}

}  // namespace
}  // namespace idk::test
