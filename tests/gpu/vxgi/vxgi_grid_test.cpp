// vxgi_grid_test.cpp: --gi-grid camera (frame/vxgi_feature.hpp followCamera): the grid keeps the fitted cube's size
// and voxel size, centred on the camera and snapped to steps of gridSize / 8 voxels. On a static scene of quads (a
// point light, no shadow maps, centre raster, 64^3 voxels, 16x16 frames):
//  * moving the camera within a step (0.5 step on every axis) leaves the box and the grid bit-identical;
//  * moving it by one step along x moves the box by exactly one step and the grid by exactly 8 voxels: every voxel
//    of the overlap equals the one 8 voxels over in the first grid (occupancy exactly; rgb within one fp16 step:
//    the fragments' world positions are interpolated from a corner that differs in its last float bits);
//  * --gi-grid fit does not move with the camera.
//  * --gi-voxel-draws single (one draw, a geometry shader projects each triangle along its dominant axis) gives the
//    three-draw grid: same occupancy, rgba within one fp16 step, with centre raster and with the dilating geometry
//    shader (conservative raster's fallback rung; the native rung where the device has it).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "frame/vxgi_feature.hpp"
#include "render/renderer.hpp"
#include "support/gpu_fixture.hpp"
#include "support/placed_quads.hpp"
#include "support/vxgi_cone_oracle.hpp"

