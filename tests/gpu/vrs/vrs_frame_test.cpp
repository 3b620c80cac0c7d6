// vrs_frame_test.cpp: the software VRS rung in whole frames (Hdr output, sizes with partial tiles):
//  * every tile at 1x1 gives exactly the VRS-off frame (bit for bit), reconstruction included;
//  * at coarse rates (each fixed rate, and the classifier's own mix), lighting and sky shade exactly the pixels
//    the rates imply: with the target pre-filled by a sentinel and no reconstruction, the shaded pixels are
//    exactly the cell anchors, their count is FrameResult::shadingInvocations, and each equals the VRS-off pixel;
//  * with reconstruction, the frame stays close to VRS off (PSNR bound stated below).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <iostream>

#include "app/default_scene.hpp"
#include "frame/vrs_oracle.hpp"
#include "render/renderer.hpp"
#include "render/scene_textures.hpp"
#include "scene/gltf_loader.hpp"
#include "shared/vrs_types.h"
#include "support/gpu_fixture.hpp"

namespace idk::test {
namespace {

constexpr uint32_t kWidth = 104, kHeight = 72;  // partial tiles on the right and bottom

const scene::Scene& helmet() {
    static const scene::Scene s =
        scene::loadGltf(std::string(IDK_SHARED_DIR) + "/scenes/DamagedHelmet/glTF-Binary/DamagedHelmet.glb");
    return s;
}

struct Rendered {
    render::FrameResult frame;
    std::vector<uint32_t> rates;  // the rates the frame used (empty with VRS off)
};

// Renders the scene's default view; with VRS on, twice (the first frame classifies or fills the fixed rate).
Rendered render(vk::Context& ctx, vk::ShaderLibrary& shaders, const scene::Scene& scene, const frame::VrsSettings& vrs) {
    render::RenderSettings settings;
    settings.output = render::OutputKind::Hdr;
    settings.vrs = vrs;
    render::Renderer renderer(ctx, shaders, settings);
    renderer.setScene(scene);
    render::SceneTextureStream textures(ctx, renderer, scene);
    textures.finishSynchronously();
    const scene::CameraView camera = scene::defaultCamera(scene);
    if (vrs.enabled) renderer.renderOffscreen(camera, kWidth, kHeight);
    Rendered r;
    r.frame = renderer.renderOffscreen(camera, kWidth, kHeight);
    r.rates = renderer.vrs().lastRates();
    return r;
}

double psnr(const core::ImageRgba32f& a, const core::ImageRgba32f& b) {
    double se = 0.0;
    size_t n = 0;
    for (size_t i = 0; i < a.pixels.size(); ++i) {
        if (i % 4 == 3) continue;
        const double d = std::min(a.pixels[i], 1.0f) - std::min(b.pixels[i], 1.0f);  // radiance clipped at 1
        se += d * d;
        n++;
    }
    return 10.0 * std::log10(1.0 / std::max(se / double(n), 1e-20));
}

class VrsFrameTest : public GpuTest {};

TEST_F(VrsFrameTest, OneByOneEverywhereEqualsVrsOffExactly) {
    for (const scene::Scene& scene : {app::loadDefaultScene(), helmet()}) {
        Rendered off = render(ctx(), shaders(), scene, {});
        frame::VrsSettings vrs;
        vrs.enabled = true;
        vrs.fixedRate = 0;
        Rendered on = render(ctx(), shaders(), scene, vrs);
        ASSERT_EQ(on.frame.image.pixels.size(), off.frame.image.pixels.size());
        EXPECT_EQ(std::memcmp(on.frame.image.pixels.data(), off.frame.image.pixels.data(),
                              off.frame.image.pixels.size() * sizeof(float)), 0);
        EXPECT_EQ(off.frame.shadingInvocations, uint64_t(kWidth) * kHeight);
        EXPECT_EQ(on.frame.shadingInvocations, uint64_t(kWidth) * kHeight);
        EXPECT_NE(std::find(on.frame.passesRun.begin(), on.frame.passesRun.end(), "vrs_reconstruct"),
                  on.frame.passesRun.end());
    }
}

TEST_F(VrsFrameTest, CoarseRatesShadeExactlyTheCountedInvocations) {
    const scene::Scene scene = helmet();
    const Rendered off = render(ctx(), shaders(), scene, {});
    const uint32_t tile = gpu::kVrsDefaultTileSize, tilesX = (kWidth + tile - 1) / tile;
    for (int fixed : {1, 3, 4, -1}) {  // -1: the classifier's rates from the first frame
        frame::VrsSettings vrs;
        vrs.enabled = true;
        vrs.fixedRate = fixed;
        vrs.testShadedOnly = true;
        const Rendered on = render(ctx(), shaders(), scene, vrs);
        ASSERT_EQ(on.rates.size(), size_t(tilesX) * ((kHeight + tile - 1) / tile));
        const uint64_t expected = frame::vrsShadingInvocations(on.rates, tilesX, tile, kWidth, kHeight);
        EXPECT_EQ(on.frame.shadingInvocations, expected) << "rate " << fixed;
        uint64_t shaded = 0;
        for (uint32_t y = 0; y < kHeight; ++y) {
            for (uint32_t x = 0; x < kWidth; ++x) {
                const size_t i = (size_t(y) * kWidth + x) * 4;
                const glm::uvec2 cell = gpu::vrsCellSize(on.rates[(y / tile) * tilesX + x / tile]);
                const bool anchor = x % cell.x == 0 && y % cell.y == 0;
                const bool written = on.frame.image.pixels[i] != gpu::kVrsSentinel;
                shaded += written;
                ASSERT_EQ(written, anchor) << "rate " << fixed << " pixel " << x << "," << y;
                if (anchor) {
                    ASSERT_EQ(std::memcmp(&on.frame.image.pixels[i], &off.frame.image.pixels[i], 16), 0)
                        << "rate " << fixed << ": anchor " << x << "," << y << " differs from VRS off";
                }
            }
        }
        EXPECT_EQ(shaded, expected) << "rate " << fixed;
        if (fixed == 4) {
            EXPECT_EQ(expected, uint64_t(kWidth / 4) * (kHeight / 4));
        }
        std::cout << "[ vrs ] rate " << fixed << ": " << shaded << " of " << kWidth * kHeight << " pixels shaded\n";
    }
}

TEST_F(VrsFrameTest, ReconstructedFramesStayCloseToVrsOff) {
    const scene::Scene scene = helmet();
    const Rendered off = render(ctx(), shaders(), scene, {});
    for (int fixed : {1, -1}) {
        frame::VrsSettings vrs;
        vrs.enabled = true;
        vrs.fixedRate = fixed;
        const Rendered on = render(ctx(), shaders(), scene, vrs);
        const double db = psnr(on.frame.image, off.frame.image);
        std::cout << "[ vrs ] rate " << fixed << ": PSNR " << db << " dB, " << on.frame.shadingInvocations
                  << " invocations\n";
        // Measured on lavapipe: 30.5 dB at 2x1 everywhere, 36.5 dB at the classifier's rates (34% of the
        // invocations); unfilled or black pixels would give < 15 dB.
        EXPECT_GT(db, fixed == 1 ? 28.0 : 33.0) << "rate " << fixed;
        EXPECT_LT(on.frame.shadingInvocations, off.frame.shadingInvocations);
    }
}

}  // namespace
}  // namespace idk::test
