// material_layers_test.cpp: the rasterizer's material extensions and split-sum energy compensation
// (include/material_layers.glsl) on scenes/material_spheres.gltf, 64x64 on lavapipe:
//  * white furnace: every surface a white metal of roughness r (0.2 .. 1), no lights, constant environment
//    L = 0.5: every geometry pixel reflects L within 1% (the split-sum's A + B is the path tracer's tabulated GGX
//    albedo and the multiple-scattering factor makes up what single scattering loses: without it rough metals
//    reflect down to ~0.6 L at grazing views);
//  * the extensions reach the deferred and the forward (BLEND) shading: with them the frame differs from the same
//    scene with the extensions stripped by more than 1% of its summed radiance (the spheres are a small part of
//    the frame: measured 2.0% deferred, 1.9% forward), by the same amount on both paths (within 25%);
//  * KHR_materials_anisotropy: the deferred pass (direction from the G-buffer's layers target) and the forward pass
//    (tangent frame) shade the same anisotropic lobe: the change an anisotropic gold makes to the frame, against
//    the isotropic stand-in at the rms roughness, agrees per pixel on both paths; a scene without anisotropic
//    materials (or extension textures) allocates no layers target.
//  * KHR_materials_iridescence: the film changes the deferred and the forward frame alike; a film of thickness 0
//    renders the film-less frame; its textures (through the G-buffer's layer texels in the deferred pass) render
//    like the factors they encode;
//  * clearcoatNormalTexture: a tilted coat normal changes the deferred and the forward frame alike (within 25%);
//    a flat coat normal map (texel 128, 128, 255) renders the map-less frame within 0.1% of its radiance;
//  * anisotropyTexture: a constant texture (RG 255, 128: the tangent; B 204) renders as the factors (strength x 0.8)
//    in both passes, and in the forward pass (the one with a tangent frame) a texture direction of 90 degrees (RG
//    128, 255) as anisotropyRotation = pi/2, each within 1e-3 of the radiance, 10x below what the rotation (or, in
//    the deferred pass, an unread strength texel) changes.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <vector>

#include "render/renderer.hpp"
#include "render/scene_textures.hpp"
#include "scene/gltf_loader.hpp"
#include "support/gpu_fixture.hpp"
#include "support/quad_scene.hpp"
#include "support/layer_textures.hpp"

