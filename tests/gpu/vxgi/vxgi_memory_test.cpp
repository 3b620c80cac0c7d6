// vxgi_memory_test.cpp: the VXGI grid's memory check (frame/vxgi_memory.hpp) inside a renderer that already holds a
// 64^3 grid, with a forced budget of 80 MiB free (IDK_TEST_MEMORY_BUDGET_MIB; 128^3 needs 165.9 MiB with packed
// directional volumes in one slab, 95.9 MiB in 8 slabs, the least: more than the 80 MiB and the 10.9 MiB of the
// 64^3 grid it would release):
//  * the grid it holds is the computed volumes' size, to the byte (the allocator's sizes of the grid's and the
//    directions' images);
//  * the viewer's guard (refuseVxgiChange) reverts a change to 128 and names 64 as the largest that fits; a change
//    that fits, or turning VXGI off, passes untouched;
//  * a frame asked for 128 directly throws VxgiMemoryError and keeps the old grid (same image, 64^3); the next
//    frame at 64 renders with that same grid, not a new one.
// With 100 MiB free the 128^3 grid renders voxelized in 8 z-slabs (the smallest count that fits), holding the
// computed volumes to the byte. The slab planner (planVoxelSlabs) on its own: the smallest count that fits, a forced
// count, the gl-interop rung's one slab, a lowered maxImageDimension3D (the keys' z extent 2 n / S must fit it: a
// clear refusal naming the grid and the limit instead of createImage's DeviceLimitError), and 512^3 within an 8 GiB
// device with a 1920x1080 frame's other resources.
// (The CLI side, exit code and message, and the bytes against --json at 64^3 and 128^3: tests/cli/vxgi_memory.sh.)
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <string>

#include "frame/vxgi_feature.hpp"
#include "frame/vxgi_memory.hpp"
#include "render/renderer.hpp"
#include "support/gpu_fixture.hpp"
#include "support/placed_quads.hpp"

