// vxgi_memory_test.cpp: the VXGI grid's memory check (frame/vxgi_memory.hpp) inside a renderer that already holds a
// 64^3 grid, with a forced budget of 100 MiB free (IDK_TEST_MEMORY_BUDGET_MIB; 128^3 needs 149.9 MiB with packed
// directional volumes):
//  * the grid it holds is the computed volumes' size, to the byte (the allocator's sizes of the grid's and the
//    directions' images);
//  * the viewer's guard (refuseVxgiChange) reverts a change to 128 and names 64 as the largest that fits; a change
//    that fits, or turning VXGI off, passes untouched;
//  * a frame asked for 128 directly throws VxgiMemoryError and keeps the old grid (same image, 64^3); the next
//    frame at 64 renders with that same grid, not a new one.
// (The CLI side, exit code and message, and the bytes against --json at 64^3 and 128^3: tests/cli/vxgi_memory.sh.)
#include <gtest/gtest.h>

#include <cstdlib>

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
        setenv("IDK_TEST_MEMORY_BUDGET_MIB", "100", 1);
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
    // Free: the forced 100 MiB and the 64^3 grid the resize would release first.
    const VkDeviceSize held = r.vxgi().heldBytes(), free = (VkDeviceSize(100) << 20) + held;
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

}  // namespace
}  // namespace idk::test
