// vxgi_transparency_test.cpp: transparent (alpha BLEND) surfaces inside the VXGI grid trace the cone set per
// fragment in the forward pass (transparency/forward_body.h, parameters from the VXGI feature's buffer) where opaque
// surfaces get it from the G-buffer pass (vxgi/cone_trace.comp). The closed room (vxgi_room.hpp) lit only by its
// emissive panel, environment off, with a grey quad standing in it facing the camera, 64x64 pixels, 64^3 voxels,
// cones at full resolution: once OPAQUE (deferred lighting with the G-buffer pass's cones), once BLEND with alpha 1
// (the "over" blend then shows the forward pass's radiance alone). No punctual light and no sky: every pixel of
// the quad is its indirect light. Over the quad's interior pixels (CPU ray cast, its four neighbours on it too):
//  * --gi vxgi, --oit sorted (the default transparency pass): the transparent quad's mean radiance within 2% of the opaque one's and 95% of its pixels within
//    5% (the G-buffer rounds albedo to 8-bit sRGB and roughness to 8 bits, the forward pass does not; its receiver
//    plane comes from the triangle's derivatives instead of the depth buffer);
//  * --gi none: the transparent quad is exactly black, as before the forward pass traced cones (no environment, no
//    punctual light: nothing else lights it), and no VXGI pass ran.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "gpu/vxgi/vxgi_room.hpp"
#include "render/renderer.hpp"
#include "shared/pt_common.h"
#include "support/gpu_fixture.hpp"

namespace idk::test {
namespace {

constexpr uint32_t kSize = 64;
constexpr size_t kQuad = kStandingQuad;

scene::Scene roomScene(bool blend) {
    scene::Scene s = closedRoomScene(glm::vec3(8.0f), closedRoomWithStandingQuad());
    if (blend) {
        s.materials[kQuad].alphaMode = scene::AlphaMode::Blend;
        s.materials[kQuad].baseColorFactor.a = 1.0f;  // "over" with alpha 1: the forward radiance alone
    }
    return s;
}

struct Frame {
    core::ImageRgba32f image;
    size_t vxgiPasses = 0;
};

Frame render(vk::Context& ctx, vk::ShaderLibrary& shaders, const scene::Scene& s, frame::GiMode gi,
             render::OitMode oit = render::OitMode::Sorted) {
    render::RenderSettings settings;
    settings.oit = oit;
    settings.output = render::OutputKind::Hdr;
    settings.environmentIntensity = 0.0f;
    settings.vxgi.mode = gi;
    settings.vxgi.voxels = 64;
    settings.vxgi.resolution = frame::GiResolution::Full;
    render::Renderer renderer(ctx, shaders, settings);
    renderer.setScene(s);
    render::FrameResult frame = renderer.renderOffscreen(closedRoomCamera(), kSize, kSize);
    Frame f{frame.image};
    for (const std::string& pass : frame.passesRun) f.vxgiPasses += pass.rfind("vxgi_", 0) == 0;
    return f;
}

// The quad's interior pixels: the camera ray through the pixel and through its four neighbours hits it first.
std::vector<size_t> quadPixels() {
    const std::vector<PlacedQuad> quads = closedRoomWithStandingQuad();
    const scene::CameraView camera = closedRoomCamera();
    const glm::mat4 inverseViewProjection =
        glm::inverse(scene::projectionMatrix(camera, 1.0f) * scene::viewMatrix(camera));
    auto onQuad = [&](int x, int y) {
        glm::vec3 o, d;
        gpu::ptCameraRay(inverseViewProjection, glm::vec2(float(x) + 0.5f, float(y) + 0.5f), glm::vec2(float(kSize)),
                         o, d);
        const auto h = castRay(quads, glm::dvec3(o), glm::dvec3(d), 0.0, 1e9);
        return h && h->quad == kQuad;
    };
    std::vector<size_t> out;
    for (int y = 1; y + 1 < int(kSize); ++y)
        for (int x = 1; x + 1 < int(kSize); ++x)
            if (onQuad(x, y) && onQuad(x - 1, y) && onQuad(x + 1, y) && onQuad(x, y - 1) && onQuad(x, y + 1))
                out.push_back(size_t(y) * kSize + size_t(x));
    return out;
}

double luminance(const core::ImageRgba32f& img, size_t i) {
    const float* p = &img.pixels[i * 4];
    return (double(p[0]) + p[1] + p[2]) / 3.0;
}

class VxgiTransparencyTest : public GpuTest {};

TEST_F(VxgiTransparencyTest, TransparentQuadTracesConesLikeTheOpaquePath) {
    const std::vector<size_t> pixels = quadPixels();
    ASSERT_GT(pixels.size(), size_t(200)) << "the camera should see the quad";
    const Frame opaque = render(ctx(), shaders(), roomScene(false), frame::GiMode::Vxgi);
    // The sorted rung traces cones; the OIT rungs (--oit weighted|layers) keep the SH ambient.
    for (render::OitMode oit : {render::OitMode::Sorted}) {
        const Frame blend = render(ctx(), shaders(), roomScene(true), frame::GiMode::Vxgi, oit);
        double sumOpaque = 0.0, sumBlend = 0.0, worst = 0.0;
        size_t close = 0;
        for (size_t i : pixels) {
            const double a = luminance(blend.image, i), b = luminance(opaque.image, i);
            sumOpaque += b;
            sumBlend += a;
            const double rel = std::abs(a - b) / std::max(b, 1e-6);
            worst = std::max(worst, rel);
            close += rel <= 0.05;
        }
        const double meanRel = std::abs(sumBlend - sumOpaque) / sumOpaque;
        const double closeFraction = double(close) / double(pixels.size());
        std::printf("quad in the lit room (oit %d), %zu pixels: mean radiance opaque %.4f, transparent %.4f (rel. "
                    "%.4f), within 5%%: %.4f, worst rel. %.4f\n",
                    int(oit), pixels.size(), sumOpaque / double(pixels.size()), sumBlend / double(pixels.size()),
                    meanRel, closeFraction, worst);
        EXPECT_GT(sumOpaque, 0.0) << "the panel lights the quad through the cones";
        EXPECT_LT(meanRel, 0.02) << "oit " << int(oit);
        EXPECT_GE(closeFraction, 0.95) << "oit " << int(oit);
    }
}

TEST_F(VxgiTransparencyTest, GiNoneLeavesTheTransparentQuadAsBefore) {
    const std::vector<size_t> pixels = quadPixels();
    const Frame none = render(ctx(), shaders(), roomScene(true), frame::GiMode::None);
    EXPECT_EQ(none.vxgiPasses, 0u);
    size_t black = 0;
    for (size_t i : pixels)
        black += none.image.pixels[i * 4] == 0.0f && none.image.pixels[i * 4 + 1] == 0.0f &&
                 none.image.pixels[i * 4 + 2] == 0.0f;
    EXPECT_EQ(black, pixels.size()) << "nothing but cones could light the quad";
}

}  // namespace
}  // namespace idk::test