namespace idk::test {
namespace {

class VxgiMemoryTest : public GpuTest {
protected:
    void SetUp() override {
        GpuTest::SetUp();
        setenv("IDK_TEST_MEMORY_BUDGET_MIB", "80", 1);
    }
    void TearDown() override {
        unsetenv("IDK_TEST_MEMORY_BUDGET_MIB");
        GpuTest::TearDown();
    }
};

scene::Scene floorScene() {
    std::vector<PlacedQuad> q;
    q.push_back(placedQuad({0.02f, -1.0f, 0.01f}, {0, 1, 0}, {0.93f, 0.91f}, {0.8f, 0.8f, 0.8f}));
    scene::Scene s = makePlacedQuadScene(q);
    s.lights.push_back(pointLight({0.2f, 0.6f, 0.1f}, 3.0f));
    return s;
}

TEST_F(VxgiMemoryTest, TooLargeAGridIsRefusedAndTheOldOneKept) {
    render::RenderSettings settings;
    settings.output = render::OutputKind::Hdr;
    settings.pointShadows.maxLights = 0;
    settings.vxgi.mode = frame::GiMode::Vxgi;
    settings.vxgi.voxels = 64;
    render::Renderer r(ctx(), shaders(), settings);
    r.setScene(floorScene());
    scene::CameraView camera;
    camera.position = {0.0f, 0.5f, 2.0f};
    r.renderOffscreen(camera, 16, 16);
    ASSERT_NE(r.vxgi().grid(), nullptr);
    const VkImage grid = r.vxgi().grid()->image;
    const vk::Rung atomics = ctx().ladder("vxgi-atomics").chosen;
    EXPECT_EQ(r.vxgi().heldBytes(), frame::vxgiMemory(ctx(), 64, atomics).volumes);

    frame::VxgiSettings before = settings.vxgi, asked = before;
    asked.voxels = 128;
    const std::string refused = frame::refuseVxgiChange(ctx(), before, asked, r.vxgi().heldBytes());
    EXPECT_NE(refused.find("--voxels 128: the 128^3 VXGI grid needs"), std::string::npos) << refused;
    EXPECT_NE(refused.find(" bytes (in 8 slabs), but"), std::string::npos) << refused;
    // Free: the forced 80 MiB and the 64^3 grid the resize would release first.
    const VkDeviceSize held = r.vxgi().heldBytes(), free = (VkDeviceSize(80) << 20) + held;
    EXPECT_NE(refused.find(" (" + std::to_string(free) + " bytes) free (IDK_TEST_MEMORY_BUDGET_MIB, with the " +
                           std::to_string(held) + " bytes of the grid it replaces)"),
              std::string::npos)
        << refused;
    EXPECT_NE(refused.find("the largest --voxels that fits is 64"), std::string::npos) << refused;
    EXPECT_EQ(asked.voxels, 64u);
    EXPECT_EQ(asked.mode, frame::GiMode::Vxgi);
    frame::VxgiSettings off = before;
    off.mode = frame::GiMode::None;
    off.voxels = 512;
    EXPECT_EQ(frame::refuseVxgiChange(ctx(), before, off, r.vxgi().heldBytes()), "");
    EXPECT_EQ(off.voxels, 512u);  // nothing is allocated with VXGI off: not refused

    r.settings().vxgi.voxels = 128;
    EXPECT_THROW(r.renderOffscreen(camera, 16, 16), frame::VxgiMemoryError);
    ASSERT_NE(r.vxgi().grid(), nullptr);
    EXPECT_EQ(r.vxgi().grid()->image, grid);
    EXPECT_EQ(r.vxgi().grid()->extent.width, 64u);

    r.settings().vxgi.voxels = 64;
    r.renderOffscreen(camera, 16, 16);
    EXPECT_EQ(r.vxgi().grid()->image, grid);
}

TEST_F(VxgiMemoryTest, AGridThatFitsOnlyInSlabsRendersInThem) {
    setenv("IDK_TEST_MEMORY_BUDGET_MIB", "100", 1);
    render::RenderSettings settings;
    settings.output = render::OutputKind::Hdr;
    settings.pointShadows.maxLights = 0;
    settings.vxgi.mode = frame::GiMode::Vxgi;
    settings.vxgi.voxels = 128;
    const vk::Rung atomics = ctx().ladder("vxgi-atomics").chosen;
    const VkDeviceSize budget = VkDeviceSize(100) << 20;
    EXPECT_GT(frame::vxgiMemory(ctx(), 128, atomics, 4).total(), budget);
    EXPECT_LE(frame::vxgiMemory(ctx(), 128, atomics, 8).total(), budget);
    render::Renderer r(ctx(), shaders(), settings);
    r.setScene(floorScene());
    scene::CameraView camera;
    camera.position = {0.0f, 0.5f, 2.0f};
    const render::FrameResult frame = r.renderOffscreen(camera, 16, 16);
    EXPECT_EQ(r.vxgi().slabs(), 8u);
    EXPECT_EQ(r.vxgi().heldBytes(), frame::vxgiMemory(ctx(), 128, atomics, 8).volumes);
    EXPECT_NE(std::find(frame.passesRun.begin(), frame.passesRun.end(), "vxgi_merge slab 7"), frame.passesRun.end());
    // The transient accumulators and keys cover one slab, 128 x 128 x 16 voxels: 7/8 of the grid's fewer voxels, each
    // of 8 (float-add) or 7 (r32ui) accumulator words and 2 key words.
    EXPECT_EQ(frame::vxgiMemory(ctx(), 128, atomics, 1).accumulators -
                  frame::vxgiMemory(ctx(), 128, atomics, 8).accumulators,
              VkDeviceSize(128) * 128 * (128 - 16) * 4 * (atomics == vk::Rung::Native ? 10 : 9));
}

TEST_F(VxgiMemoryTest, SlabPlanner) {
    // A synthetic cost: 100 bytes of volumes, 800 / S of accumulators.
    auto memory = [](uint32_t s) { return frame::VxgiMemory{100, 800 / s}; };
    auto plan = [&](uint32_t voxels, vk::Rung rung, uint32_t forced, uint32_t limit, VkDeviceSize available) {
        return frame::planVoxelSlabs(voxels, rung, forced, limit, available, memory, "the budget", {});
    };
    auto refusal = [&](uint32_t voxels, vk::Rung rung, uint32_t forced, uint32_t limit, VkDeviceSize available) {
        try {
            plan(voxels, rung, forced, limit, available);
        } catch (const frame::VxgiMemoryError& e) {
            return std::string(e.what());
        }
        return std::string("(not refused)");
    };
    EXPECT_EQ(plan(512, vk::Rung::Native, 0, 2048, 900), 1u);  // fits whole: small grids pay nothing
    EXPECT_EQ(plan(512, vk::Rung::Native, 0, 2048, 300), 4u);  // 100 + 200
    EXPECT_EQ(plan(512, vk::Rung::Native, 2, 2048, 900), 2u);  // forced
    EXPECT_EQ(plan(512, vk::Rung::Fallback, 0, 2048, 200), 8u);
    EXPECT_NE(refusal(512, vk::Rung::Native, 0, 2048, 199)
                  .find("(200 bytes): volumes 100 + accumulators 100 bytes (in 8 slabs), but the device-local memory "
                        "budget has the budget; no --voxels fits"),
              std::string::npos)
        << refusal(512, vk::Rung::Native, 0, 2048, 199);
    EXPECT_NE(refusal(512, vk::Rung::Native, 2, 2048, 400).find("(in 2 slabs)"), std::string::npos);
    // gl-interop: one slab (its GL sums cover the grid).
    EXPECT_EQ(plan(64, vk::Rung::GlInterop, 0, 2048, 900), 1u);
    EXPECT_NE(refusal(64, vk::Rung::GlInterop, 0, 2048, 899).find("(in 1 slab)"), std::string::npos);
    EXPECT_NE(refusal(64, vk::Rung::GlInterop, 2, 2048, 900).find("--gi-slabs 2: the gl-interop rung"),
              std::string::npos);
    // A lowered maxImageDimension3D: the keys' z extent 2 n / S must fit it, the grid's n too.
    EXPECT_EQ(plan(512, vk::Rung::Native, 0, 512, 900), 2u);  // 512 x 512 x 512 keys
    EXPECT_EQ(plan(512, vk::Rung::Native, 0, 600, 900), 2u);
    EXPECT_EQ(plan(512, vk::Rung::Native, 0, 1024, 900), 1u);
    EXPECT_EQ(refusal(512, vk::Rung::Native, 1, 1000, 900),
              "--voxels 512: the 512^3 VXGI grid in 1 slab: its depth keys (512 x 512 x 1024 texels) exceed the "
              "device's maxImageDimension3D (1000)");
    EXPECT_EQ(refusal(512, vk::Rung::Native, 0, 500, 900),
              "--voxels 512: the 512^3 VXGI grid exceeds the device's maxImageDimension3D (500)");
    EXPECT_EQ(refusal(64, vk::Rung::GlInterop, 0, 100, 900),
              "--voxels 64: the 64^3 VXGI grid: its depth keys (64 x 64 x 128 texels) exceed the device's "
              "maxImageDimension3D (100)");

    // 512^3 on an 8 GiB device, with the other resources of a 1920x1080 frame (kFrameMiB: idk render
    // scenes/cornell_box.gltf --size 1920x1080 --gi vxgi --voxels 64 --json measured 130.7 MiB of device memory, 10.9
    // of them the "vxgi" category; its transient accumulators, 10.1 MiB, are left in): the check picks 2 slabs
    // (8036.9 MiB); one slab (10596.9 MiB) does not fit.
    constexpr VkDeviceSize kFrameMiB = 120;
    const vk::Rung atomics = ctx().ladder("vxgi-atomics").chosen;
    setenv("IDK_TEST_MEMORY_BUDGET_MIB", std::to_string(8192 - kFrameMiB).c_str(), 1);
    const uint32_t slabs = frame::checkVxgiMemory(ctx(), 512, atomics);
    EXPECT_LE(frame::vxgiMemory(ctx(), 512, atomics, slabs).total() + (kFrameMiB << 20), VkDeviceSize(8192) << 20);
    EXPECT_GT(frame::vxgiMemory(ctx(), 512, atomics, 1).total(), VkDeviceSize(8192) << 20);
    EXPECT_GT(slabs, 1u);
}

}  // namespace
}  // namespace idk::test
