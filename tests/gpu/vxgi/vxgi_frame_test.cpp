// vxgi_frame_test.cpp: whole frames with --gi vxgi against the path tracer, on a closed room (2 m cube of grey
// inward-facing walls) lit only by an emissive panel in its ceiling, environment off, 64x64 pixels, 64^3 voxels.
//  * --gi none: no vxgi_* pass runs and no grid exists; with vxgi all thirteen passes run (64^3: six mip levels;
//    the default half-resolution cone trace, its upsample and fix-up trace).
//  * --gi none: the room is black: every pixel that does not see the panel is exactly 0 (the rasterizer has no
//    area lights; emission reaches other surfaces only through GI).
//  * --gi vxgi (64^3 voxels, 1 + 8 diffuse cones, step 0.5): the walls receive the panel's light through the
//    cones. The reference is the GPU path tracer with maxDepth 2 (camera segment + one bounce: exactly the light
//    VXGI carries, emission seen by the diffuse and specular cones; 256 spp). Every wall pixel's light is indirect,
//    so the wall radiance is the indirect term. Asserted over the pixels that do not see the panel: mean radiance
//    within 11% of the path tracer's (measured 10.6% darker), and RMSE relative to the reference mean below 3.0
//    (measured 2.80: dominated by the ceiling around the panel). History: 30.3% darker before the receiver-plane
//    clamp and the cell-based step opacity of shared/vxgi_cone.h, then 32.0% brighter while level 0 was isotropic
//    (the panel, one voxel thick and radiating equally in all directions, glowed edge-on in the directional mips);
//    the directional level 0 by the surfaces' facing (vxgiVoxelTowards) brought it to 7.0% brighter (rms 3.12),
//    two errors cancelling: each cone's tube (0.2..0.3 of its width) hit the panel with the cone's whole weight,
//    while the level cap (cells of at most N / 8, 25 cm here) kept far cones from reaching it. The default 4
//    footprint cones (--gi-footprint) gather the panel by its solid angle (rms 3.12 -> 2.80) and leave the cap's
//    share: a narrow cone from the floor, 2 m below, samples 25 cm cells where its footprint is 1.1 m wide. A cap
//    one level higher (N / 4) measured brighter here but lets the thin wall below leak 0.175 of the lit side.
//    The front-most rule (shared/vxgi_depth_key.h: the panel's voxels no longer average in the ceiling it hides)
//    measured 5.4% brighter with one cone and 10.6% darker with four (10.1% without the rule): the panel sits in
//    its own voxel layer here, so the rule changes little in this room.
//  The images are written to <build>/vxgi_frame_test/room_{vxgi,pt_one_bounce,pt_full}.exr.
//  * The full path-traced image (maxDepth 8, all bounces) is also measured and printed: the gap is the light of
//    further bounces, which single-bounce VXGI leaves out by design.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "render/path_tracer.hpp"
#include "render/renderer.hpp"
#include "support/gpu_fixture.hpp"
#include "gpu/vxgi/vxgi_room.hpp"
#include "support/placed_quads.hpp"
#include "support/vxgi_cone_oracle.hpp"

