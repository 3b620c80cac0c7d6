// layer_spill_test.cpp: the G-buffer's spill target (include/gbuffer_layer_bits.glsl), 64x64 on lavapipe. A leaf
// quad whose one material combines KHR_materials_iridescence, _diffuse_transmission, a clearcoat normal texture and
// KHR_materials_anisotropy, each from 1x1 textures (decoys in the channels the extension does not read), lit by a
// point light in front, one behind and a constant environment:
//  * the deferred frame equals the forward (BLEND, alpha 1) frame: for each of the six textures, the deferred
//    frame's mean difference from the forward one is below a tenth of what dropping that texture alone changes in
//    the forward frame (per colour channel), so a texel the G-buffer lost (the factor alone shading) fails it
//    (measured: the frames differ by 7.4e-4, 8.5e-5, 3.7e-4 per channel, the G-buffer's quantised normal and
//    coat normal; the smallest effect, the iridescence thickness texture's, is 1.3e-2 in R; ignoring the spill
//    target's diffuse-transmission texels makes the difference 0.14 .. 0.34, its anisotropy direction 8.6e-3);
//  * the spill target is in the frame's graph only for that combination: not for the same material with
//    diffuse-transmission factors instead of textures and a coat without a normal texture (the first layers target
//    holds everything), nor for a scene without extensions.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>

#include "conformance/quad_scene.hpp"
#include "render/renderer.hpp"
#include "render/scene_textures.hpp"
#include "scene/camera.hpp"
#include "support/gpu_fixture.hpp"
#include "support/layer_textures.hpp"

