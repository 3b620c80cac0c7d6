// scene_data_test.cpp: what buildPathTraceScene prepares: emissive triangles and punctual lights in the light list
// with per-instance offsets (lightIndex = firstLight + triangle id), front normals that follow mirrored instances,
// power-proportional light selection; textures sampled with wrap modes, KHR_texture_transform, the second UV set,
// vertex colours and alpha MASK; the real default HDR environment's sampling tables.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include <glm/gtc/matrix_transform.hpp>

#include "pathtrace/alias_table.hpp"
#include "pathtrace/pt_material.hpp"
#include "pathtrace/pt_scene.hpp"
#include "pt_test_scenes.hpp"
#include "shared/pt_sampling.h"

namespace idk::test {
namespace {

using namespace idk::gpu;

TEST(PtSceneData, LightListOffsetsAndMirroring) {
    scene::Scene s;
    addObject(s, quad({-1, 0, 1}, {1, 0, 1}, {1, 0, -1}, {-1, 0, -1}), diffuse(glm::vec3(0.5f)));
    scene::Material lamp = diffuse(glm::vec3(0.0f));
    lamp.emissive = glm::vec3(2.0f);
    const scene::Primitive panel = quad({-0.5f, 2, -0.5f}, {-0.5f, 2, 0.5f}, {0.5f, 2, 0.5f}, {0.5f, 2, -0.5f});
    addObject(s, panel, lamp);  // faces up (+y)
    // The same panel mirrored in x (det < 0) and twice as large: still faces up, 4x the power.
    addObject(s, panel, lamp, glm::scale(glm::mat4(1.0f), glm::vec3(-2.0f, 1.0f, 2.0f)));
    scene::Light point;
    point.position = glm::vec3(0.0f, 1.0f, 0.0f);
    point.intensity = 3.0f;
    s.lights.push_back(point);
    const pathtrace::PathTraceScene pts = pathtrace::buildPathTraceScene(s, nullptr, 1.0f);

    ASSERT_EQ(pts.lights.size(), 5u);  // 2 + 2 triangles, 1 point light
    EXPECT_EQ(pts.instanceLights[0].firstLight, kPtNoLight);
    EXPECT_EQ(pts.instanceLights[1].firstLight, 0u);
    EXPECT_EQ(pts.instanceLights[2].firstLight, 2u);
    EXPECT_EQ(pts.lights[4].type, kPtLightPoint);
    EXPECT_EQ(pts.environmentDesc.lightCount, 5u);
    EXPECT_EQ(pts.environmentDesc.selectProbability, 0.0f) << "black environment";
    for (uint32_t inst : {1u, 2u}) {
        for (uint32_t tri = 0; tri < 2; ++tri) {
            const GpuPtLight& l = pts.lights[pts.instanceLights[inst].firstLight + tri];
            EXPECT_EQ(l.instance, inst);
            EXPECT_EQ(l.triangle, tri);
            EXPECT_EQ((l.flags & kPtLightFlipped) != 0u, inst == 2u);
            float area;
            const glm::vec3 n = ptTriangleLightNormal(l, area);
            const pathtrace::PtHitPoint hit = pathtrace::hitPoint(pts, inst, tri, 0.3f, 0.3f);
            EXPECT_NEAR(glm::dot(n, hit.geometricNormal), 1.0f, 1e-5f) << "light and hit agree on the front face";
            EXPECT_NEAR(n.y, 1.0f, 1e-5f) << "both panels face up (mirroring keeps the physical side)";
            EXPECT_NEAR(area, inst == 1 ? 0.5f : 2.0f, 1e-5f);
        }
    }
    // Power: pi * area * luminance(2) per triangle; the mirrored panel's triangles carry 4x.
    const double p1 = pts.lightAlias[0].probability, p2 = pts.lightAlias[2].probability;
    EXPECT_NEAR(p2 / p1, 4.0, 1e-4);
    const std::vector<double> exact = pathtrace::aliasSelectionProbabilities(pts.lightAlias);
    for (size_t i = 0; i < exact.size(); ++i) EXPECT_NEAR(exact[i], pts.lightAlias[i].probability, 1e-6);
}

// A 2x2 RGBA PNG: (255,0,0,255) (0,255,0,255) / (0,0,255,255) (255,255,255,0) as texels (0,0) (1,0) / (0,1) (1,1).
std::filesystem::path writeTestPng() {
    core::ImageRgba32f img;
    img.width = img.height = 2;
    img.pixels = {1, 0, 0, 1, 0, 1, 0, 1, 0, 0, 1, 1, 1, 1, 1, 0};
    const auto path = std::filesystem::temp_directory_path() / "idk_pt_scene_data_test.png";
    core::writeImage(path, img);
    return path;
}

TEST(PtSceneData, TexturedMaterialAtAHit) {
    scene::Scene s;
    scene::Image image;
    image.path = writeTestPng();
    s.images.push_back(image);
    scene::Texture tex;
    tex.image = 0;
    tex.sampler.magFilter = 9728;  // NEAREST: exact texels
    tex.sampler.wrapS = 33071;     // CLAMP
    tex.sampler.wrapT = 10497;     // REPEAT
    s.textures.push_back(tex);
    scene::Material m = diffuse(glm::vec3(1.0f));
    m.baseColorTexture = scene::TextureRef{};
    m.baseColorTexture->texCoord = 1;
    m.baseColorTexture->offset = glm::vec2(0.5f, 0.0f);  // KHR_texture_transform: shift half a texture in u
    m.alphaMode = scene::AlphaMode::Mask;
    scene::Primitive p = quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0});
    p.uv0.assign(4, glm::vec2(0.0f));
    p.uv1 = {{0.0f, 0.0f}, {0.5f, 0.0f}, {0.5f, 0.5f}, {0.0f, 0.5f}};
    p.colors.assign(4, glm::vec4(0.5f, 1.0f, 1.0f, 1.0f));
    addObject(s, p, m);
    const pathtrace::PathTraceScene pts = pathtrace::buildPathTraceScene(s, nullptr, 1.0f);
    ASSERT_TRUE(pts.warnings.empty()) << pts.warnings.front();
    ASSERT_EQ(pts.textures.size(), 1u);
    ASSERT_EQ(pts.textures[0].width, 2u);

