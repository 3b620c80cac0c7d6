// cone_trace_test.cpp: the cone-tracing pass (passes/vxgi_cone_trace.cpp) against the CPU cone tracer
// (support/vxgi_cone_oracle.hpp) on the same grid: a frame with --gi vxgi (64^3 voxels, 8 ring cones, step 0.5)
// is rendered, its voxel grid and the six directional mip chains are read back, and for every pixel the CPU
// traces the same diffuse cone set from the same surface point through those volumes. The walls have no specular
// layer (KHR_materials_specular factor 0) and no light other than the cone-traced ambient reaches them, so the
// frame there is exactly albedo / pi * E (the shared ambient function, surface_lighting.glsl), E the traced
// irradiance: the pixel compares with the CPU's E directly. Pixels whose neighbours see another quad (the depth
// buffer's geometric normal) or that see the emitter are left out.
//  * Closed room lit by an emissive ceiling panel with a box on the floor, environment off (occlusion, emission
//    and the mips' compositing; the sky term is 0).
//  * A floor and a box under a uniform sky of 0.5 (the sky through partly occluded cones).
//  * The closed room again with each diffuse cone traced as 7 footprint cones (--gi-footprint 7).
// Asserted on both: the mean relative difference below 0.3% and 99% of pixel channels within 1% (+1e-4 absolute)
// of the CPU (measured: room 0.059% mean, worst 1.35%; sky 0.076%, worst 1.93%; 99.8% within 1%). What remains is the sampler's
// fixed-point texel weights (subTexelPrecisionBits; a real GPU may have fewer bits than lavapipe, hence the
// margin), the depth-reconstructed position and the fp16 output; the G-buffer's 8-bit sRGB albedo is decoded
// on the CPU alike.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "render/renderer.hpp"
#include "support/gpu_fixture.hpp"
#include "support/placed_quads.hpp"
#include "support/vxgi_cone_oracle.hpp"

