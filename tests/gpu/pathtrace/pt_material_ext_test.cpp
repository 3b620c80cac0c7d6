// pt_material_ext_test.cpp: the material extensions (KHR_materials_specular, _clearcoat, _sheen) and the GGX
// energy compensation in the GPU path tracer against the CPU reference, on scenes/material_spheres.gltf (one
// sphere per extension and a rough gold one) under a point light and a constant environment: at the same seed
// the GPU draws the CPU's samples, so at least 90% of the pixels agree to 1e-3 relative (discrete choices may
// flip on rounding), and the means agree within 1%. The extensions' effect is real: removing them changes the
// CPU image by more than 5% of its mean radiance. KHR_materials_anisotropy the same way, on the spheres given
// azimuthal (brushed) tangents and anisotropic materials: GPU equals CPU, and anisotropy changes the image by more
// than 2% of its mean radiance. KHR_materials_iridescence likewise, with factors on three spheres and its two
// textures (support/layer_textures.hpp) on two: GPU equals CPU, the film changes the image, and an
// iridescenceTexture of constant R renders as the factor R / 255 without it. clearcoatNormalTexture: a tilted coat
// normal on the clearcoat sphere (tangents around the vertical axis): GPU equals CPU, the tilt changes the image,
// and a flat coat normal map (texel 128, 128, 255: xy 1/255 off flat) renders as no map on 98% of the pixels.
// anisotropyTexture: GPU equals CPU; a constant texture (RG 255, 128 = the tangent, B 204) renders as the factors
// (strength x 0.8) and a texture direction of 90 degrees (RG 128, 255) as anisotropyRotation = pi/2 without one,
// both within 0.4% RMSE of the mean (the texel 128 is 1/255 off the exact 0.5).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "gpu/pathtrace/pt_image_util.hpp"
#include "pathtrace/cpu_path_tracer.hpp"
#include "pathtrace/pt_scene.hpp"
#include "scene/gltf_loader.hpp"
#include "support/gpu_fixture.hpp"
#include "support/layer_textures.hpp"
#include "support/same_pixels.hpp"

