// material_layer_textures_test.cpp: the textures of KHR_materials_specular, _clearcoat and _sheen in the
// rasterizer (G-buffer layer texels -> deferred lighting; forward BLEND shading), on scenes/material_spheres.gltf
// (support/layer_textures.hpp), 64x64 HDR on lavapipe:
//  * constant textures equal to the factors give the factors' frame, deferred and forward: every channel of every
//    pixel within 1e-3 relative (the sRGB decode of the texture view and the G-buffer's 8-bit sRGB round trip of
//    the colour texels are the only differences; measured numbers printed);
//  * a clearcoat texture that is 0 on the clearcoat sphere's -x half and 1 on its +x half: of the pixels the coat
//    changes (texture all 1 vs all 0), the textured frame equals the coated frame on some and the uncoated frame on
//    the others (each at least 20% of them, to 1e-3), and the coated ones lie to the right (+x) of the uncoated
//    ones in the image (the camera looks down -z).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "render/renderer.hpp"
#include "render/scene_textures.hpp"
#include "support/gpu_fixture.hpp"
#include "support/layer_textures.hpp"

namespace idk::test {
namespace {

constexpr uint32_t kSize = 64;

class MaterialLayerTexturesTest : public GpuTest {};

core::ImageRgba32f renderHdr(vk::Context& ctx, vk::ShaderLibrary& shaders, const scene::Scene& scene) {
    render::RenderSettings settings;
    settings.output = render::OutputKind::Hdr;
    render::Renderer renderer(ctx, shaders, settings);
    renderer.setScene(scene);
    render::SceneTextureStream textures(ctx, renderer, scene);
    textures.finishSynchronously();
    return renderer.renderOffscreen(scene::defaultCamera(scene), kSize, kSize).image;
}

bool close(float a, float b, float tol) { return std::abs(a - b) <= tol * (1.0f + std::abs(b)); }

scene::Scene blended(scene::Scene s) {  // the forward transparency pass: BLEND with alpha 1 shades like opaque
    for (scene::Material& m : s.materials) {
        m.alphaMode = scene::AlphaMode::Blend;
        m.baseColorFactor.a = 1.0f;
    }
    return s;
}

TEST_F(MaterialLayerTexturesTest, ConstantTexturesShadeLikeTheirFactors) {
    for (int blend = 0; blend < 2; ++blend) {
        scene::Scene factors = layer_textures::quantizedSpheres();
        scene::Scene textured = layer_textures::texturedSpheres();
        if (blend) {
            factors = blended(factors);
            textured = blended(textured);
        }
        const core::ImageRgba32f a = renderHdr(ctx(), shaders(), textured);
        const core::ImageRgba32f b = renderHdr(ctx(), shaders(), factors);
        double worst = 0.0;
        size_t bad = 0;
        for (size_t i = 0; i < a.pixels.size(); ++i) {
            if (i % 4 == 3) continue;
            worst = std::max(worst, std::abs(double(a.pixels[i]) - b.pixels[i]) / (1.0 + std::abs(b.pixels[i])));
            bad += !close(a.pixels[i], b.pixels[i], 1e-3f);
        }
        std::printf("raster %s: constant extension textures vs factors: worst relative difference %.2e\n",
                    blend ? "forward (BLEND)" : "deferred", worst);
        EXPECT_EQ(bad, 0u) << (blend ? "forward" : "deferred");
    }
}

TEST_F(MaterialLayerTexturesTest, AClearcoatTextureCoatsOnlyWhereItIsOne) {
    // The references take the same shader path (a clearcoat texture, all 255 or all 0): only the texel differs.
    const scene::Scene half = layer_textures::coatHalfSpheres();
    const scene::Scene coated = layer_textures::coatHalfSpheres(255, 255);
    const scene::Scene bare = layer_textures::coatHalfSpheres(0, 0);
    const core::ImageRgba32f h = renderHdr(ctx(), shaders(), half);
    const core::ImageRgba32f c = renderHdr(ctx(), shaders(), coated);
    const core::ImageRgba32f n = renderHdr(ctx(), shaders(), bare);
    size_t changed = 0, asCoated = 0, asBare = 0;
    double xCoated = 0.0, xBare = 0.0;
    for (size_t p = 0; p < size_t(kSize) * kSize; ++p) {
        bool differs = false, eqCoated = true, eqBare = true;
        for (int k = 0; k < 3; ++k) {
            const size_t i = 4 * p + size_t(k);
            differs |= !close(c.pixels[i], n.pixels[i], 1e-2f);
            eqCoated &= close(h.pixels[i], c.pixels[i], 1e-3f);
            eqBare &= close(h.pixels[i], n.pixels[i], 1e-3f);
        }
        if (!differs) continue;
        ++changed;
        const double x = double(p % kSize);
        if (eqCoated) {
            ++asCoated;
            xCoated += x;
        } else if (eqBare) {
            ++asBare;
            xBare += x;
        }
    }
    std::printf("raster half-coat: the coat changes %zu pixels; textured = coated on %zu, = uncoated on %zu\n",
                changed, asCoated, asBare);
    ASSERT_GT(changed, 20u);
    EXPECT_GE(asCoated, changed / 5);
    EXPECT_GE(asBare, changed / 5);
    if (asCoated > 0 && asBare > 0) {
        EXPECT_GT(xCoated / double(asCoated), xBare / double(asBare));
    }
}

}  // namespace
}  // namespace idk::test
