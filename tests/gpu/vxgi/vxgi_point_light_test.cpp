// vxgi_point_light_test.cpp: the voxel grid's occupancy (alpha = coverage) does not depend on the lights. The
// closed room of vxgi_frame_test (2 m cube of grey inward-facing walls, ceiling in five pieces around an emissive
// panel), 64^3 voxels, 64x64 frames: the grid with a shadow-casting point light at (0.4, y, -0.2), y = 0.3, -0.5,
// 0.9, must hold exactly the occupied voxels (alpha > 0) of the grid without it, on both raster strategies
// (conservative, centre) and both draw schemes (three draws, single draw). The oracle is the lightless grid, the
// same passes minus the point-shadow ones; its ceiling layer (y index 63) must be whole with conservative raster
// (64 x 64 cells) and at least 63 x 63 with centre raster (measured 3969: the outermost row and column of pixel
// centres lie outside the 2 m ceiling).
// Regression: with GPU culling on (the default) the cube faces draw with vkCmdDrawIndexedIndirectCount, and
// lavapipe applied the last face's count to the voxelization's plain indirect draws, which then drew only the
// first 5, 3 and 6 of the room's 10 draws (ceiling layer 252, 128 and 652 cells instead of 4096); see
// passes/vxgi_voxelize.cpp.
#include <gtest/gtest.h>

#include <cstdio>
#include <vector>

#include "conformance/voxel_oracle.hpp"
#include "render/renderer.hpp"
#include "support/gpu_fixture.hpp"
#include "gpu/vxgi/vxgi_room.hpp"
#include "support/placed_quads.hpp"

namespace idk::test {
namespace {

constexpr uint32_t kVoxels = 64;
constexpr uint32_t kSize = 64;

// The closed room; quad 5 is the emissive panel (the ceiling is four strips around it, all in the plane y = 1).
scene::Scene closedRoom() { return closedRoomScene(glm::vec3(8.0f)); }

scene::CameraView camera() { return closedRoomCamera(); }

// One frame's grid occupancy (alpha > 0 per voxel, x fastest).
std::vector<bool> occupancy(vk::Context& ctx, vk::ShaderLibrary& shaders, const scene::Scene& s,
                            frame::VoxelRaster raster, frame::VoxelDraws draws) {
    render::RenderSettings settings;
    settings.output = render::OutputKind::Hdr;
    settings.environmentIntensity = 0.0f;
    settings.vxgi.mode = frame::GiMode::Vxgi;
    settings.vxgi.voxels = kVoxels;
    settings.vxgi.raster = raster;
    settings.vxgi.draws = draws;
    render::Renderer renderer(ctx, shaders, settings);
    renderer.setScene(s);
    const render::FrameResult frame = renderer.renderOffscreen(camera(), kSize, kSize);
    if (!s.lights.empty()) {
        // The condition that exposed the bug: GPU-culled cube faces (counted draws) with fewer than all draws.
        size_t faces = 0, culledFaces = 0;
        for (const passes::CullingViewStats& v : frame.culling) {
            if (v.view.rfind("light", 0) != 0) continue;
            ++faces;
            culledFaces += v.instancesDrawn < v.instancesTested;
        }
        EXPECT_EQ(faces, 6u) << "one GPU-culled cube";
        EXPECT_GT(culledFaces, 0u) << "no cube face culled a draw";
    }
    const std::vector<glm::vec4> grid = conformance::readVoxelGrid(ctx, *renderer.vxgi().grid());
    std::vector<bool> occupied(grid.size());
    for (size_t i = 0; i < grid.size(); ++i) occupied[i] = grid[i].a > 0.0f;
    return occupied;
}

size_t layerCount(const std::vector<bool>& occupied, uint32_t y) {
    size_t n = 0;
    for (uint32_t z = 0; z < kVoxels; ++z)
        for (uint32_t x = 0; x < kVoxels; ++x) n += occupied[(size_t(z) * kVoxels + y) * kVoxels + x];
    return n;
}

class VxgiPointLightTest : public GpuTest {};

TEST_F(VxgiPointLightTest, OccupancyDoesNotDependOnAShadowedPointLight) {
    const scene::Scene dark = closedRoom();
    for (frame::VoxelRaster raster : {frame::VoxelRaster::Conservative, frame::VoxelRaster::Centre}) {
        for (frame::VoxelDraws draws : {frame::VoxelDraws::Three, frame::VoxelDraws::Single}) {
            const char* name = raster == frame::VoxelRaster::Conservative ? "conservative" : "centre";
            const char* scheme = draws == frame::VoxelDraws::Three ? "three draws" : "single draw";
            const std::vector<bool> reference = occupancy(ctx(), shaders(), dark, raster, draws);
            size_t occupiedReference = 0;
            for (bool o : reference) occupiedReference += o;
            const size_t ceiling = layerCount(reference, kVoxels - 1);
            const size_t whole = raster == frame::VoxelRaster::Conservative ? size_t(kVoxels) * kVoxels
                                                                            : size_t(kVoxels - 1) * (kVoxels - 1);
            ASSERT_GE(ceiling, whole) << name << ", " << scheme << ": the lightless ceiling layer";
            for (float y : {0.3f, -0.5f, 0.9f}) {
                scene::Scene lit = dark;
                lit.lights.push_back(pointLight({0.4f, y, -0.2f}, 1.5f));
                const std::vector<bool> got = occupancy(ctx(), shaders(), lit, raster, draws);
                ASSERT_EQ(got.size(), reference.size());
                size_t differ = 0, occupied = 0;
                for (size_t i = 0; i < got.size(); ++i) {
                    differ += got[i] != reference[i];
                    occupied += got[i];
                }
                std::printf("%s, %s, light y %.1f: %zu occupied voxels (without the light %zu), ceiling layer %zu, "
                            "%zu differ\n",
                            name, scheme, y, occupied, occupiedReference, layerCount(got, kVoxels - 1), differ);
                EXPECT_EQ(differ, 0u) << name << ", " << scheme << ", light at y " << y;
            }
        }
    }
}

}  // namespace
}  // namespace idk::test
