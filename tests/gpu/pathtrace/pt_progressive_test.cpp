// pt_progressive_test.cpp: the path tracer's progressive accumulation (PathTracer::beginProgressive / accumulate /
// resolveProgressive, the building block of a path-traced viewer mode) on scenes/material_spheres.gltf under a
// constant environment, 64x64. Oracles: render() of a fresh tracer with the same seed and sample count (the
// progressive image after 2 + 6 samples equals the 8-spp render: >= 99% of the pixels within 1e-4 relative, mean
// within 0.1%), a 64-spp render with another seed (the error falls from 2 to 8 samples), and the sample count
// (restarts at 0 with a new camera; render() ends the progressive image).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "gpu/pathtrace/pt_image_util.hpp"
#include "pathtrace/pt_scene.hpp"
#include "scene/gltf_loader.hpp"
#include "support/gpu_fixture.hpp"

namespace idk::test {
namespace {

constexpr uint32_t kSize = 64;

class PtProgressiveTest : public GpuTest {};

pathtrace::PtSettings settings(uint32_t spp, uint32_t seed) {
    pathtrace::PtSettings s;
    s.spp = spp;
    s.seed = seed;
    s.maxDepth = 4;
    return s;
}

TEST_F(PtProgressiveTest, AccumulatedSamplesGiveTheRenderAndConverge) {
    const scene::Scene sc = scene::loadGltf(std::filesystem::path(IDK_SOURCE_DIR) / "scenes/material_spheres.gltf");
    const pathtrace::PathTraceScene pts = pathtrace::buildPathTraceScene(sc, nullptr, 1.0f, glm::vec3(0.6f, 0.7f, 0.8f));
    const scene::CameraView camera = scene::defaultCamera(sc);
    render::PathTracerOptions options;
    options.traversal = render::PtTraversal::Bvh;
    options.samplesPerBatch = 2;

    render::PathTracer reference(ctx(), shaders(), sc, pts, options);
    const core::ImageRgba32f eight = reference.render(camera, kSize, kSize, settings(8, 5)).image;
    const core::ImageRgba32f converged = reference.render(camera, kSize, kSize, settings(64, 1000)).image;

    render::PathTracer tracer(ctx(), shaders(), sc, pts, options);
    tracer.beginProgressive(camera, kSize, kSize, settings(0, 5));
    EXPECT_EQ(tracer.accumulatedSamples(), 0u);
    EXPECT_EQ(tracer.accumulate(2), 2u);
    const render::PathTraceResult two = tracer.resolveProgressive();
    EXPECT_EQ(two.samples, 2u);
    EXPECT_EQ(tracer.accumulate(3), 5u);
    EXPECT_EQ(tracer.accumulate(3), 8u);  // batches of 2: 2 + 1
    const render::PathTraceResult progressive = tracer.resolveProgressive();
    EXPECT_EQ(progressive.samples, 8u);
    EXPECT_EQ(nonFiniteCount(progressive.image), 0u);

    size_t same = 0;
    const size_t pixels = size_t(kSize) * kSize;
    for (size_t p = 0; p < pixels; ++p) {
        bool close = true;
        for (int k = 0; k < 3; ++k) {
            const float a = progressive.image.pixels[4 * p + k], b = eight.pixels[4 * p + k];
            close &= std::abs(a - b) <= 1e-4f * (1.0f + std::abs(b));
        }
        same += close;
    }
    const double error2 = rmse(two.image, converged), error8 = rmse(progressive.image, converged);
    std::printf("progressive 2+6 spp vs render 8 spp: %zu of %zu pixels equal, mean %.5f vs %.5f; RMSE vs 64 spp: "
                "%.5f at 2 spp, %.5f at 8 spp\n",
                same, pixels, meanRadiance(progressive.image), meanRadiance(eight), error2, error8);
    EXPECT_GE(double(same), 0.99 * double(pixels));
    EXPECT_NEAR(meanRadiance(progressive.image), meanRadiance(eight), 1e-3 * meanRadiance(eight));
    EXPECT_LT(error8, 0.8 * error2);

    // A new camera restarts the count; render() ends the progressive image.
    scene::CameraView moved = camera;
    moved.position += glm::vec3(0.1f, 0.0f, 0.0f);
    tracer.beginProgressive(moved, kSize, kSize, settings(0, 5));
    EXPECT_EQ(tracer.accumulatedSamples(), 0u);
    EXPECT_EQ(tracer.accumulate(1), 1u);
    EXPECT_EQ(tracer.resolveProgressive().samples, 1u);
    tracer.render(camera, kSize, kSize, settings(1, 5));
    EXPECT_EQ(tracer.accumulatedSamples(), 0u);
    EXPECT_THROW(tracer.accumulate(1), std::logic_error);
    EXPECT_THROW(tracer.resolveProgressive(), std::logic_error);
}

}  // namespace
}  // namespace idk::test
