// material_textures_test.cpp: the CPU path tracer's material evaluation (pathtrace::evaluateMaterial) reads the
// textures of KHR_materials_specular, _clearcoat and _sheen: at a hit on a material whose factors live in constant
// textures (support/layer_textures.hpp) the PtSurface equals the factor-only material's exactly (each value from
// its channel: specular A, specularColor sRGB RGB, clearcoat R, clearcoatRoughness G, sheenColor sRGB RGB,
// sheenRoughness A; the other channels hold a decoy); a 2x1 clearcoat texture (0 | 255) gives clearcoat 0 at
// u = 0.25 and the factor at u = 0.75, with its KHR_texture_transform (offset 0.5) swapping the halves.
#include <gtest/gtest.h>

#include "pathtrace/pt_material.hpp"
#include "pathtrace/pt_scene.hpp"
#include "support/layer_textures.hpp"

namespace idk::test {
namespace {

gpu::PtSurface surfaceAt(const pathtrace::PathTraceScene& pts, uint32_t material, glm::vec2 uv) {
    pathtrace::PtHitPoint hit;
    hit.material = material;
    hit.uv0 = uv;
    return pathtrace::evaluateMaterial(pts, hit, glm::vec3(0.0f, 0.0f, 1.0f)).surface;
}

TEST(PtMaterialTextures, ConstantTexturesGiveTheFactors) {
    const scene::Scene factors = layer_textures::quantizedSpheres();
    const scene::Scene textured = layer_textures::texturedSpheres();
    const pathtrace::PathTraceScene a = pathtrace::buildPathTraceScene(factors, nullptr, 1.0f, glm::vec3(0.5f));
    const pathtrace::PathTraceScene b = pathtrace::buildPathTraceScene(textured, nullptr, 1.0f, glm::vec3(0.5f));
    ASSERT_TRUE(b.warnings.empty()) << b.warnings.front();
    for (uint32_t m = 0; m < factors.materials.size(); ++m) {
        const gpu::PtSurface x = surfaceAt(a, m, glm::vec2(0.3f)), y = surfaceAt(b, m, glm::vec2(0.3f));
        EXPECT_NEAR(y.specular, x.specular, 1e-6f) << m;
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(y.specularColor[c], x.specularColor[c], 1e-6f) << m;
            EXPECT_NEAR(y.sheenColor[c], x.sheenColor[c], 1e-6f) << m;
        }
        EXPECT_NEAR(y.clearcoat, x.clearcoat, 1e-6f) << m;
        EXPECT_NEAR(y.clearcoatRoughness, x.clearcoatRoughness, 1e-6f) << m;
        EXPECT_NEAR(y.sheenRoughness, x.sheenRoughness, 1e-6f) << m;
    }
    // The factors are not the defaults: the comparison above is not vacuous.
    EXPECT_NEAR(surfaceAt(b, 1, glm::vec2(0.3f)).specular, 77.0f / 255.0f, 1e-6f);
    EXPECT_NEAR(surfaceAt(b, 2, glm::vec2(0.3f)).clearcoatRoughness, 26.0f / 255.0f, 1e-6f);
    EXPECT_NEAR(surfaceAt(b, 3, glm::vec2(0.3f)).sheenRoughness, 102.0f / 255.0f, 1e-6f);
}

TEST(PtMaterialTextures, AVaryingClearcoatTextureVariesTheCoat) {
    scene::Scene s = layer_textures::coatHalfSpheres();
    const uint32_t coat = layer_textures::kCoatMaterial;
    {
        const pathtrace::PathTraceScene pts = pathtrace::buildPathTraceScene(s, nullptr, 1.0f, glm::vec3(0.5f));
        EXPECT_EQ(surfaceAt(pts, coat, glm::vec2(0.25f, 0.5f)).clearcoat, 0.0f);
        EXPECT_EQ(surfaceAt(pts, coat, glm::vec2(0.75f, 0.5f)).clearcoat, 1.0f);
    }
    s.materials[coat].clearcoatTexture->offset = glm::vec2(0.5f, 0.0f);  // KHR_texture_transform: u + 0.5
    s.materials[coat].clearcoat = 0.5f;
    const pathtrace::PathTraceScene pts = pathtrace::buildPathTraceScene(s, nullptr, 1.0f, glm::vec3(0.5f));
    EXPECT_EQ(surfaceAt(pts, coat, glm::vec2(0.25f, 0.5f)).clearcoat, 0.5f);  // u' = 0.75: texel 255
    EXPECT_EQ(surfaceAt(pts, coat, glm::vec2(0.75f, 0.5f)).clearcoat, 0.5f);  // u' = 1.25: clamped to 255
    EXPECT_EQ(surfaceAt(pts, coat, glm::vec2(-0.4f, 0.5f)).clearcoat, 0.0f);  // u' = 0.1: texel 0
}

}  // namespace
}  // namespace idk::test
