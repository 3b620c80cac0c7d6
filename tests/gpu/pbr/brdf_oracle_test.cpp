// brdf_oracle_test.cpp: the deferred renderer's lighting (deferred_lighting pass, IDKEngine's DeferredLighting)
// against a C++ evaluation of the same glTF BRDF at pixel centres, on scenes of flat quads built in code.
#include <gtest/gtest.h>
// Known metallic/roughness/base colour, no ambient (environment intensity 0), linear HDR output. Interior pixels
// only (more than 1.5 pixel footprints from a quad edge); background pixels must be exactly black with alpha 0.
// Tolerance: |gpu - cpu| <= 1% of cpu + 2e-4 per channel for every interior pixel (observed on lavapipe: at most
// 0.3% above radiance 0.01). Error budget: llvmpipe's polynomial sRGB decode of the albedo target (~0.3%), RGBA16F
// output (0.05%), float32 depth/position reconstruction; the G-buffer's 8-bit storage itself is reproduced by the
// oracle (sRGB-exact base colours, roughness multiples of 0.2, normal (0, 0, 1) exact in octahedral form).

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <limits>

#include "core/image_file.hpp"
#include "render/renderer.hpp"
#include "support/gpu_fixture.hpp"
#include "support/lambert_oracle.hpp"
#include "support/pbr_oracle.hpp"
#include "support/quad_scene.hpp"

