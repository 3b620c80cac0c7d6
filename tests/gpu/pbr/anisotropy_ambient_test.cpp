// anisotropy_ambient_test.cpp: the rasterizer's split-sum for KHR_materials_anisotropy (include/material_layers.glsl
// ambientSpecularAlbedo) against a C++ evaluation of the same formula at pixel centres: a coloured anisotropic metal
// quad, drawn by the forward (BLEND) pass that knows the tangent frame, seen obliquely under the constant environment
// L = 0.5 with no lights, so each pixel is L (f0 A + B)(1 + f0 (1 / E - 1)) with A + B = E, the anisotropic GGX
// albedo at the view's azimuth from the anisotropy direction (shared/pt_energy.h's table, the path tracer's
// compensation), A / B split by the analytic fit at the rms roughness. Tolerance 1% + 1e-3 per channel (RGBA16F
// output and the constant cubemap's fp16 texels: ~0.1%). The same pixels with E read from the isotropic table at
// the rms roughness (the model before the anisotropic table) must miss that tolerance somewhere, so the check sees E.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "render/renderer.hpp"
#include "shared/pt_energy.h"
#include "support/gpu_fixture.hpp"
#include "support/quad_scene.hpp"

namespace idk::test {
namespace {

using namespace idk::gpu;

constexpr uint32_t kWidth = 96, kHeight = 64;

// pbr.glsl's environmentBrdfApprox split into (A, B).
glm::dvec2 environmentBrdfAB(double r, double NdotV) {
    const glm::dvec4 rr = r * glm::dvec4(-1.0, -0.0275, -0.572, 0.022) + glm::dvec4(1.0, 0.0425, 1.04, -0.04);
    const double a004 = std::min(rr.x * rr.x, std::exp2(-9.28 * NdotV)) * rr.x + rr.y;
    return glm::dvec2(-1.04 * a004 + rr.z, 1.04 * a004 + rr.w);  // f0 * A + B = f0 * ab.x + ab.y
}

struct Case {
    float roughness, strength, rotation;
};

class AnisotropyAmbientTest : public GpuTest {};

TEST_F(AnisotropyAmbientTest, ForwardSplitSumReadsTheAnisotropicAlbedo) {
    const glm::dvec3 f0(1.0, 0.55, 0.2);  // red: a white channel (E cancels), green and blue see E
    uint32_t checked = 0, failures = 0, oldModelMisses = 0;
    double worst = 0.0;
    for (const Case c : {Case{0.3f, 0.8f, 0.0f}, Case{0.5f, 1.0f, 1.2f}, Case{0.15f, 0.6f, 0.5f}}) {
        QuadSpec q;
        q.halfSize = 6.0f;
        q.baseColor = glm::vec3(f0);
        q.metallic = 1.0f;
        q.roughness = c.roughness;
        scene::Scene s = makeQuadScene({q});
        for (scene::Mesh& mesh : s.meshes)
            for (scene::Primitive& prim : mesh.primitives) prim.tangents.assign(prim.normals.size(), glm::vec4(1, 0, 0, 1));
        scene::Material& m = s.materials[0];
        m.alphaMode = scene::AlphaMode::Blend;  // the forward pass: it has the tangent frame
        m.anisotropyStrength = c.strength;
        m.anisotropyRotation = c.rotation;

        render::RenderSettings settings;
        settings.output = render::OutputKind::Hdr;
        settings.environment = std::filesystem::path();  // constant radiance 0.5
        render::Renderer renderer(ctx(), shaders(), settings);
        renderer.setScene(s);
        scene::CameraView camera;
        camera.position = glm::vec3(0.0f, -2.2f, 1.1f);
        camera.forward = glm::normalize(glm::vec3(0.0f, 0.5f, 0.0f) - camera.position);
        camera.up = glm::vec3(0.0f, 0.0f, 1.0f);
        camera.znear = 0.05f;
        camera.zfar = 100.0f;
        const core::ImageRgba32f img = renderer.renderOffscreen(camera, kWidth, kHeight).image;

        const glm::dmat4 inv = glm::inverse(
            glm::dmat4(scene::projectionMatrix(camera, float(kWidth) / kHeight) * scene::viewMatrix(camera)));
        const double alpha = double(c.roughness) * c.roughness;
        const double alphaT = alpha + (1.0 - alpha) * double(c.strength) * c.strength;
        const double rms = std::sqrt(std::sqrt(0.5 * (alphaT * alphaT + alpha * alpha)));
        const glm::dvec3 t(std::cos(c.rotation), std::sin(c.rotation), 0.0), b(-t.y, t.x, 0.0);
        for (uint32_t py = 0; py < kHeight; ++py) {
            for (uint32_t px = 0; px < kWidth; ++px) {
                const double x = (px + 0.5) / kWidth * 2.0 - 1.0, y = (py + 0.5) / kHeight * 2.0 - 1.0;
                const glm::dvec4 a = inv * glm::dvec4(x, y, 0.0, 1.0), e = inv * glm::dvec4(x, y, 0.5, 1.0);
                const glm::dvec3 origin = glm::dvec3(a) / a.w, dir = glm::normalize(glm::dvec3(e) / e.w - origin);
                if (dir.z > -0.1) continue;  // sky, or the plane too close to grazing for a pixel centre
                const glm::dvec3 p = origin + dir * (-origin.z / dir.z);
                if (std::abs(p.x) > q.halfSize - 0.5 || std::abs(p.y) > q.halfSize - 0.5) continue;
                const glm::dvec3 v = -dir;
                const double NdotV = std::max(v.z, 1e-4);
                const glm::dvec2 ab = environmentBrdfAB(rms, NdotV);
                const double eAniso = ptAlbedoAnisoMetal(glm::vec3(glm::dot(v, t), glm::dot(v, b), v.z), c.roughness,
                                                         c.strength);
                const double eIso = ptAlbedoMetal(float(NdotV), float(rms));
                auto expected = [&](double eRaw, int ch) {
                    const double en = std::max(eRaw, 0.05);
                    const glm::dvec2 s2 = ab * (en / std::max(ab.x + ab.y, 1e-4));
                    return 0.5 * (f0[ch] * s2.x + s2.y) * (1.0 + f0[ch] * (1.0 / en - 1.0));
                };
                const float* got = &img.pixels[(size_t(py) * kWidth + px) * 4];
                bool oldMiss = false;
                for (int ch = 0; ch < 3; ++ch) {
                    const double want = expected(eAniso, ch), err = std::abs(double(got[ch]) - want);
                    worst = std::max(worst, err / want);
                    if (!(err <= 0.01 * want + 1e-3) && failures++ < 5)
                        ADD_FAILURE() << "pixel " << px << "," << py << " channel " << ch << ": gpu " << got[ch]
                                      << ", oracle " << want << " (roughness " << c.roughness << ", strength "
                                      << c.strength << ")";
                    const double old = expected(eIso, ch);
                    oldMiss = oldMiss || std::abs(double(got[ch]) - old) > 0.01 * old + 1e-3;
                }
                oldModelMisses += oldMiss ? 1u : 0u;
                ++checked;
            }
        }
    }
    std::printf("anisotropic split-sum: %u pixels, worst relative error %.4f; %u of them off by more than the "
                "tolerance from the isotropic-E model\n", checked, worst, oldModelMisses);
    EXPECT_GT(checked, kWidth * kHeight);  // three frames, more than a third of each on the quad
    EXPECT_EQ(failures, 0u);
    EXPECT_GT(oldModelMisses, checked / 20);
}

}  // namespace
}  // namespace idk::test