namespace idk::test {
namespace {

constexpr uint32_t kSize = 48;

PlacedQuad panel(glm::vec3 centre, glm::vec3 normal, glm::vec2 half, float albedo) {
    PlacedQuad q;
    q.centre = centre;
    q.normal = normal;
    q.halfSize = half;
    q.baseColor = glm::vec3(albedo);
    return q;
}

struct Case {
    std::vector<PlacedQuad> quads;
    int emitter = -1;
    bool sky = false;  // uniform 0.5 (else the environment is off)
    scene::CameraView camera;
};

Case closedRoom() {
    Case c;
    c.quads = {panel({0, -1, 0}, {0, 1, 0}, {1, 1}, 0.6f),   panel({-1, 0, 0}, {1, 0, 0}, {1, 1}, 0.6f),
               panel({1, 0, 0}, {-1, 0, 0}, {1, 1}, 0.6f),   panel({0, 0, -1}, {0, 0, 1}, {1, 1}, 0.6f),
               panel({0, 0, 1}, {0, 0, -1}, {1, 1}, 0.6f),   panel({0, 1, 0}, {0, -1, 0}, {1, 1}, 0.6f),
               panel({0, 0.99f, 0}, {0, -1, 0}, {0.3f, 0.3f}, 0.6f)};
    c.emitter = 6;
    for (const PlacedQuad& f : boxFaces({0.3f, -1.0f, -0.2f}, {0.25f, 0.4f, 0.25f}, glm::vec3(0.6f)))
        c.quads.push_back(f);
    c.camera.position = {-0.2f, -0.1f, 0.9f};
    c.camera.forward = glm::normalize(glm::vec3(0.2f, -0.2f, -1.0f));
    c.camera.up = glm::normalize(glm::cross(glm::cross(c.camera.forward, glm::vec3(0, 1, 0)), c.camera.forward));
    c.camera.yfov = 1.3f;
    c.camera.znear = 0.01f;
    return c;
}

Case skyFloor() {
    Case c;
    c.quads = {panel({0, 0, 0}, {0, 1, 0}, {1.5f, 1.5f}, 1.0f)};
    for (const PlacedQuad& f : boxFaces({0.0f, 0.0f, 0.0f}, {0.4f, 0.5f, 0.4f}, glm::vec3(1.0f))) c.quads.push_back(f);
    c.sky = true;
    c.camera.position = {0.9f, 1.2f, 1.3f};
    c.camera.forward = glm::normalize(glm::vec3(-0.9f, -1.2f, -1.3f));
    c.camera.up = glm::normalize(glm::cross(glm::cross(c.camera.forward, glm::vec3(0, 1, 0)), c.camera.forward));
    c.camera.yfov = 1.0f;
    c.camera.znear = 0.01f;
    return c;
}

class VxgiConeTraceTest : public GpuTest {
protected:
    void compare(const Case& k, const char* name, uint32_t footprintCones = 1) {
        scene::Scene s = makePlacedQuadScene(k.quads);
        for (scene::Material& m : s.materials) {
            m.metallic = 0.0f;
            m.specular = 0.0f;  // no specular layer: the frame is albedo / pi * E
        }
        if (k.emitter >= 0) s.materials[size_t(k.emitter)].emissive = glm::vec3(8.0f);
        render::RenderSettings settings;
        settings.output = render::OutputKind::Hdr;
        if (k.sky) settings.environment = std::filesystem::path();  // constant radiance 0.5
        else settings.environmentIntensity = 0.0f;
        settings.vxgi.mode = frame::GiMode::Vxgi;
        settings.vxgi.voxels = 64;
        settings.vxgi.resolution = frame::GiResolution::Full;  // every pixel traced: the CPU's per-pixel oracle
        settings.vxgi.ringCones = 8;
        settings.vxgi.stepFactor = 0.5f;
        settings.vxgi.footprintCones = footprintCones;
        render::Renderer renderer(ctx(), shaders(), settings);
        renderer.setScene(s);
        const core::ImageRgba32f img = renderer.renderOffscreen(k.camera, kSize, kSize).image;

        ASSERT_NE(renderer.vxgi().grid(), nullptr);
        const ConeGridData grid = readConeGrid(ctx(), renderer.vxgi());
        const gpu::ConeTracePush c = conePush(renderer.vxgi(), settings.vxgi);
        const glm::vec3 sky(k.sky ? 0.5f : 0.0f);
        size_t compared = 0, within = 0;
        double sumRelative = 0.0, worst = 0.0, meanGpu = 0.0;
        for (const PredictedPixel& px : predictDiffuseFrame(k.quads, k.emitter, k.camera, kSize, grid, c, sky)) {
            for (int ch = 0; ch < 3; ++ch) {
                const double cpu = px.radiance[ch];
                const double gpu = img.pixels[(size_t(px.y) * kSize + px.x) * 4 + ch];
                const double rel = std::abs(gpu - cpu) / std::max(cpu, 1e-3);
                sumRelative += rel;
                worst = std::max(worst, rel);
                within += std::abs(gpu - cpu) <= 0.01 * cpu + 1e-4;
                meanGpu += gpu;
                ++compared;
            }
        }
        ASSERT_GT(compared, size_t(kSize) * kSize) << "most pixels should be compared";
        const double meanRelative = sumRelative / double(compared);
        const double fractionWithin = double(within) / double(compared);
        std::printf("cone trace vs CPU, %s: %zu channels, mean GPU radiance %.4f, mean relative difference %.5f, "
                    "worst %.4f, within 1%%: %.4f\n",
                    name, compared, meanGpu / double(compared), meanRelative, worst, fractionWithin);
        EXPECT_GT(meanGpu / double(compared), 0.01) << "the cones gather light";
        EXPECT_LT(meanRelative, 0.003);
        EXPECT_GE(fractionWithin, 0.99);
    }
};

TEST_F(VxgiConeTraceTest, ClosedRoomMatchesCpuConeTracer) { compare(closedRoom(), "closed room"); }

TEST_F(VxgiConeTraceTest, OpenFloorUnderSkyMatchesCpuConeTracer) { compare(skyFloor(), "floor under sky"); }

TEST_F(VxgiConeTraceTest, ClosedRoomFootprintConesMatchCpuConeTracer) {
    compare(closedRoom(), "closed room, 7 footprint cones", 7);
}

}  // namespace
}  // namespace idk::test