namespace idk::test {
namespace {

constexpr uint32_t kVoxels = 64;

// Quad edges away from voxel centres (no rasterization ties), walls on the bounds.
scene::Scene gridScene() {
    std::vector<PlacedQuad> q;
    q.push_back(placedQuad({0.02f, -1.0f, 0.01f}, {0, 1, 0}, {0.93f, 0.91f}, {0.8f, 0.8f, 0.8f}));
    q.push_back(placedQuad({-0.01f, 0.03f, -1.0f}, {0, 0, 1}, {0.88f, 0.94f}, {0.7f, 0.7f, 0.6f}));
    q.push_back(placedQuad({-1.0f, 0.02f, 0.03f}, {1, 0, 0}, {0.74f, 0.69f}, {0.8f, 0.1f, 0.1f}));
    q.push_back(placedQuad({1.0f, -0.03f, 0.01f}, {-1, 0, 0}, {0.67f, 0.73f}, {0.1f, 0.8f, 0.1f}));
    q.push_back(placedQuad({0.1f, -0.2f, 0.15f}, {0.3f, 0.8f, 0.45f}, {0.4f, 0.3f}, {0.2f, 0.7f, 0.3f}, true));
    scene::Scene s = makePlacedQuadScene(q);
    for (scene::Material& m : s.materials) m.metallic = 0.0f;
    s.lights.push_back(pointLight({0.2f, 0.6f, 0.1f}, 3.0f));
    return s;
}

struct Grid {
    passes::VoxelGridBox box;
    std::vector<glm::vec4> voxels;
};

Grid render(render::Renderer& r, vk::Context& ctx, glm::vec3 position) {
    scene::CameraView c;
    c.position = position;
    r.renderOffscreen(c, 16, 16);
    Grid g;
    g.box = r.vxgi().box();
    g.voxels = readVoxelVolume(ctx, *r.vxgi().grid(), 1, VK_IMAGE_LAYOUT_GENERAL).levels[0];
    return g;
}

render::RenderSettings gridSettings(frame::VoxelGridPlacement placement,
                                    frame::VoxelRaster raster = frame::VoxelRaster::Centre,
                                    frame::VoxelDraws draws = frame::VoxelDraws::Three) {
    render::RenderSettings s;
    s.output = render::OutputKind::Hdr;
    s.pointShadows.maxLights = 0;
    s.vxgi.mode = frame::GiMode::Vxgi;
    s.vxgi.voxels = kVoxels;
    s.vxgi.raster = raster;
    s.vxgi.grid = placement;
    s.vxgi.draws = draws;
    return s;
}

size_t index(int x, int y, int z) { return (size_t(z) * kVoxels + size_t(y)) * kVoxels + size_t(x); }

class VxgiGridTest : public GpuTest {};

TEST_F(VxgiGridTest, CameraGridMovesInWholeStepsOnly) {
    render::Renderer r(ctx(), shaders(), gridSettings(frame::VoxelGridPlacement::Camera));
    r.setScene(gridScene());
    // Place the camera 0.35 step into a step on every axis (then +0.5 step stays inside it).
    const Grid probe = render(r, ctx(), glm::vec3(0.1f, 0.2f, 0.3f));
    const float step = frame::voxelGridStep(probe.box);
    ASSERT_NEAR(step, probe.box.voxelSize * float(kVoxels / 8), 1e-6f);
    const float half = 0.5f * probe.box.voxelSize * float(kVoxels);
    const glm::vec3 c0 = probe.box.gridMin + glm::vec3(half + 0.35f * step);

    const Grid a = render(r, ctx(), c0);
    const Grid b = render(r, ctx(), c0 + glm::vec3(0.5f * step));
    EXPECT_EQ(a.box.gridMin, b.box.gridMin) << "a move within the step keeps the box";
    ASSERT_EQ(a.voxels.size(), b.voxels.size());
    EXPECT_EQ(std::memcmp(a.voxels.data(), b.voxels.data(), a.voxels.size() * sizeof(glm::vec4)), 0)
        << "a move within the step keeps the grid bit-identical";

    const Grid c = render(r, ctx(), c0 + glm::vec3(step, 0.0f, 0.0f));
    EXPECT_NEAR(c.box.gridMin.x - a.box.gridMin.x, step, 1e-5f * step) << "one step along x moves the box by one step";
    EXPECT_EQ(c.box.gridMin.y, a.box.gridMin.y);
    EXPECT_EQ(c.box.gridMin.z, a.box.gridMin.z);
    EXPECT_EQ(c.box.voxelSize, a.box.voxelSize);
    const int shift = int(kVoxels / 8);
    size_t occupied = 0, occupancyDiff = 0, valueDiff = 0;
    for (int z = 0; z < int(kVoxels); ++z)
        for (int y = 0; y < int(kVoxels); ++y)
            for (int x = 0; x + shift < int(kVoxels); ++x) {
                const glm::vec4& moved = c.voxels[index(x, y, z)];
                const glm::vec4& before = a.voxels[index(x + shift, y, z)];
                occupied += before.a > 0.0f;
                if ((moved.a > 0.0f) != (before.a > 0.0f)) {
                    ++occupancyDiff;
                    continue;
                }
                for (int k = 0; k < 4; ++k)  // one fp16 step (2^-10 relative)
                    valueDiff += std::abs(moved[k] - before[k]) > 1e-3f * std::abs(before[k]) + 1e-6f;
            }
    EXPECT_GT(occupied, 5000u) << "the overlap should hold the scene";
    EXPECT_EQ(occupancyDiff, 0u) << "the grid moved by exactly 8 voxels";
    EXPECT_EQ(valueDiff, 0u);
}

TEST_F(VxgiGridTest, FitGridIgnoresTheCamera) {
    render::Renderer r(ctx(), shaders(), gridSettings(frame::VoxelGridPlacement::Fit));
    r.setScene(gridScene());
    const Grid a = render(r, ctx(), glm::vec3(0.1f, 0.2f, 0.3f));
    const Grid b = render(r, ctx(), glm::vec3(-0.6f, 0.4f, 0.9f));
    EXPECT_EQ(a.box.gridMin, b.box.gridMin);
    EXPECT_EQ(std::memcmp(a.voxels.data(), b.voxels.data(), a.voxels.size() * sizeof(glm::vec4)), 0);
    // The camera grid at the scene's centre is the fitted cube moved by less than a step per axis.
    render::Renderer rc(ctx(), shaders(), gridSettings(frame::VoxelGridPlacement::Camera));
    rc.setScene(gridScene());
    const Grid c = render(rc, ctx(), a.box.gridMin + glm::vec3(0.5f * a.box.voxelSize * float(kVoxels)));
    for (int k = 0; k < 3; ++k) EXPECT_LE(std::abs(c.box.gridMin[k] - a.box.gridMin[k]), frame::voxelGridStep(a.box));
    EXPECT_EQ(c.box.voxelSize, a.box.voxelSize);
}

TEST_F(VxgiGridTest, SingleDrawGivesTheThreeDrawGrid) {
    for (frame::VoxelRaster raster : {frame::VoxelRaster::Centre, frame::VoxelRaster::Conservative}) {
        Grid grids[2];
        for (int single = 0; single < 2; ++single) {
            render::Renderer r(ctx(), shaders(),
                               gridSettings(frame::VoxelGridPlacement::Fit, raster,
                                            single ? frame::VoxelDraws::Single : frame::VoxelDraws::Three));
            r.setScene(gridScene());
            grids[single] = render(r, ctx(), glm::vec3(0.1f, 0.2f, 0.3f));
        }
        const char* what = raster == frame::VoxelRaster::Centre ? "centre raster" : "conservative raster";
        ASSERT_EQ(grids[0].voxels.size(), grids[1].voxels.size());
        size_t occupied = 0, occupancyDiff = 0, valueDiff = 0;
        for (size_t i = 0; i < grids[0].voxels.size(); ++i) {
            const glm::vec4 &a = grids[0].voxels[i], &b = grids[1].voxels[i];
            occupied += a.a > 0.0f;
            if ((a.a > 0.0f) != (b.a > 0.0f)) {
                ++occupancyDiff;
                continue;
            }
            for (int k = 0; k < 4; ++k) valueDiff += std::abs(a[k] - b[k]) > 1e-3f * std::abs(a[k]) + 1e-6f;
        }
        EXPECT_GT(occupied, 5000u) << what;
        EXPECT_EQ(occupancyDiff, 0u) << what;
        EXPECT_EQ(valueDiff, 0u) << what;
    }
}

}  // namespace
}  // namespace idk::test