namespace idk::test {
namespace {

constexpr uint32_t kWidth = 256, kHeight = 128;

float srgbCode(int code) { return core::srgbToLinear(float(code) / 255.0f); }

scene::CameraView frontCamera() {
    scene::CameraView c;
    c.position = glm::vec3(0.0f, 0.0f, 3.0f);
    c.forward = glm::vec3(0.0f, 0.0f, -1.0f);
    c.up = glm::vec3(0.0f, 1.0f, 0.0f);
    c.znear = 0.1f;
    c.zfar = 100.0f;
    return c;
}

struct OracleStats {
    uint32_t interior = 0, background = 0, failures = 0;
    double maxRelative = 0.0;
    std::string firstFailure;
};

// Renders `scene` and compares every classified pixel with the oracle. `quads` must match the scene's meshes.
OracleStats renderAndCompare(vk::Context& ctx, vk::ShaderLibrary& shaders, const scene::Scene& scene,
                             const std::vector<QuadSpec>& quads, const std::string& name) {
    render::RenderSettings settings;
    settings.output = render::OutputKind::Hdr;
    settings.environment = std::filesystem::path();  // constant
    settings.environmentIntensity = 0.0f;            // no ambient: direct light and emission only
    render::Renderer renderer(ctx, shaders, settings);
    renderer.setScene(scene);
    scene::CameraView camera = frontCamera();
    render::FrameResult frame = renderer.renderOffscreen(camera, kWidth, kHeight);
    std::vector<gpu::GpuLight> lights;
    for (const scene::Light& l : scene.lights) {
        gpu::GpuLight g{};
        g.position = l.position;
        g.type = l.type == scene::LightType::Directional ? gpu::kLightDirectional
                 : l.type == scene::LightType::Spot      ? gpu::kLightSpot
                                                         : gpu::kLightPoint;
        g.direction = glm::normalize(l.direction);
        g.range = l.range;
        g.intensity = l.color * l.intensity;
        double cosOuter = std::cos(l.outerConeAngle), cosInner = std::cos(l.innerConeAngle);
        g.spotScale = float(1.0 / std::max(0.001, cosInner - cosOuter));
        g.spotOffset = float(-cosOuter) * g.spotScale;
        lights.push_back(g);
    }

    glm::dmat4 inv =
        glm::inverse(glm::dmat4(scene::projectionMatrix(camera, float(kWidth) / kHeight) * scene::viewMatrix(camera)));
    core::ImageRgba32f expected{kWidth, kHeight, std::vector<float>(size_t(kWidth) * kHeight * 4, 0.0f)};
    OracleStats stats;
    const double footprint =
        2.0 * 3.0 * std::tan(scene::kDefaultYfov / 2.0) / kHeight;  // world units per pixel at z = 0
    const double margin = 1.5 * footprint;
    for (uint32_t py = 0; py < kHeight; ++py) {
        for (uint32_t px = 0; px < kWidth; ++px) {
            double x = (px + 0.5) / kWidth * 2.0 - 1.0, y = (py + 0.5) / kHeight * 2.0 - 1.0;
            glm::dvec4 a = inv * glm::dvec4(x, y, 0.0, 1.0), b = inv * glm::dvec4(x, y, 0.5, 1.0);
            glm::dvec3 origin = glm::dvec3(a) / a.w, dir = glm::normalize(glm::dvec3(b) / b.w - origin);
            glm::dvec3 p = origin + dir * (-origin.z / dir.z);
            int inside = -1;
            bool nearEdge = false;
            for (size_t i = 0; i < quads.size(); ++i) {
                double dx = std::abs(p.x - quads[i].centre.x), dy = std::abs(p.y - quads[i].centre.y);
                double h = quads[i].halfSize;
                if (dx < h - margin && dy < h - margin)
                    inside = int(i);
                else if (dx < h + margin && dy < h + margin)
                    nearEdge = true;
            }
            const float* got = &frame.image.pixels[(size_t(py) * kWidth + px) * 4];
            float* want = &expected.pixels[(size_t(py) * kWidth + px) * 4];
            if (nearEdge) continue;
            bool visible =
                inside >= 0 && (quads[size_t(inside)].basis[2][2] > 0.0f || quads[size_t(inside)].doubleSided);
            if (!visible) {
                ++stats.background;
                if (got[0] != 0.0f || got[1] != 0.0f || got[2] != 0.0f || got[3] != 0.0f) {
                    if (stats.failures++ == 0)
                        stats.firstFailure =
                            "background pixel " + std::to_string(px) + "," + std::to_string(py) + " not black";
                }
                continue;
            }
            const QuadSpec& q = quads[size_t(inside)];
            glm::dvec3 base(quantizeSrgb8(q.baseColor.r), quantizeSrgb8(q.baseColor.g), quantizeSrgb8(q.baseColor.b));
            glm::dvec3 radiance = glm::dvec3(q.emissive);
            for (const gpu::GpuLight& light : lights) {
                glm::dvec3 l;
                glm::dvec3 incident = lightIncidence(light, p, l);
                radiance += brdfCosine(base, quantizeUnorm8(q.metallic), quantizeUnorm8(q.roughness),
                                       glm::dvec3(0, 0, 1), -dir, l) *
                            incident;
            }
            ++stats.interior;
            for (int c = 0; c < 3; ++c) {
                want[c] = float(radiance[c]);
                double err = std::abs(double(got[c]) - radiance[c]);
                if (radiance[c] > 1e-2) stats.maxRelative = std::max(stats.maxRelative, err / radiance[c]);
                if (!(err <= 0.01 * radiance[c] + 2e-4)) {
                    if (stats.failures++ == 0)
                        stats.firstFailure = "pixel " + std::to_string(px) + "," + std::to_string(py) + " channel " +
                                             std::to_string(c) + ": gpu " + std::to_string(got[c]) + ", cpu " +
                                             std::to_string(radiance[c]);
                }
            }
            want[3] = 1.0f;
            if (got[3] != 1.0f && stats.failures++ == 0) stats.firstFailure = "geometry alpha is not 1";
        }
    }
    if (stats.failures) writeDiffImage(std::string(IDK_BINARY_DIR) + "/" + name + "_diff.exr", frame.image, expected);
    return stats;
}

class BrdfOracleTest : public GpuTest {};

// (metallic, roughness) sweep under one point light.
TEST_F(BrdfOracleTest, PointLightOnMetallicRoughnessGridMatchesCpuBrdf) {
    std::vector<QuadSpec> quads;
    const glm::vec3 colors[2] = {{srgbCode(200), srgbCode(150), srgbCode(100)},
                                 {srgbCode(230), srgbCode(180), srgbCode(60)}};
    for (int row = 0; row < 2; ++row)
        for (int col = 0; col < 5; ++col) {
            QuadSpec q;
            q.centre = glm::vec2(-1.2f + 0.6f * col, 0.3f - 0.6f * row);
            q.baseColor = colors[row];
            q.metallic = float(row);
            q.roughness = 0.2f * float(col + 1);
            quads.push_back(q);
        }
    scene::Scene scene = makeQuadScene(quads);
    scene::Light light;
    light.type = scene::LightType::Point;
    light.position = glm::vec3(0.2f, 0.4f, 1.5f);
    light.intensity = 3.0f;
    scene.lights.push_back(light);

    OracleStats s = renderAndCompare(ctx(), shaders(), scene, quads, "brdf_point");
    EXPECT_GT(s.interior, 4000u);
    EXPECT_GT(s.background, 10000u);
    EXPECT_EQ(s.failures, 0u) << s.firstFailure << " (max relative error " << s.maxRelative << ")";
}

// Spot (cone falloff), directional, and a point light with a finite range; one emissive quad.
TEST_F(BrdfOracleTest, SpotDirectionalAndRangedPointLightsMatchCpuBrdf) {
    std::vector<QuadSpec> quads;
    for (int col = 0; col < 4; ++col) {
        QuadSpec q;
        q.centre = glm::vec2(-1.5f + 1.0f * col, 0.0f);
        q.halfSize = 0.45f;
        q.baseColor = glm::vec3(srgbCode(210), srgbCode(190), srgbCode(170));
        q.metallic = col == 3 ? 1.0f : 0.0f;
        q.roughness = col == 2 ? 0.2f : 0.6f;
        if (col == 1) q.emissive = glm::vec3(0.25f, 0.1f, 0.0f);
        quads.push_back(q);
    }
    scene::Scene scene = makeQuadScene(quads);
    scene::Light spot;
    spot.type = scene::LightType::Spot;
    spot.position = glm::vec3(-1.0f, 0.1f, 1.0f);
    spot.direction = glm::normalize(glm::vec3(-0.2f, 0.0f, -1.0f));
    spot.innerConeAngle = 0.15f;
    spot.outerConeAngle = 0.45f;
    spot.intensity = 4.0f;
    spot.color = glm::vec3(1.0f, 0.9f, 0.8f);
    scene::Light sun;
    sun.type = scene::LightType::Directional;
    sun.direction = glm::normalize(glm::vec3(0.3f, -0.2f, -1.0f));
    sun.intensity = 0.7f;
    scene::Light ranged;
    ranged.type = scene::LightType::Point;
    ranged.position = glm::vec3(1.2f, 0.2f, 0.8f);
    ranged.range = 1.6f;
    ranged.intensity = 2.0f;
    scene.lights = {spot, sun, ranged};

    OracleStats s = renderAndCompare(ctx(), shaders(), scene, quads, "brdf_lights");
    EXPECT_GT(s.interior, 6000u);
    EXPECT_EQ(s.failures, 0u) << s.firstFailure << " (max relative error " << s.maxRelative << ")";
}

// Facing rules: a single-sided quad turned away is rejected, a double-sided one is shaded with its normal
// flipped towards the viewer, and a mirrored instance (negative determinant) stays visible and correctly lit.
TEST_F(BrdfOracleTest, BackFacesMirrorsAndDoubleSidedMatchCpuBrdf) {
    const glm::mat3 turned = glm::mat3(glm::rotate(glm::mat4(1.0f), 3.14159265f, glm::vec3(0, 1, 0)));
    const glm::mat3 mirrored = glm::mat3(glm::scale(glm::mat4(1.0f), glm::vec3(-1.0f, 1.0f, 1.0f)));
    std::vector<QuadSpec> quads(3);
    for (int i = 0; i < 3; ++i) {
        quads[i].centre = glm::vec2(-1.2f + 1.2f * i, 0.0f);
        quads[i].halfSize = 0.45f;
        quads[i].baseColor = glm::vec3(srgbCode(180));
        quads[i].roughness = 0.4f;
    }
    quads[0].basis = turned;  // single-sided, back facing: culled
    quads[1].basis = turned;  // double-sided, back facing: visible, normal flipped
    quads[1].doubleSided = true;
    quads[2].basis = mirrored;  // front facing through a mirror
    scene::Scene scene = makeQuadScene(quads);
    scene::Light light;
    light.position = glm::vec3(0.0f, 0.5f, 1.5f);
    light.intensity = 3.0f;
    scene.lights.push_back(light);

    OracleStats s = renderAndCompare(ctx(), shaders(), scene, quads, "brdf_facing");
    EXPECT_GT(s.interior, 3000u);  // the culled quad counts as background
    EXPECT_EQ(s.failures, 0u) << s.firstFailure << " (max relative error " << s.maxRelative << ")";
}

}  // namespace
}  // namespace idk::test
