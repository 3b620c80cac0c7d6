// jitter_test.cpp: the sub-pixel jitter of frame/temporal_feature.hpp: Halton(2,3) values, offsets inside the
// pixel with a mean near its centre over the phases, and a jittered matrix that moves every projected point by
// exactly -offset pixels (so the pixel centre sees the point `offset` away). No GPU.
#include <gtest/gtest.h>

#include <glm/glm.hpp>

#include "frame/temporal_feature.hpp"
#include "frame/upscale_feature.hpp"
#include "scene/camera.hpp"

namespace idk::frame {
namespace {

TEST(Jitter, HaltonMatchesTheRadicalInverse) {
    EXPECT_FLOAT_EQ(halton(1, 2), 0.5f);
    EXPECT_FLOAT_EQ(halton(2, 2), 0.25f);
    EXPECT_FLOAT_EQ(halton(3, 2), 0.75f);
    EXPECT_FLOAT_EQ(halton(6, 2), 0.375f);
    EXPECT_FLOAT_EQ(halton(1, 3), 1.0f / 3.0f);
    EXPECT_FLOAT_EQ(halton(5, 3), 2.0f / 3.0f + 1.0f / 9.0f);  // 5 = 12 in base 3
}

TEST(Jitter, OffsetsStayInsideThePixelAndAverageToItsCentre) {
    for (uint32_t phases : {1u, 6u, 16u}) {
        glm::vec2 sum(0.0f);
        for (uint32_t f = 0; f < phases; ++f) {
            const glm::vec2 o = jitterOffset(f, phases);
            EXPECT_GE(o.x, -0.5f);
            EXPECT_LT(o.x, 0.5f);
            EXPECT_GE(o.y, -0.5f);
            EXPECT_LT(o.y, 0.5f);
            sum += o;
            EXPECT_EQ(jitterOffset(f + phases, phases), o) << "the sequence repeats every `phases` frames";
        }
        if (phases == 16) {
            EXPECT_LT(std::abs(sum.x / 16.0f), 0.05f);
            EXPECT_LT(std::abs(sum.y / 16.0f), 0.05f);
        }
    }
}

TEST(Jitter, JitteredMatrixMovesProjectedPointsByMinusTheOffset) {
    scene::CameraView camera;
    camera.position = {0.3f, 0.2f, 4.0f};
    camera.forward = glm::normalize(glm::vec3(-0.1f, 0.0f, -1.0f));
    camera.up = {0.0f, 1.0f, 0.0f};
    const uint32_t width = 160, height = 90;
    const glm::mat4 vp = scene::projectionMatrix(camera, float(width) / float(height)) * scene::viewMatrix(camera);
    const glm::vec2 offset(0.3125f, -0.2f);
    const glm::mat4 jittered = jitteredViewProjection(vp, offset, width, height);
    const auto pixelOf = [&](const glm::mat4& m, glm::vec3 p) {
        const glm::vec4 c = m * glm::vec4(p, 1.0f);
        return (glm::vec2(c) / c.w * 0.5f + 0.5f) * glm::vec2(float(width), float(height));
    };
    for (glm::vec3 p : {glm::vec3(0.0f), glm::vec3(1.0f, -0.5f, 0.5f), glm::vec3(-2.0f, 1.0f, -3.0f)}) {
        const glm::vec2 shift = pixelOf(jittered, p) - pixelOf(vp, p);
        EXPECT_NEAR(shift.x, -offset.x, 1e-3f);
        EXPECT_NEAR(shift.y, -offset.y, 1e-3f);
        // Depth is untouched: the G-buffer's depth test sees the same surfaces.
        const glm::vec4 a = vp * glm::vec4(p, 1.0f), b = jittered * glm::vec4(p, 1.0f);
        EXPECT_FLOAT_EQ(a.z / a.w, b.z / b.w);
    }
}

// The upscaler lengthens the Halton sequence by 1 / S^2 (each output pixel sees as many samples near its centre
// as with TAA) and renders at round(S x size) per dimension.
TEST(Jitter, UpscalerPhasesAndRenderExtent) {
    render::RenderSettings s;
    s.temporal.frames = 16;
    s.temporal.aa = AntiAliasing::Taa;
    EXPECT_EQ(TemporalFeature::jitterPhases(s), 16u);
    s.temporal.aa = AntiAliasing::Upscale;
    s.temporal.upscale = 0.5f;
    EXPECT_EQ(TemporalFeature::jitterPhases(s), 64u);
    EXPECT_EQ(TemporalFeature::stillFrames(s), 64u);
    s.temporal.upscale = 1.0f;
    EXPECT_EQ(TemporalFeature::jitterPhases(s), 16u);
    s.temporal.upscale = 0.67f;
    EXPECT_EQ(TemporalFeature::jitterPhases(s), 36u);  // 16 / 0.4489 = 35.6
    const VkExtent2D e = UpscaleFeature::renderExtent(s, 1280, 720);
    EXPECT_EQ(e.width, 858u);   // 857.6
    EXPECT_EQ(e.height, 482u);  // 482.4
    s.temporal.upscale = 0.5f;
    EXPECT_EQ(UpscaleFeature::renderExtent(s, 1, 1).width, 1u);
    s.temporal.aa = AntiAliasing::None;
    EXPECT_EQ(TemporalFeature::stillFrames(s), 1u);
}

// `--aa taa --upscale S` runs the upscaler for S < 1 and TAA at S = 1 (the default); `--aa upscale` is the alias that
// runs the upscaler at any S; --aa none runs neither.
TEST(Jitter, TaaWithAScaleBelowOneRunsTheUpscaler) {
    render::RenderSettings s;
    EXPECT_EQ(s.temporal.upscale, 1.0f);
    s.temporal.frames = 16;
    s.temporal.aa = AntiAliasing::Taa;
    EXPECT_FALSE(UpscaleFeature::enabled(s));
    s.temporal.upscale = 0.5f;
    EXPECT_TRUE(UpscaleFeature::enabled(s));
    EXPECT_EQ(TemporalFeature::jitterPhases(s), 64u);
    s.temporal.upscale = 1.0f;
    s.temporal.aa = AntiAliasing::Upscale;
    EXPECT_TRUE(UpscaleFeature::enabled(s));
    s.temporal.aa = AntiAliasing::None;
    s.temporal.upscale = 0.5f;
    EXPECT_FALSE(UpscaleFeature::enabled(s));
    EXPECT_EQ(TemporalFeature::stillFrames(s), 1u);
}

}  // namespace
}  // namespace idk::frame
