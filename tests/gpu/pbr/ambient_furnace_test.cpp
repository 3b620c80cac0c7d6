// ambient_furnace_test.cpp: the rasterizer's ambient term (SH9 irradiance + split-sum specular, surface_lighting.glsl)
// in a furnace: a white Lambertian-like floor (albedo 1, dielectric f0 0.04, roughness 1) under the constant
// environment (radiance L = 0.5, no lights), --gi none. The split-sum ambient weights the diffuse term by
// (1 - E_s) and the specular by E_s, so with albedo 1 every pixel must reflect exactly L whatever E_s is. For
// reference, the exact hemispherical integral of the glTF BRDF (Smith-GGX single scattering, Schlick (1 - F)
// diffuse) gives 0.486 at NdotV = 1 (the split sum ignores the energy the single-scattering lobe loses).
// Tolerance: 1% of L. Before the SH projection integrated over texel areas the floor rendered 0.2976.
#include <gtest/gtest.h>

#include <cstdio>

#include "render/renderer.hpp"
#include "support/gpu_fixture.hpp"
#include "support/placed_quads.hpp"

namespace idk::test {
namespace {

constexpr uint32_t kSize = 64;

class AmbientFurnaceTest : public GpuTest {};

TEST_F(AmbientFurnaceTest, WhiteFloorUnderAConstantSkyReflectsTheSky) {
    PlacedQuad floor;
    floor.centre = {0.0f, 0.0f, 0.0f};
    floor.normal = {0.0f, 1.0f, 0.0f};
    floor.halfSize = {2.0f, 2.0f};
    floor.baseColor = glm::vec3(1.0f);
    scene::Scene s = makePlacedQuadScene({floor});
    s.materials[0].metallic = 0.0f;
    s.lights.clear();
    scene::CameraView c;
    c.position = {0.0f, 1.0f, 0.0f};
    c.forward = {0.0f, -1.0f, 0.0f};
    c.up = {0.0f, 0.0f, -1.0f};
    c.yfov = 1.0f;
    c.znear = 0.01f;
    render::RenderSettings settings;
    settings.output = render::OutputKind::Hdr;
    settings.environment = std::filesystem::path();  // constant radiance 0.5
    render::Renderer renderer(ctx(), shaders(), settings);
    renderer.setScene(s);
    const core::ImageRgba32f img = renderer.renderOffscreen(c, kSize, kSize).image;
    double lo = 1e9, hi = 0.0;
    size_t floorPixels = 0;
    for (size_t i = 0; i < size_t(kSize) * kSize; ++i) {
        if (img.pixels[i * 4 + 3] <= 0.0f) continue;  // sky
        ++floorPixels;
        for (int k = 0; k < 3; ++k) {
            lo = std::min(lo, double(img.pixels[i * 4 + k]));
            hi = std::max(hi, double(img.pixels[i * 4 + k]));
        }
    }
    std::printf("white floor, constant sky 0.5, --gi none: %zu floor pixels, radiance %.4f .. %.4f\n", floorPixels, lo,
                hi);
    ASSERT_EQ(floorPixels, size_t(kSize) * kSize) << "the floor fills the frame";
    EXPECT_NEAR(lo, 0.5, 0.005);
    EXPECT_NEAR(hi, 0.5, 0.005);
}

}  // namespace
}  // namespace idk::test