    // Triangle 0 = (v0, v1, v2); barycentrics (u of v1, v = of v2) give uv1 = 0.5 u + 0.5 v, 0.5 v.
    // uv1 (0.2, 0.1) + offset (0.5, 0) -> (0.7, 0.1): texel (1, 0) green, times the vertex colour's red 0.5.
    const glm::vec3 wo(0.0f, 0.0f, 1.0f);
    pathtrace::PtHitPoint hit = pathtrace::hitPoint(pts, 0, 0, 0.2f, 0.2f);
    EXPECT_NEAR(hit.uv1.x, 0.2f, 1e-6f);
    EXPECT_NEAR(hit.uv1.y, 0.1f, 1e-6f);
    pathtrace::PtMaterialHit mh = pathtrace::evaluateMaterial(pts, hit, wo);
    EXPECT_NEAR(mh.surface.baseColor.x, 0.0f, 1e-6f);
    EXPECT_NEAR(mh.surface.baseColor.y, 1.0f, 1e-6f);
    EXPECT_FALSE(mh.passThrough);
    // uv1 (0.7, 0.6) -> u 1.2 clamps to texel 1; v 0.6 -> texel 1: (255,255,255,0), alpha 0 -> MASK passes through.
    hit = pathtrace::hitPoint(pts, 0, 0, 0.2f, 1.2f);
    mh = pathtrace::evaluateMaterial(pts, hit, wo);
    EXPECT_NEAR(mh.surface.baseColor.x, 0.5f, 1e-6f);
    EXPECT_TRUE(mh.passThrough);
    // v = 1.1 repeats to 0.1 (row 0); u -0.3 + 0.5 = 0.2 -> texel 0: red x 0.5.
    hit.uv1 = glm::vec2(-0.3f, 1.1f);
    mh = pathtrace::evaluateMaterial(pts, hit, wo);
    EXPECT_NEAR(mh.surface.baseColor.x, 0.5f, 1e-6f);
    EXPECT_NEAR(mh.surface.baseColor.y, 0.0f, 1e-6f);
    std::filesystem::remove(writeTestPng());
}

TEST(PtSceneData, DefaultHdrEnvironmentTables) {
    const std::filesystem::path file =
        std::filesystem::path(IDK_SHARED_DIR) / "environments" / "snow_field_puresky_1k.hdr";
    if (!std::filesystem::exists(file)) GTEST_SKIP() << file << " is missing";
    const core::ImageRgba32f hdr = core::readImage(file);
    const pathtrace::EnvironmentMap env = pathtrace::buildEnvironmentMap(hdr, 1.5f);
    ASSERT_EQ(env.aliasTable.size(), size_t(hdr.width) * hdr.height);
    // Importance sampling estimates the integral of luminance * solid angle with small error.
    double exact = 0.0;
    for (uint32_t y = 0; y < env.height; ++y) {
        const double sa = 2.0 * M_PI / env.width * (std::cos(M_PI * y / env.height) - std::cos(M_PI * (y + 1) / env.height));
        for (uint32_t x = 0; x < env.width; ++x) exact += double(ptLuminance(env.radiance[y * env.width + x])) * sa;
    }
    PtRng rng = ptRngInit(3, 1, 4);
    double sum = 0.0;
    const int n = 100000;
    for (int i = 0; i < n; ++i) {
        const uint slot = ptAliasSlot(ptRandom(rng), uint(env.aliasTable.size()));
        const uint texel = ptAliasResolve(env.aliasTable[slot], slot, ptRandom(rng));
        glm::vec3 dir;
        const float pdf = ptSampleEnvironment(texel, env.aliasTable[texel].probability, env.width, env.height,
                                              glm::vec2(ptRandom(rng), ptRandom(rng)), dir);
        if (pdf > 0.0f) sum += double(ptLuminance(env.radiance[texel])) / double(pdf);
    }
    EXPECT_NEAR(sum / n, exact, 0.01 * exact);
    EXPECT_NEAR(env.meanLuminance * 4.0 * M_PI, exact, 1e-3 * exact);
}

}  // namespace
}  // namespace idk::test