namespace idk::test {
namespace {

constexpr uint32_t kSize = 64;

class PtMaterialExtTest : public GpuTest {};

scene::Scene materialSpheres() {
    return scene::loadGltf(std::filesystem::path(IDK_SOURCE_DIR) / "scenes/material_spheres.gltf");
}

pathtrace::PtSettings settings() {
    pathtrace::PtSettings s;
    s.spp = 8;
    s.seed = 77;
    s.maxDepth = 4;
    s.rouletteDepth = 3;
    return s;
}

TEST_F(PtMaterialExtTest, GpuGivesTheCpuSamples) {
    const scene::Scene sc = materialSpheres();
    ASSERT_EQ(sc.materials.size(), 5u);
    EXPECT_NEAR(sc.materials[1].specular, 0.3f, 1e-6f);
    EXPECT_NEAR(sc.materials[2].clearcoat, 1.0f, 1e-6f);
    EXPECT_NEAR(sc.materials[3].sheenColor.y, 0.5f, 1e-6f);
    const glm::vec3 environment(0.6f, 0.7f, 0.8f);
    const pathtrace::PathTraceScene pts = pathtrace::buildPathTraceScene(sc, nullptr, 1.0f, environment);
    const scene::CameraView camera = scene::defaultCamera(sc);
    const core::ImageRgba32f cpu = pathtrace::renderReference(pts, camera, kSize, kSize, settings());

    expectGpuDrawsTheCpuSamples(ctx(), shaders(), sc, pts, camera, kSize, settings(), cpu, "material spheres");
    const double meanCpu = meanRadiance(cpu);

    // Without the extensions (core glTF materials) the image is measurably different.
    scene::Scene plain = sc;
    for (scene::Material& m : plain.materials) {
        m.specular = 1.0f;
        m.specularColor = glm::vec3(1.0f);
        m.clearcoat = 0.0f;
        m.sheenColor = glm::vec3(0.0f);
    }
    const pathtrace::PathTraceScene plainPts = pathtrace::buildPathTraceScene(plain, nullptr, 1.0f, environment);
    const core::ImageRgba32f without = pathtrace::renderReference(plainPts, camera, kSize, kSize, settings());
    const double change = rmse(without, cpu);
    std::printf("material spheres: RMSE with vs without the extensions %.5f (%.1f%% of the mean)\n", change,
                100.0 * change / meanCpu);
    EXPECT_GT(change, 0.05 * meanCpu);
}


TEST_F(PtMaterialExtTest, AnisotropyGpuGivesTheCpuSamples) {
    scene::Scene sc = materialSpheres();
    // Brushed spheres: tangents around the vertical axis (the file has no UVs, so no generated tangents), one
    // rotated by the material's anisotropyRotation; the floor keeps none (the BSDF's own basis).
    for (scene::Mesh& mesh : sc.meshes) {
        for (scene::Primitive& prim : mesh.primitives) {
            if (prim.material == 0u) continue;
            prim.tangents.resize(prim.normals.size());
            for (size_t v = 0; v < prim.normals.size(); ++v) {
                const glm::vec3 t = glm::cross(glm::vec3(0.0f, 1.0f, 0.0f), prim.normals[v]);
                prim.tangents[v] = glm::dot(t, t) > 1e-8f ? glm::vec4(glm::normalize(t), 1.0f)
                                                          : glm::vec4(1.0f, 0.0f, 0.0f, 1.0f);
            }
        }
    }
    sc.materials[4].anisotropyStrength = 0.8f;  // rough gold: brushed metal
    sc.materials[1].anisotropyStrength = 0.6f;  // specular plastic, turned by 60 degrees
    sc.materials[1].anisotropyRotation = 1.0472f;
    sc.materials[2].anisotropyStrength = 1.0f;  // under a clearcoat
    sc.materials[0].anisotropyStrength = 0.5f;  // floor: no tangents, the BSDF's basis
    const glm::vec3 environment(0.6f, 0.7f, 0.8f);
    const pathtrace::PathTraceScene pts = pathtrace::buildPathTraceScene(sc, nullptr, 1.0f, environment);
    const scene::CameraView camera = scene::defaultCamera(sc);
    const core::ImageRgba32f cpu = pathtrace::renderReference(pts, camera, kSize, kSize, settings());
    expectGpuDrawsTheCpuSamples(ctx(), shaders(), sc, pts, camera, kSize, settings(), cpu, "anisotropic spheres");
    const double meanCpu = meanRadiance(cpu);

    scene::Scene isotropic = sc;
    for (scene::Material& m : isotropic.materials) m.anisotropyStrength = 0.0f;
    const pathtrace::PathTraceScene isoPts = pathtrace::buildPathTraceScene(isotropic, nullptr, 1.0f, environment);
    const core::ImageRgba32f without = pathtrace::renderReference(isoPts, camera, kSize, kSize, settings());
    const double change = rmse(without, cpu);
    std::printf("anisotropic spheres: RMSE with vs without anisotropy %.5f (%.1f%% of the mean)\n", change,
                100.0 * change / meanCpu);
    EXPECT_GT(change, 0.02 * meanCpu);  // measured 4.0% (the spheres cover a small part of the frame)
}

TEST_F(PtMaterialExtTest, IridescenceGpuGivesTheCpuSamples) {
    namespace lt = layer_textures;
    scene::Scene sc = materialSpheres();
    lt::sideUvs(sc, 1);
    lt::sideUvs(sc, 4);
    scene::Material& plastic = sc.materials[1];  // factor 0.8 from a constant texture (R 204, decoys elsewhere)
    plastic.iridescence = 1.0f;
    plastic.iridescenceIor = 1.3f;
    plastic.iridescenceThicknessMax = 380.0f;
    plastic.iridescenceTexture = lt::addTexture(sc, {{204, lt::kDecoy, lt::kDecoy, lt::kDecoy}});
    scene::Material& gold = sc.materials[4];  // thickness 150 nm on the -x half, 600 nm on the +x half
    gold.iridescence = 1.0f;
    gold.iridescenceIor = 1.8f;
    gold.iridescenceThicknessMin = 150.0f;
    gold.iridescenceThicknessMax = 600.0f;
    gold.iridescenceThicknessTexture =
        lt::addTexture(sc, {{lt::kDecoy, 0, lt::kDecoy, lt::kDecoy}, {lt::kDecoy, 255, lt::kDecoy, lt::kDecoy}});
    scene::Material& coat = sc.materials[2];  // under the clearcoat
    coat.iridescence = 0.7f;
    coat.iridescenceThicknessMax = 250.0f;
    const glm::vec3 environment(0.6f, 0.7f, 0.8f);
    const pathtrace::PathTraceScene pts = pathtrace::buildPathTraceScene(sc, nullptr, 1.0f, environment);
    const scene::CameraView camera = scene::defaultCamera(sc);
    const core::ImageRgba32f cpu = pathtrace::renderReference(pts, camera, kSize, kSize, settings());
    expectGpuDrawsTheCpuSamples(ctx(), shaders(), sc, pts, camera, kSize, settings(), cpu, "iridescent spheres");
    const double meanCpu = meanRadiance(cpu);

    scene::Scene bare = sc;
    for (scene::Material& m : bare.materials) m.iridescence = 0.0f;
    const pathtrace::PathTraceScene barePts = pathtrace::buildPathTraceScene(bare, nullptr, 1.0f, environment);
    const double change = rmse(pathtrace::renderReference(barePts, camera, kSize, kSize, settings()), cpu);
    std::printf("iridescent spheres: RMSE with vs without the film %.5f (%.1f%% of the mean)\n", change,
                100.0 * change / meanCpu);
    EXPECT_GT(change, 0.005 * meanCpu);  // measured 1.1% (three small spheres)

    // The texture's R channel scales the factor: the same scene with the factor 204 / 255 and no texture renders
    // the same CPU image (nearest 1x1 texel: the same numbers up to the float product's rounding).
    scene::Scene factor = sc;
    factor.materials[1].iridescence = 204.0f / 255.0f;
    factor.materials[1].iridescenceTexture.reset();
    const pathtrace::PathTraceScene factorPts = pathtrace::buildPathTraceScene(factor, nullptr, 1.0f, environment);
    const core::ImageRgba32f byFactor = pathtrace::renderReference(factorPts, camera, kSize, kSize, settings());
    const double sameFactor = samePixelFraction(byFactor, cpu);
    // ... and not as the factor 1 (what an unread texture's white placeholder would give).
    factor.materials[1].iridescence = 1.0f;
    const core::ImageRgba32f byOne = pathtrace::renderReference(
        pathtrace::buildPathTraceScene(factor, nullptr, 1.0f, environment), camera, kSize, kSize, settings());
    const double factorErr = rmse(byFactor, cpu), oneErr = rmse(byOne, cpu);
    std::printf("iridescent spheres: texture R 204 vs factor 0.8: %.2f%% of the pixels equal, RMSE %.6f (vs factor "
                "1: %.6f)\n", 100.0 * sameFactor, factorErr, oneErr);
    EXPECT_GT(sameFactor, 0.99);
    EXPECT_LT(factorErr, 0.1 * oneErr);
}

// The clearcoat sphere with tangents around the vertical axis and UVs, and a 1x1 coat normal map of texel `rgb`.
scene::Scene coatNormalSpheres(std::array<uint8_t, 3> rgb, bool withMap) {
    namespace lt = layer_textures;
    scene::Scene sc = materialSpheres();
    lt::sideUvs(sc, lt::kCoatMaterial);
    for (scene::Mesh& mesh : sc.meshes)
        for (scene::Primitive& prim : mesh.primitives) {
            if (prim.material != lt::kCoatMaterial) continue;
            prim.tangents.resize(prim.normals.size());
            for (size_t v = 0; v < prim.normals.size(); ++v) {
                const glm::vec3 t = glm::cross(glm::vec3(0.0f, 1.0f, 0.0f), prim.normals[v]);
                prim.tangents[v] = glm::dot(t, t) > 1e-8f ? glm::vec4(glm::normalize(t), 1.0f)
                                                          : glm::vec4(1.0f, 0.0f, 0.0f, 1.0f);
            }
        }
    sc.materials[lt::kCoatMaterial].clearcoatRoughness = 0.15f;
    if (withMap)
        sc.materials[lt::kCoatMaterial].clearcoatNormalTexture = lt::addTexture(sc, {{rgb[0], rgb[1], rgb[2], 255}});
    return sc;
}

TEST_F(PtMaterialExtTest, CoatNormalGpuGivesTheCpuSamples) {
    const scene::Scene sc = coatNormalSpheres({210, 90, 220}, true);
    const glm::vec3 environment(0.6f, 0.7f, 0.8f);
    const pathtrace::PathTraceScene pts = pathtrace::buildPathTraceScene(sc, nullptr, 1.0f, environment);
    const scene::CameraView camera = scene::defaultCamera(sc);
    const core::ImageRgba32f cpu = pathtrace::renderReference(pts, camera, kSize, kSize, settings());
    expectGpuDrawsTheCpuSamples(ctx(), shaders(), sc, pts, camera, kSize, settings(), cpu, "coat normal");

    auto cpuImage = [&](const scene::Scene& s) {
        return pathtrace::renderReference(pathtrace::buildPathTraceScene(s, nullptr, 1.0f, environment), camera,
                                          kSize, kSize, settings());
    };
    const core::ImageRgba32f none = cpuImage(coatNormalSpheres({128, 128, 255}, false));
    const core::ImageRgba32f flat = cpuImage(coatNormalSpheres({128, 128, 255}, true));
    // Same seed: the flat map (1/255 off flat) perturbs few paths enough to flip a discrete choice, the tilt most of
    // those that meet the coat.
    const double tiltedSame = samePixelFraction(cpu, none), flatSame = samePixelFraction(flat, none);
    std::printf("coat normal: pixels equal to the map-less image: tilted %.2f%%, flat map %.2f%%\n",
                100.0 * tiltedSame, 100.0 * flatSame);
    EXPECT_GT(flatSame, 0.98);
    EXPECT_LT(tiltedSame, flatSame - 0.02);
}

// Brushed spheres (tangents around the vertical axis, UVs) with anisotropic gold and plastic; `textured` moves the
// direction and a strength factor into 1x1 anisotropy textures (texel rg + B 204 for a strength factor x 0.8).
scene::Scene brushedSpheres(bool textured, std::array<uint8_t, 2> rg, float rotation) {
    namespace lt = layer_textures;
    scene::Scene sc = materialSpheres();
    for (uint32_t m : {1u, 4u}) lt::sideUvs(sc, m);
    for (scene::Mesh& mesh : sc.meshes)
        for (scene::Primitive& prim : mesh.primitives) {
            if (prim.material == 0u) continue;
            prim.tangents.resize(prim.normals.size());
            for (size_t v = 0; v < prim.normals.size(); ++v) {
                const glm::vec3 t = glm::cross(glm::vec3(0.0f, 1.0f, 0.0f), prim.normals[v]);
                prim.tangents[v] = glm::dot(t, t) > 1e-8f ? glm::vec4(glm::normalize(t), 1.0f)
                                                          : glm::vec4(1.0f, 0.0f, 0.0f, 1.0f);
            }
        }
    for (uint32_t i : {1u, 4u}) {
        scene::Material& m = sc.materials[i];
        m.anisotropyStrength = 0.8f;
        m.anisotropyRotation = rotation;
        if (textured) {
            m.anisotropyStrength = 1.0f;
            m.anisotropyTexture = lt::addTexture(sc, {{rg[0], rg[1], 204, 255}});
        }
    }
    return sc;
}

TEST_F(PtMaterialExtTest, AnisotropyTextureGpuGivesTheCpuSamples) {
    const scene::Scene sc = brushedSpheres(true, {200, 60}, 0.3f);
    const glm::vec3 environment(0.6f, 0.7f, 0.8f);
    const pathtrace::PathTraceScene pts = pathtrace::buildPathTraceScene(sc, nullptr, 1.0f, environment);
    const scene::CameraView camera = scene::defaultCamera(sc);
    const core::ImageRgba32f cpu = pathtrace::renderReference(pts, camera, kSize, kSize, settings());
    expectGpuDrawsTheCpuSamples(ctx(), shaders(), sc, pts, camera, kSize, settings(), cpu, "anisotropy texture");
    const double meanCpu = meanRadiance(cpu);

    auto cpuImage = [&](const scene::Scene& s) {
        return pathtrace::renderReference(pathtrace::buildPathTraceScene(s, nullptr, 1.0f, environment), camera,
                                          kSize, kSize, settings());
    };
    const core::ImageRgba32f factors = cpuImage(brushedSpheres(false, {0, 0}, 0.0f));
    const core::ImageRgba32f constant = cpuImage(brushedSpheres(true, {255, 128}, 0.0f));
    const core::ImageRgba32f rotated = cpuImage(brushedSpheres(false, {0, 0}, 1.5707963f));
    const core::ImageRgba32f turned = cpuImage(brushedSpheres(true, {128, 255}, 0.0f));
    const double constantErr = rmse(constant, factors), turnedErr = rmse(turned, rotated),
                 rotationEffect = rmse(rotated, factors);
    std::printf("anisotropy texture: constant texture vs factors RMSE %.6f, 90-degree texture vs rotation pi/2 %.6f "
                "(rotating changes the image by %.5f; mean %.5f)\n", constantErr, turnedErr, rotationEffect,
                meanCpu);
    EXPECT_LT(constantErr, 0.004 * meanCpu);  // measured 0.26% and 0.25% of the mean
    EXPECT_LT(turnedErr, 0.004 * meanCpu);
    EXPECT_GT(rotationEffect, 10.0 * std::max(constantErr, turnedErr));
}

}  // namespace
}  // namespace idk::test