namespace idk::test {
namespace {

constexpr uint32_t kSize = 64;

scene::Scene materialSpheres() {
    return scene::loadGltf(std::filesystem::path(IDK_SOURCE_DIR) / "scenes/material_spheres.gltf");
}

core::ImageRgba32f renderHdr(vk::Context& ctx, vk::ShaderLibrary& shaders, const scene::Scene& scene, bool constantEnv) {
    render::RenderSettings settings;
    settings.output = render::OutputKind::Hdr;
    if (constantEnv) settings.environment = std::filesystem::path();  // constant radiance 0.5
    render::Renderer renderer(ctx, shaders, settings);
    renderer.setScene(scene);
    if (!scene.textures.empty()) {  // the extension-texture cases: every texture resident before the frame
        render::SceneTextureStream textures(ctx, renderer, scene);
        textures.finishSynchronously();
        return renderer.renderOffscreen(scene::defaultCamera(scene), kSize, kSize).image;
    }
    return renderer.renderOffscreen(scene::defaultCamera(scene), kSize, kSize).image;
}

class MaterialLayersTest : public GpuTest {};

TEST_F(MaterialLayersTest, RoughWhiteMetalFurnaceReflectsTheEnvironment) {
    for (float roughness : {0.2f, 0.5f, 0.8f, 1.0f}) {
        scene::Scene s = materialSpheres();
        s.lights.clear();
        for (scene::Material& m : s.materials) {
            m = scene::Material{};
            m.baseColorFactor = glm::vec4(1.0f);
            m.metallic = 1.0f;
            m.roughness = roughness;
        }
        const core::ImageRgba32f img = renderHdr(ctx(), shaders(), s, true);
        size_t geometry = 0;
        double lo = 1e9, hi = 0.0;
        for (size_t p = 0; p < size_t(kSize) * kSize; ++p) {
            if (img.pixels[4 * p + 3] < 1.0f) continue;
            ++geometry;
            for (int c = 0; c < 3; ++c) {
                lo = std::min(lo, double(img.pixels[4 * p + c]));
                hi = std::max(hi, double(img.pixels[4 * p + c]));
            }
        }
        std::printf("raster furnace, white metal roughness %.1f: %zu geometry pixels in [%.4f, %.4f] (L = 0.5)\n",
                    roughness, geometry, lo, hi);
        EXPECT_GT(geometry, size_t(kSize) * kSize / 4);
        EXPECT_GE(lo, 0.99 * 0.5) << "roughness " << roughness;
        EXPECT_LE(hi, 1.01 * 0.5) << "roughness " << roughness;
    }
}

double relativeChange(const core::ImageRgba32f& a, const core::ImageRgba32f& b) {
    double diff = 0.0, mean = 0.0;
    for (size_t i = 0; i < a.pixels.size(); ++i) {
        if (i % 4 == 3) continue;
        diff += std::abs(double(a.pixels[i]) - b.pixels[i]);
        mean += std::abs(double(b.pixels[i]));
    }
    return diff / std::max(mean, 1e-9);
}

TEST_F(MaterialLayersTest, ExtensionsChangeDeferredAndForwardShadingAlike) {
    double change[2];
    for (int blend = 0; blend < 2; ++blend) {
        scene::Scene layered = materialSpheres();
        for (scene::Material& m : layered.materials) {
            if (blend) {  // forward transparency pass: BLEND with alpha 1 shades like opaque, over the background
                m.alphaMode = scene::AlphaMode::Blend;
                m.baseColorFactor.a = 1.0f;
            }
        }
        scene::Scene plain = layered;
        for (scene::Material& m : plain.materials) {
            m.specular = 1.0f;
            m.specularColor = glm::vec3(1.0f);
            m.clearcoat = 0.0f;
            m.sheenColor = glm::vec3(0.0f);
        }
        const core::ImageRgba32f a = renderHdr(ctx(), shaders(), layered, false);
        const core::ImageRgba32f b = renderHdr(ctx(), shaders(), plain, false);
        change[blend] = relativeChange(a, b);
        std::printf("raster %s: the extensions change the frame by %.2f%% of its radiance\n",
                    blend ? "forward (BLEND)" : "deferred", 100.0 * change[blend]);
        EXPECT_GT(change[blend], 0.01) << (blend ? "forward" : "deferred");  // measured 2.0% and 1.9%
    }
    EXPECT_NEAR(change[0], change[1], 0.25 * change[0]) << "deferred and forward shade the extensions alike";
}

// Brushed spheres: tangents around the vertical axis (the file has no UVs, hence no generated tangents).
void brushedTangents(scene::Scene& s) {
    for (scene::Mesh& mesh : s.meshes) {
        for (scene::Primitive& prim : mesh.primitives) {
            prim.tangents.resize(prim.normals.size());
            for (size_t v = 0; v < prim.normals.size(); ++v) {
                const glm::vec3 t = glm::cross(glm::vec3(0.0f, 1.0f, 0.0f), prim.normals[v]);
                prim.tangents[v] = glm::dot(t, t) > 1e-8f ? glm::vec4(glm::normalize(t), 1.0f)
                                                          : glm::vec4(1.0f, 0.0f, 0.0f, 1.0f);
            }
        }
    }
}

TEST_F(MaterialLayersTest, AnisotropyDeferredMatchesForward) {
    const float strength = 0.8f;
    std::vector<double> delta[2], standInFrame[2];
    double change[2];
    for (int blend = 0; blend < 2; ++blend) {
        scene::Scene aniso = materialSpheres();
        brushedTangents(aniso);
        for (scene::Material& m : aniso.materials) {
            if (blend) {
                m.alphaMode = scene::AlphaMode::Blend;
                m.baseColorFactor.a = 1.0f;
            }
        }
        scene::Material& gold = aniso.materials[4];
        gold.roughness = 0.3f;
        gold.anisotropyStrength = strength;
        gold.anisotropyRotation = 0.4f;
        scene::Scene standIn = aniso;
        const float alpha = gold.roughness * gold.roughness;
        const float alphaT = alpha + (1.0f - alpha) * strength * strength;
        standIn.materials[4].anisotropyStrength = 0.0f;
        standIn.materials[4].roughness = std::sqrt(std::sqrt(0.5f * (alphaT * alphaT + alpha * alpha)));
        const core::ImageRgba32f a = renderHdr(ctx(), shaders(), aniso, false);
        const core::ImageRgba32f b = renderHdr(ctx(), shaders(), standIn, false);
        change[blend] = relativeChange(a, b);
        for (size_t i = 0; i < a.pixels.size(); ++i) {
            if (i % 4 == 3) continue;
            delta[blend].push_back(double(a.pixels[i]) - b.pixels[i]);
            standInFrame[blend].push_back(b.pixels[i]);
        }
    }
    // The forward pass draws every BLEND object back to front by its centre, so where spheres overlap the floor
    // a different surface can end on top than in the depth-tested G-buffer: compare the pixels where the
    // stand-in frames agree within 1% in every channel (the same surface visible on both paths).
    double disagreement = 0.0, magnitude = 0.0;
    size_t compared = 0;
    auto sameSurface = [&](size_t i) {
        return std::abs(standInFrame[0][i] - standInFrame[1][i]) <= 0.01 * std::abs(standInFrame[1][i]) + 1e-3;
    };
    for (size_t p = 0; p + 2 < delta[0].size(); p += 3) {
        if (!sameSurface(p) || !sameSurface(p + 1) || !sameSurface(p + 2)) continue;
        for (size_t i = p; i < p + 3; ++i) {
            ++compared;
            disagreement += std::abs(delta[0][i] - delta[1][i]);
            magnitude += std::abs(delta[1][i]);
        }
    }
    std::printf("raster: anisotropic gold vs the isotropic stand-in changes the frame by %.4f%% deferred, %.4f%% "
                "forward; on the %zu channels where both paths show the same surface the per-pixel changes differ "
                "by %.1f%% of the forward change\n",
                100.0 * change[0], 100.0 * change[1], compared, 100.0 * disagreement / magnitude);
    EXPECT_GT(change[1], 0.002);  // the anisotropic lobe is visible (one small sphere of the frame)
    EXPECT_GT(compared, delta[0].size() * 3 / 4);
    EXPECT_LT(disagreement, 0.05 * magnitude);
}

// The layers target exists only for scenes that need it: none for plain quads, one once a material is anisotropic.
TEST_F(MaterialLayersTest, LayersTargetOnlyForAnisotropicScenes) {
    for (float strength : {0.0f, 0.7f}) {
        scene::Scene s = makeQuadScene({QuadSpec{}});
        s.materials[0].anisotropyStrength = strength;
        render::RenderSettings settings;
        settings.output = render::OutputKind::Hdr;
        render::Renderer renderer(ctx(), shaders(), settings);
        renderer.setScene(s);
        const render::FrameResult frame = renderer.renderOffscreen(scene::defaultCamera(s), 32, 32);
        EXPECT_EQ(frame.graphText.find("gbuffer layers") != std::string::npos, strength > 0.0f) << strength;
    }
}

// Iridescent films on three spheres (factors), optionally as textures: the plastic's factor 0.8 from a constant
// R 204 texture, the gold's thickness (150 .. 600 nm) from a constant G 255 texture (so the maximum either way).
scene::Scene iridescentSpheres(bool blend, bool textured) {
    namespace lt = layer_textures;
    scene::Scene s = materialSpheres();
    for (size_t i = 1; i < s.materials.size() && blend; ++i) {  // the spheres; the floor stays opaque, so that
        s.materials[i].alphaMode = scene::AlphaMode::Blend;      // weighted-blended OIT does not mix it in
        s.materials[i].baseColorFactor.a = 1.0f;
    }
    scene::Material& plastic = s.materials[1];
    plastic.iridescence = textured ? 1.0f : 204.0f / 255.0f;
    plastic.iridescenceThicknessMax = 380.0f;
    scene::Material& gold = s.materials[4];
    gold.iridescence = 1.0f;
    gold.iridescenceIor = 1.8f;
    gold.iridescenceThicknessMin = 150.0f;
    gold.iridescenceThicknessMax = 600.0f;
    s.materials[2].iridescence = 0.7f;
    s.materials[2].iridescenceThicknessMax = 250.0f;
    if (textured) {
        lt::sideUvs(s, 1);
        lt::sideUvs(s, 4);
        s.materials[1].iridescenceTexture = lt::addTexture(s, {{204, lt::kDecoy, lt::kDecoy, lt::kDecoy}});
        s.materials[4].iridescenceThicknessTexture = lt::addTexture(s, {{lt::kDecoy, 255, lt::kDecoy, lt::kDecoy}});
    }
    return s;
}

TEST_F(MaterialLayersTest, IridescenceDeferredAndForward) {
    double change[2];
    for (int blend = 0; blend < 2; ++blend) {
        const char* path = blend ? "forward (BLEND)" : "deferred";
        const scene::Scene film = iridescentSpheres(blend, false);
        scene::Scene bare = film;
        for (scene::Material& m : bare.materials) m.iridescence = 0.0f;
        scene::Scene zero = film;
        for (scene::Material& m : zero.materials) m.iridescenceThicknessMin = m.iridescenceThicknessMax = 0.0f;
        const core::ImageRgba32f a = renderHdr(ctx(), shaders(), film, false);
        const core::ImageRgba32f b = renderHdr(ctx(), shaders(), bare, false);
        const core::ImageRgba32f z = renderHdr(ctx(), shaders(), zero, false);
        const core::ImageRgba32f t = renderHdr(ctx(), shaders(), iridescentSpheres(blend, true), false);
        scene::Scene one = film;  // what unread textures (white placeholders) would give: factor 1
        one.materials[1].iridescence = 1.0f;
        const core::ImageRgba32f o = renderHdr(ctx(), shaders(), one, false);
        change[blend] = relativeChange(a, b);
        const double zeroChange = relativeChange(z, b), textureChange = relativeChange(t, a);
        const double oneChange = relativeChange(o, a);
        std::printf("raster %s: the film changes the frame by %.2f%%; thickness 0 vs none %.5f%%; textures vs "
                    "factors %.5f%% (factor 1 vs 0.8: %.5f%%) of its radiance\n", path, 100.0 * change[blend],
                    100.0 * zeroChange, 100.0 * textureChange, 100.0 * oneChange);
        EXPECT_GT(change[blend], 0.002) << path;  // three small spheres of the frame (measured 0.37% deferred)
        // The layered path's arithmetic differs from the plain BRDF's by rounding only.
        EXPECT_LT(zeroChange, 1e-4) << path;
        // 8-bit texels of exactly the factors' values (the G-buffer keeps 8 bits, as the textures hold).
        EXPECT_LT(textureChange, 1e-4) << path;
        EXPECT_LT(textureChange, 0.1 * oneChange) << path;
    }
    EXPECT_NEAR(change[0], change[1], 0.25 * change[0]) << "deferred and forward shade the film alike";
}

// The clearcoat sphere with vertex tangents around the vertical axis, UVs, and a 1x1 coat normal map of `rgb`.
scene::Scene coatNormalSpheres(bool blend, std::array<uint8_t, 3> rgb, bool withMap) {
    namespace lt = layer_textures;
    scene::Scene s = materialSpheres();
    brushedTangents(s);
    lt::sideUvs(s, lt::kCoatMaterial);
    for (size_t i = 1; i < s.materials.size() && blend; ++i) {  // the spheres; the floor stays opaque, so that
        s.materials[i].alphaMode = scene::AlphaMode::Blend;      // weighted-blended OIT does not mix it in
        s.materials[i].baseColorFactor.a = 1.0f;
    }
    s.materials[lt::kCoatMaterial].clearcoatRoughness = 0.15f;
    if (withMap)
        s.materials[lt::kCoatMaterial].clearcoatNormalTexture = lt::addTexture(s, {{rgb[0], rgb[1], rgb[2], 255}});
    return s;
}

TEST_F(MaterialLayersTest, CoatNormalDeferredAndForward) {
    double change[2];
    for (int blend = 0; blend < 2; ++blend) {
        const char* path = blend ? "forward (BLEND)" : "deferred";
        auto render = [&](const scene::Scene& s) { return renderHdr(ctx(), shaders(), s, false); };
        const core::ImageRgba32f none = render(coatNormalSpheres(blend, {128, 128, 255}, false));
        const core::ImageRgba32f flat = render(coatNormalSpheres(blend, {128, 128, 255}, true));
        const core::ImageRgba32f tilted = render(coatNormalSpheres(blend, {210, 90, 220}, true));
        change[blend] = relativeChange(tilted, none);
        const double flatChange = relativeChange(flat, none);
        std::printf("raster %s: tilted coat normal changes the frame by %.3f%%, a flat map by %.4f%%\n", path,
                    100.0 * change[blend], 100.0 * flatChange);
        EXPECT_GT(change[blend], 0.002) << path;
        EXPECT_LT(flatChange, 1e-3) << path;
    }
    EXPECT_NEAR(change[0], change[1], 0.25 * change[0]) << "deferred and forward shade the coat normal alike";
}

// Brushed gold and plastic (tangents around the vertical axis, UVs): strength 0.8 and `rotation`, or strength 1 with
// a 1x1 anisotropy texture (rg, B 204).
scene::Scene anisotropicSpheres(bool blend, bool textured, std::array<uint8_t, 2> rg, float rotation) {
    namespace lt = layer_textures;
    scene::Scene s = materialSpheres();
    brushedTangents(s);
    for (size_t i = 1; i < s.materials.size() && blend; ++i) {
        s.materials[i].alphaMode = scene::AlphaMode::Blend;
        s.materials[i].baseColorFactor.a = 1.0f;
    }
    for (uint32_t i : {1u, 4u}) {
        lt::sideUvs(s, i);
        scene::Material& m = s.materials[i];
        m.roughness = 0.3f;
        m.anisotropyStrength = 0.8f;
        m.anisotropyRotation = rotation;
        if (textured) {
            m.anisotropyStrength = 1.0f;
            m.anisotropyTexture = lt::addTexture(s, {{rg[0], rg[1], 204, 255}});
        }
    }
    return s;
}

TEST_F(MaterialLayersTest, AnisotropyTextureDeferredAndForward) {
    for (int blend = 0; blend < 2; ++blend) {
        const char* path = blend ? "forward (BLEND)" : "deferred";
        auto render = [&](const scene::Scene& s) { return renderHdr(ctx(), shaders(), s, false); };
        const core::ImageRgba32f factors = render(anisotropicSpheres(blend, false, {0, 0}, 0.0f));
        const core::ImageRgba32f constant = render(anisotropicSpheres(blend, true, {255, 128}, 0.0f));
        const double constantChange = relativeChange(constant, factors);
        if (!blend) {  // no tangent in the G-buffer: only the strength texel matters (not read: strength 1)
            scene::Scene one = anisotropicSpheres(blend, false, {0, 0}, 0.0f);
            for (uint32_t i : {1u, 4u}) one.materials[i].anisotropyStrength = 1.0f;
            const double oneChange = relativeChange(render(one), constant);
            std::printf("raster %s: constant anisotropy texture vs factors %.5f%% (vs strength 1: %.4f%%)\n", path,
                        100.0 * constantChange, 100.0 * oneChange);
            EXPECT_LT(constantChange, 1e-3) << path;
            EXPECT_LT(constantChange, 0.1 * oneChange) << path;
            continue;
        }
        const core::ImageRgba32f rotated = render(anisotropicSpheres(blend, false, {0, 0}, 1.5707963f));
        const core::ImageRgba32f turned = render(anisotropicSpheres(blend, true, {128, 255}, 0.0f));
        const double turnedChange = relativeChange(turned, rotated), rotationChange = relativeChange(rotated, factors);
        std::printf("raster %s: constant anisotropy texture vs factors %.5f%%, 90-degree texture vs rotation pi/2 "
                    "%.5f%% (the rotation changes %.4f%%)\n", path, 100.0 * constantChange, 100.0 * turnedChange,
                    100.0 * rotationChange);
        EXPECT_LT(constantChange, 1e-3) << path;
        EXPECT_LT(turnedChange, 1e-3) << path;
        EXPECT_GT(rotationChange, 10.0 * std::max(constantChange, turnedChange)) << path;
    }
}

}  // namespace
}  // namespace idk::test