namespace idk::test {
namespace {

constexpr uint32_t kSize = 64;

PlacedQuad wall(glm::vec3 centre, glm::vec3 normal, glm::vec2 half) { return roomWall(centre, normal, half); }

// The closed room; quad 5 is the emissive panel (the ceiling is four strips around it, all in the plane y = 1).
scene::Scene closedRoom() { return closedRoomScene(glm::vec3(8.0f)); }

scene::CameraView camera() { return closedRoomCamera(); }

core::ImageRgba32f raster(vk::Context& ctx, vk::ShaderLibrary& shaders, const scene::Scene& s, frame::GiMode gi,
                          uint32_t voxels = 64, float step = 0.5f, uint32_t cones = 8) {
    const bool on = gi == frame::GiMode::Vxgi;
    render::RenderSettings settings;
    settings.output = render::OutputKind::Hdr;
    settings.environmentIntensity = 0.0f;
    settings.vxgi.mode = gi;
    settings.vxgi.voxels = voxels;
    settings.vxgi.stepFactor = step;
    settings.vxgi.ringCones = cones;
    render::Renderer renderer(ctx, shaders, settings);
    renderer.setScene(s);
    render::FrameResult frame = renderer.renderOffscreen(camera(), kSize, kSize);
    // --gi none: no VXGI pass ran and nothing is held; vxgi: the voxelization, mip and cone passes all ran.
    size_t vxgiPasses = 0;
    for (const std::string& pass : frame.passesRun) vxgiPasses += pass.rfind("vxgi_", 0) == 0;
    EXPECT_EQ(vxgiPasses, on ? 5u + 6u + 3u : 0u) << "clear, depth keys, voxelize, merge args, merge, 6 mip levels "
                                                     "(64^3), half-resolution cone trace, upsample, fix-up trace";
    EXPECT_EQ(renderer.vxgi().grid() != nullptr, on);
    return frame.image;
}

core::ImageRgba32f pathTrace(vk::Context& ctx, vk::ShaderLibrary& shaders, const scene::Scene& s, uint32_t depth) {
    render::PathTracerOptions options;
    options.environmentIntensity = 0.0f;
    render::PathTracer tracer(ctx, shaders, s, options);
    render::PathTraceSettings settings;
    settings.spp = 256;
    settings.maxDepth = depth;
    return tracer.render(camera(), kSize, kSize, settings).image;
}

double luminance(const core::ImageRgba32f& img, size_t i) {
    const float* p = &img.pixels[i * 4];
    return (double(p[0]) + p[1] + p[2]) / 3.0;
}

struct Error {
    double meanRelative = 0.0, rmsRelative = 0.0, mean = 0.0, reference = 0.0;
};

// Over the pixels that do not see the panel (`none` is 0 there).
Error measure(const core::ImageRgba32f& img, const core::ImageRgba32f& ref, const core::ImageRgba32f& none) {
    Error e;
    double sq = 0.0;
    size_t n = 0;
    for (size_t i = 0; i < size_t(kSize) * kSize; ++i) {
        if (luminance(none, i) > 0.0) continue;
        const double a = luminance(img, i), b = luminance(ref, i);
        e.mean += a;
        e.reference += b;
        sq += (a - b) * (a - b);
        ++n;
    }
    e.mean /= double(n);
    e.reference /= double(n);
    e.meanRelative = std::abs(e.mean - e.reference) / e.reference;
    e.rmsRelative = std::sqrt(sq / double(n)) / e.reference;  // RMSE relative to the mean reference radiance
    return e;
}

class VxgiFrameTest : public GpuTest {};

TEST_F(VxgiFrameTest, ClosedRoomLitByPanelMatchesOneBouncePathTracer) {
    const scene::Scene s = closedRoom();
    const core::ImageRgba32f none = raster(ctx(), shaders(), s, frame::GiMode::None);
    size_t lit = 0, panel = 0;
    for (size_t i = 0; i < size_t(kSize) * kSize; ++i) (luminance(none, i) > 0.0 ? panel : lit)++;
    ASSERT_GT(panel, 20u) << "the camera should see the panel";
    ASSERT_GT(lit, size_t(kSize) * kSize / 2) << "and mostly walls";

    const core::ImageRgba32f vxgi = raster(ctx(), shaders(), s, frame::GiMode::Vxgi);
    const core::ImageRgba32f oneBounce = pathTrace(ctx(), shaders(), s, 2);
    const core::ImageRgba32f full = pathTrace(ctx(), shaders(), s, 8);
    const Error e = measure(vxgi, oneBounce, none);
    const std::filesystem::path dir = std::filesystem::path(IDK_BINARY_DIR) / "vxgi_frame_test";
    std::filesystem::create_directories(dir);
    core::writeImage((dir / "room_vxgi.exr").string(), vxgi);
    core::writeImage((dir / "room_pt_one_bounce.exr").string(), oneBounce);
    core::writeImage((dir / "room_pt_full.exr").string(), full);
    const Error eFull = measure(vxgi, full, none);
    std::printf("closed room, mean wall radiance: vxgi %.4f, path tracer one bounce %.4f (mean error %.1f%%, per-pixel "
                "rms relative %.3f), all bounces %.4f (mean error %.1f%%)\n",
                e.mean, e.reference, 100.0 * e.meanRelative, e.rmsRelative, eFull.reference,
                100.0 * eFull.meanRelative);
    EXPECT_GT(e.mean, 0.0) << "the closed room is still black with VXGI";
    EXPECT_LT(e.meanRelative, 0.11);
    EXPECT_LT(e.rmsRelative, 3.0);
}

// Furnace-like check: a white floor (albedo 1, rough dielectric) under a uniform sky of radiance 0.5. With VXGI
// every cone must see the sky unoccluded; the floor's own voxels must not shadow its cones (self-occlusion darkens
// it). The reference is the same frame with --gi none, whose SH9 irradiance of the constant sky is exact since the
// projection integrates over texel areas (it reflects exactly L = 0.5, tests/gpu/pbr/ambient_furnace_test.cpp).
// Asserted: VXGI's floor within 1% of it everywhere (measured 0.4998). The cones' receiver-plane clamp
// (shared/vxgi_cone.h) makes it so; before it the ring cones saw the floor's own coarse cells (0.28 .. 0.30).
TEST_F(VxgiFrameTest, WhiteFloorUnderUniformSkyReflectsTheSky) {
    PlacedQuad floor = wall({0, 0, 0}, {0, 1, 0}, {2, 2});
    floor.baseColor = glm::vec3(1.0f);
    scene::Scene s = makePlacedQuadScene({floor});
    s.materials[0].metallic = 0.0f;
    scene::CameraView c;
    c.position = {0.0f, 1.5f, 0.0f};
    c.forward = {0.0f, -1.0f, 0.0f};
    c.up = {0.0f, 0.0f, -1.0f};
    c.yfov = 1.0f;
    c.znear = 0.01f;
    double none = 0.0;
    for (frame::GiMode gi : {frame::GiMode::None, frame::GiMode::Vxgi}) {
        render::RenderSettings settings;
        settings.output = render::OutputKind::Hdr;
        settings.environment = std::filesystem::path();  // constant radiance 0.5
        settings.vxgi.mode = gi;
        settings.vxgi.voxels = 64;
        render::Renderer renderer(ctx(), shaders(), settings);
        renderer.setScene(s);
        const core::ImageRgba32f img = renderer.renderOffscreen(c, kSize, kSize).image;
        double lo = 1e9, hi = 0.0;
        for (size_t i = 0; i < size_t(kSize) * kSize; ++i) {
            if (img.pixels[i * 4 + 3] <= 0.0f) continue;  // sky
            lo = std::min(lo, luminance(img, i));
            hi = std::max(hi, luminance(img, i));
        }
        std::printf("white floor, uniform sky 0.5, gi %s: floor radiance %.4f .. %.4f\n",
                    gi == frame::GiMode::Vxgi ? "vxgi" : "none", lo, hi);
        if (gi == frame::GiMode::None) {
            EXPECT_NEAR(lo, hi, 1e-3 * hi) << "a constant sky lights the floor evenly";
            EXPECT_NEAR(lo, 0.5, 0.005) << "albedo 1 under the split-sum ambient reflects exactly the sky";
            none = lo;
        } else {
            EXPECT_NEAR(lo, none, 0.01 * none);
            EXPECT_NEAR(hi, none, 0.01 * none);
        }
    }
}

// Thin walls: the closed room split at x = 0.013 by a one-voxel-thin double-sided wall (its plane inside a voxel),
// the emissive panel over the lit half (x > 0) only, no sky, 64^3 voxels, conservative voxelization (the voxelized
// wall has no holes: VoxelizeTest.ThinWallHasNoHolesWithConservativeRaster). A camera in each half looking down
// -z; every surface the dark camera sees is in the dark half, whose true radiance is 0 (the path tracer's). No
// specular layers, so every wall pixel is albedo / pi * E and the CPU cone tracer (support/vxgi_cone_oracle.hpp)
// predicts it from the read-back grid.
// The aim (dark below 1% of lit) is out of reach by construction: a cone's sample holds one scalar opacity
// per direction for a cell as wide as the cone, so a 30-degree cone that crosses the wall's plane obliquely sees
// the wall as partial coverage in each of the several cells its axis crosses (|dir.x| of a cell's silhouette in
// each), composited as a Beer-Lambert medium, where the true wall blocks every ray that crosses it. The CPU cone
// tracer on the same grid gives this inherent leak: measured dark / lit 0.0541 (the GPU frame 0.0541; 0.0629 with
// one cone per direction instead of the default 4 footprint cones; 0.0505 while level 0 was isotropic, fully opaque
// from every side; 0.4853 before the receiver-plane clamp and the cell-based step opacity of shared/vxgi_cone.h).
// Asserted: the GPU's dark / lit ratio within 5% of the CPU cone tracer's over the same pixels, and below 0.06.
TEST_F(VxgiFrameTest, ThinWallLeaksNoMoreThanTheConeTracerInherently) {
    std::vector<PlacedQuad> q;
    q.push_back(wall({0, -1, 0}, {0, 1, 0}, {1, 1}));
    q.push_back(wall({-1, 0, 0}, {1, 0, 0}, {1, 1}));
    q.push_back(wall({1, 0, 0}, {-1, 0, 0}, {1, 1}));
    q.push_back(wall({0, 0, -1}, {0, 0, 1}, {1, 1}));
    q.push_back(wall({0, 0, 1}, {0, 0, -1}, {1, 1}));
    q.push_back(wall({0.5f, 1, 0}, {0, -1, 0}, {0.3f, 0.3f}));  // the panel, over the lit half
    q.push_back(wall({-0.4f, 1, 0}, {0, -1, 0}, {0.6f, 1}));
    q.push_back(wall({0.9f, 1, 0}, {0, -1, 0}, {0.1f, 1}));
    q.push_back(wall({0.5f, 1, -0.65f}, {0, -1, 0}, {0.3f, 0.35f}));
    q.push_back(wall({0.5f, 1, 0.65f}, {0, -1, 0}, {0.3f, 0.35f}));
    PlacedQuad divider = wall({0.013f, 0, 0}, {1, 0, 0}, {1, 1});
    divider.doubleSided = true;
    q.push_back(divider);
    scene::Scene s = makePlacedQuadScene(q);
    for (scene::Material& m : s.materials) m.metallic = 0.0f;
    s.materials[5].emissive = glm::vec3(8.0f);
    auto view = [](float x) {
        scene::CameraView c;
        c.position = {x, -0.2f, 0.9f};
        c.forward = glm::normalize(glm::vec3(0.0f, -0.3f, -1.0f));
        c.up = glm::normalize(glm::cross(glm::cross(c.forward, glm::vec3(0, 1, 0)), c.forward));
        c.yfov = 0.5f;
        c.znear = 0.01f;
        return c;
    };
    for (scene::Material& m : s.materials) m.specular = 0.0f;  // wall pixels: albedo / pi * E
    render::RenderSettings settings;
    settings.output = render::OutputKind::Hdr;
    settings.environmentIntensity = 0.0f;
    settings.vxgi.mode = frame::GiMode::Vxgi;
    settings.vxgi.voxels = 64;
    settings.vxgi.ringCones = 8;
    settings.vxgi.raster = frame::VoxelRaster::Conservative;
    settings.vxgi.resolution = frame::GiResolution::Full;  // the CPU cone tracer predicts every pixel
    render::Renderer renderer(ctx(), shaders(), settings);
    renderer.setScene(s);
    double gpu[2] = {0.0, 0.0}, cpu[2] = {0.0, 0.0};
    for (int side = 0; side < 2; ++side) {
        const scene::CameraView c = view(side == 0 ? -0.5f : 0.5f);
        const core::ImageRgba32f img = renderer.renderOffscreen(c, kSize, kSize).image;
        const ConeGridData grid = readConeGrid(ctx(), renderer.vxgi());
        const std::vector<PredictedPixel> predicted =
            predictDiffuseFrame(q, 5, c, kSize, grid, conePush(renderer.vxgi(), settings.vxgi), glm::vec3(0.0f));
        ASSERT_GT(predicted.size(), size_t(kSize) * kSize / 2);
        for (const PredictedPixel& px : predicted) {
            gpu[side] += luminance(img, size_t(px.y) * kSize + px.x);
            cpu[side] += (double(px.radiance.r) + px.radiance.g + px.radiance.b) / 3.0;
        }
    }
    const double gpuRatio = gpu[0] / gpu[1], cpuRatio = cpu[0] / cpu[1];
    std::printf("thin wall: dark / lit mean radiance, GPU %.4f, CPU cone tracer %.4f\n", gpuRatio, cpuRatio);
    EXPECT_GT(gpu[1], 0.0) << "the lit half is lit";
    EXPECT_NEAR(gpuRatio, cpuRatio, 0.05 * cpuRatio);
    EXPECT_LT(gpuRatio, 0.06);
}

}  // namespace
}  // namespace idk::test