namespace idk::test {
namespace {

constexpr uint32_t kSize = 64;

class LayerSpillTest : public GpuTest {};

// The six textures of the combined material, by the member they set.
enum Texture { kIridescence, kIridescenceThickness, kDiffTrans, kDiffTransColor, kCoatNormal, kAnisotropy, kCount };
constexpr const char* kNames[kCount] = {"iridescenceTexture", "iridescenceThicknessTexture",
                                        "diffuseTransmissionTexture", "diffuseTransmissionColorTexture",
                                        "clearcoatNormalTexture", "anisotropyTexture"};

// The leaf with every texture except `without` (kCount: all of them); `textured` false: no texture at all.
scene::Scene combinedLeaf(bool blend, Texture without, bool textured = true) {
    namespace lt = layer_textures;
    conformance::QuadSpec q;
    q.halfSize = 0.45f;
    q.baseColor = glm::vec3(0.5f, 0.45f, 0.4f);
    q.roughness = 0.45f;
    q.doubleSided = true;
    scene::Scene s = conformance::makeQuadScene({q});
    scene::Material& m = s.materials[0];
    if (blend) m.alphaMode = scene::AlphaMode::Blend;  // alpha 1: the forward pass shades it like opaque
    m.iridescence = 1.0f;
    m.iridescenceIor = 1.8f;
    m.iridescenceThicknessMin = 100.0f;
    m.iridescenceThicknessMax = 800.0f;
    m.diffuseTransmission = 1.0f;
    m.clearcoat = 1.0f;
    m.clearcoatRoughness = 0.1f;
    m.anisotropyStrength = 1.0f;
    const std::array<std::array<uint8_t, 4>, kCount> texels = {{
        {150, lt::kDecoy, lt::kDecoy, lt::kDecoy},  // iridescence factor R
        {lt::kDecoy, 60, lt::kDecoy, lt::kDecoy},   // thickness G: 100 + 0.235 * 700 nm
        {lt::kDecoy, lt::kDecoy, lt::kDecoy, 140},  // diffuse transmission A
        {230, 110, 50, lt::kDecoy},                 // diffuse-transmission colour RGB (sRGB)
        {200, 80, 225, 255},                        // coat normal: tilted
        {128, 255, 190, 255},                       // anisotropy: RG 90 degrees, B strength 0.75
    }};
    std::optional<scene::TextureRef>* slots[kCount] = {&m.iridescenceTexture, &m.iridescenceThicknessTexture,
                                                       &m.diffuseTransmissionTexture,
                                                       &m.diffuseTransmissionColorTexture, &m.clearcoatNormalTexture,
                                                       &m.anisotropyTexture};
    for (int t = 0; t < kCount && textured; ++t)
        if (t != without) *slots[t] = lt::addTexture(s, {texels[t]});
    for (float z : {1.0f, -1.0f}) {  // one light in front, one behind (the diffuse transmission)
        scene::Light light;
        light.type = scene::LightType::Point;
        light.position = glm::vec3(0.25f * z, 0.15f, z);
        light.intensity = 1.5f;
        s.lights.push_back(light);
    }
    return s;
}

scene::CameraView leafCamera() {
    scene::CameraView camera;
    camera.position = glm::vec3(0.0f, 0.0f, 2.0f);
    camera.yfov = 0.6f;
    return camera;
}

render::FrameResult render(vk::Context& ctx, vk::ShaderLibrary& shaders, const scene::Scene& scene) {
    render::RenderSettings settings;
    settings.output = render::OutputKind::Hdr;
    settings.environment = std::filesystem::path();  // constant radiance
    render::Renderer renderer(ctx, shaders, settings);
    renderer.setScene(scene);
    render::SceneTextureStream textures(ctx, renderer, scene);
    textures.finishSynchronously();  // the real textures, not the placeholders streaming starts with
    return renderer.renderOffscreen(leafCamera(), kSize, kSize);
}

// Mean absolute difference per colour channel.
std::array<double, 3> meanDifference(const core::ImageRgba32f& a, const core::ImageRgba32f& b) {
    std::array<double, 3> d{};
    for (size_t p = 0; p < a.pixels.size() / 4; ++p)
        for (int c = 0; c < 3; ++c) d[c] += std::abs(double(a.pixels[4 * p + c]) - b.pixels[4 * p + c]);
    for (double& x : d) x /= double(a.pixels.size() / 4);
    return d;
}

TEST_F(LayerSpillTest, CombinedExtensionTexturesRenderDeferredAsForward) {
    const render::FrameResult deferred = render(ctx(), shaders(), combinedLeaf(false, kCount));
    const render::FrameResult forward = render(ctx(), shaders(), combinedLeaf(true, kCount));
    EXPECT_NE(deferred.graphText.find("gbuffer layer spill"), std::string::npos);
    const std::array<double, 3> error = meanDifference(deferred.image, forward.image);
    double mean = 0.0;
    for (size_t i = 0; i < forward.image.pixels.size(); ++i)
        if (i % 4 != 3) mean += forward.image.pixels[i];
    mean /= double(forward.image.pixels.size() / 4 * 3);
    std::printf("deferred vs forward: mean difference %.2e %.2e %.2e (mean radiance %.3f)\n", error[0], error[1],
                error[2], mean);
    for (int t = 0; t < kCount; ++t) {
        const render::FrameResult dropped = render(ctx(), shaders(), combinedLeaf(true, Texture(t)));
        const std::array<double, 3> effect = meanDifference(dropped.image, forward.image);
        const double largest = std::max({effect[0], effect[1], effect[2]});
        std::printf("  forward without %s changes %.2e %.2e %.2e\n", kNames[t], effect[0], effect[1], effect[2]);
        EXPECT_GT(largest, 1e-3 * mean) << kNames[t] << ": the texture must matter for the test to see it dropped";
        for (int c = 0; c < 3; ++c) {
            if (effect[c] < 0.2 * largest) continue;  // a channel the texture barely touches
            EXPECT_LT(error[c], 0.1 * effect[c]) << kNames[t] << " channel " << c;
        }
    }
}

TEST_F(LayerSpillTest, SpillTargetOnlyForCombinationsThatNeedIt) {
    auto hasSpill = [&](const scene::Scene& s) {
        return render(ctx(), shaders(), s).graphText.find("gbuffer layer spill") != std::string::npos;
    };
    // Every extension, textures only where the first layers target has room (iridescence, anisotropy).
    scene::Scene fits = combinedLeaf(false, kCount, false);
    namespace lt = layer_textures;
    fits.materials[0].iridescenceTexture = lt::addTexture(fits, {{150, lt::kDecoy, lt::kDecoy, lt::kDecoy}});
    fits.materials[0].anisotropyTexture = lt::addTexture(fits, {{128, 255, 190, 255}});
    const render::FrameResult fitsFrame = render(ctx(), shaders(), fits);
    EXPECT_NE(fitsFrame.graphText.find("gbuffer layers"), std::string::npos);
    EXPECT_EQ(fitsFrame.graphText.find("gbuffer layer spill"), std::string::npos);
    EXPECT_FALSE(hasSpill(conformance::makeQuadScene({conformance::QuadSpec{}})));
    // One texture that needs the spill bits, with each partner that takes its place in the first target.
    scene::Scene diffTransAndCoat = combinedLeaf(false, kCount, false);
    diffTransAndCoat.materials[0].iridescence = 0.0f;
    diffTransAndCoat.materials[0].anisotropyStrength = 0.0f;
    diffTransAndCoat.materials[0].diffuseTransmissionColorTexture =
        lt::addTexture(diffTransAndCoat, {{230, 110, 50, lt::kDecoy}});
    EXPECT_FALSE(hasSpill(diffTransAndCoat)) << "diffuse-transmission texture, coat without a normal texture";
    diffTransAndCoat.materials[0].clearcoatNormalTexture = lt::addTexture(diffTransAndCoat, {{200, 80, 225, 255}});
    EXPECT_TRUE(hasSpill(diffTransAndCoat)) << "diffuse-transmission texture and a coat normal texture";
    scene::Scene anisotropicCoat = combinedLeaf(false, kCount, false);
    anisotropicCoat.materials[0].iridescence = 0.0f;
    anisotropicCoat.materials[0].diffuseTransmission = 0.0f;
    anisotropicCoat.materials[0].clearcoatNormalTexture = lt::addTexture(anisotropicCoat, {{200, 80, 225, 255}});
    EXPECT_TRUE(hasSpill(anisotropicCoat)) << "anisotropy and a coat normal texture";
}

}  // namespace
}  // namespace idk::test
