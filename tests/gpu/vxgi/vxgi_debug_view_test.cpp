// vxgi_debug_view_test.cpp: --gi-debug voxels (passes/vxgi_debug_view.cpp) against a CPU walk of the same rays.
// Scene: the closed room of vxgi_frame_test.cpp with walls of different emissive colours and its ceiling panel,
// 64x64 pixels, 64^3 voxels, levels 0 (64^3 cells), 1 and 2 (the directional mips at 32^3 and 16^3).
// After the frame the test reads back the grid and the directional mips the debug pass read, and walks every
// pixel's camera ray (through the pixel centre, from the frame's own view-projection) through the cells of the
// same level in double precision (Amanatides-Woo), stopping at the first cell with coverage > 0.5: level 0 is the
// grid's merged (isotropic) value, level L >= 1 the directional volumes facing the ray weighted by |dir|
// (shared/vxgi_cone.h's vxgiCombine, written out here again). The GPU's alpha is the distance to the middle of the
// ray's stretch in its hit cell: the same hit cell means alpha equals the CPU's middle to fp16 rounding. Cells the
// ray only touches (empty stretch) are skipped on both sides. Asserted per level:
//  * the same hit cell (or a miss on both) on >= 99% of pixels (the rest: rays within float rounding of a face);
//  * on those pixels the GPU's rgb equals the cell's value within fp16 rounding (rel. 2^-10, abs. 1e-4);
//  * most pixels hit (the camera is inside a closed room) and the image is not one colour.
// Also: with --gi-debug off no debug pass runs; with it on exactly one.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <tuple>
#include <string>

#include "render/renderer.hpp"
#include "scene/camera.hpp"
#include "support/gpu_fixture.hpp"
#include "gpu/vxgi/vxgi_room.hpp"
#include "support/placed_quads.hpp"
#include "support/vxgi_cone_oracle.hpp"

namespace idk::test {
namespace {

constexpr uint32_t kSize = 64;
constexpr uint32_t kVoxels = 64;

scene::Scene litRoom() {
    scene::Scene s = closedRoomScene(glm::vec3(4.0f), closedRoomQuads({glm::vec3(0.7f), glm::vec3(0.8f, 0.1f, 0.1f),
                                                                       glm::vec3(0.1f, 0.8f, 0.1f),
                                                                       glm::vec3(0.2f, 0.3f, 0.8f), glm::vec3(0.6f)}));
    // Each wall glows with its own colour (voxel radiance is emission + direct light; there is no light here).
    for (size_t i = 0; i < 5; ++i)
        s.materials[i].emissive = glm::vec3(s.materials[i].baseColorFactor) * (0.5f + 0.1f * float(i));
    return s;
}

// 3 cells of level 2 from the front wall: the camera's own cell is empty there.
scene::CameraView camera() { return closedRoomCamera({0.0f, -0.1f, 0.6f}); }

// One level's cells as the debug view sees them along `dir`.
struct LevelView {
    uint32_t n = 0;
    uint32_t level = 0;
    const ConeGridData* data = nullptr;

    glm::dvec4 cell(glm::ivec3 c, glm::dvec3 dir) const {
        const size_t i = (size_t(c.z) * n + size_t(c.y)) * n + size_t(c.x);
        if (level == 0) return glm::dvec4(data->grid.levels[0][i]);
        auto facing = [&](int axis) {
            const int d = 2 * axis + (dir[axis] >= 0.0 ? 0 : 1);
            return glm::dvec4(data->directions[size_t(d)].levels[level][i]);
        };
        glm::dvec4 v = std::abs(dir.x) * facing(0) + std::abs(dir.y) * facing(1) + std::abs(dir.z) * facing(2);
        if (v.w > 1.0) v /= v.w;
        return v;
    }
};

struct CpuHit {
    bool hit = false;
    glm::ivec3 cell{0};
    glm::dvec3 radiance{0.0};
    double middle = 0.0;  // world distance to the middle of the ray's stretch in the cell
};

// The first cell of `v` along origin + t dir (t >= 0, in world units) with coverage > 0.5.
CpuHit marchOnCpu(const LevelView& v, const passes::VoxelGridBox& box, glm::dvec3 origin, glm::dvec3 dir) {
    const double cellSize = double(box.voxelSize) * box.size / v.n;
    const glm::dvec3 o = (origin - glm::dvec3(box.gridMin)) / cellSize;
    double tIn = 0.0, tOut = 1e30;
    for (int a = 0; a < 3; ++a) {
        if (dir[a] == 0.0) {
            if (o[a] < 0.0 || o[a] >= v.n) return {};
            continue;
        }
        double t0 = -o[a] / dir[a], t1 = (v.n - o[a]) / dir[a];
        if (t0 > t1) std::swap(t0, t1);
        tIn = std::max(tIn, t0);
        tOut = std::min(tOut, t1);
    }
    if (tIn >= tOut) return {};
    const glm::dvec3 p = o + dir * tIn;
    glm::ivec3 c = glm::clamp(glm::ivec3(glm::floor(p)), glm::ivec3(0), glm::ivec3(int(v.n) - 1));
    glm::ivec3 step(0);
    glm::dvec3 tMax(1e30), tDelta(1e30);
    for (int a = 0; a < 3; ++a) {
        if (dir[a] == 0.0) continue;
        step[a] = dir[a] > 0.0 ? 1 : -1;
        tMax[a] = (c[a] + (step[a] > 0 ? 1.0 : 0.0) - o[a]) / dir[a];
        tDelta[a] = 1.0 / std::abs(dir[a]);
    }
    double tCell = tIn;
    while (true) {
        const double tLeave = std::min({tMax.x, tMax.y, tMax.z});
        const glm::dvec4 value = v.cell(c, dir);
        if (tLeave > tCell && value.w > 0.5) return {true, c, glm::dvec3(value), 0.5 * (tCell + tLeave) * cellSize};
        tCell = tLeave;
        int a = tMax.x < tMax.y ? (tMax.x < tMax.z ? 0 : 2) : (tMax.y < tMax.z ? 1 : 2);
        c[a] += step[a];
        tMax[a] += tDelta[a];
        if (c[a] < 0 || c[a] >= int(v.n)) return {};
    }
}

class VxgiDebugViewTest : public GpuTest {};

TEST_F(VxgiDebugViewTest, FirstCoveredCellMatchesCpuWalk) {
    const scene::Scene s = litRoom();
    const scene::CameraView cam = camera();
    {  // off: nothing of the debug view runs
        render::RenderSettings settings;
        settings.output = render::OutputKind::Hdr;
        settings.vxgi.mode = frame::GiMode::Vxgi;
        settings.vxgi.voxels = kVoxels;
        render::Renderer renderer(ctx(), shaders(), settings);
        renderer.setScene(s);
        const render::FrameResult frame = renderer.renderOffscreen(cam, kSize, kSize);
        for (const std::string& pass : frame.passesRun) EXPECT_NE(pass, "vxgi_debug_voxels");
    }
    // The frame's rays: pixel centres through the renderer's view-projection (renderer.cpp), as the shader does.
    const glm::mat4 inverseVp = glm::inverse(scene::projectionMatrix(cam, 1.0f) * scene::viewMatrix(cam));
    for (uint32_t level : {0u, 1u, 2u}) {
        render::RenderSettings settings;
        settings.output = render::OutputKind::Hdr;
        settings.vxgi.mode = frame::GiMode::Vxgi;
        settings.vxgi.voxels = kVoxels;
        settings.vxgi.debug = frame::GiDebug::Voxels;
        settings.vxgi.debugLevel = level;
        render::Renderer renderer(ctx(), shaders(), settings);
        renderer.setScene(s);
        const render::FrameResult frame = renderer.renderOffscreen(cam, kSize, kSize);
        size_t debugPasses = 0;
        for (const std::string& pass : frame.passesRun) debugPasses += pass == "vxgi_debug_voxels";
        EXPECT_EQ(debugPasses, 1u);

        const ConeGridData data = readConeGrid(ctx(), renderer.vxgi());
        const passes::VoxelGridBox box = renderer.vxgi().box();
        const LevelView view{kVoxels >> level, level, &data};
        const double cellSize = double(box.voxelSize) * box.size / view.n;
        size_t same = 0, hits = 0, radianceOk = 0;
        double worstRadiance = 0.0;
        std::set<std::tuple<int, int, int>> colours;
        for (uint32_t y = 0; y < kSize; ++y) {
            for (uint32_t x = 0; x < kSize; ++x) {
                const glm::vec2 ndc = (glm::vec2(x, y) + 0.5f) / float(kSize) * 2.0f - 1.0f;
                const glm::vec4 h = inverseVp * glm::vec4(ndc, 0.5f, 1.0f);
                const glm::dvec3 origin(cam.position);
                const glm::dvec3 dir = glm::normalize(glm::dvec3(h) / double(h.w) - origin);
                const CpuHit cpu = marchOnCpu(view, box, origin, dir);
                const float* px = &frame.image.pixels[(size_t(y) * kSize + x) * 4];
                const bool gpuHit = px[3] > 0.0f;
                hits += cpu.hit;
                bool match = gpuHit == cpu.hit;
                // The GPU's cell: the one whose stretch has its middle at alpha, to fp16 rounding (2^-11 relative)
                // and float rounding of the GPU's walk (1e-4 of a cell).
                if (match && gpuHit)
                    match = std::abs(double(px[3]) - cpu.middle) <= cpu.middle * 0x1p-10 + 1e-4 * cellSize;
                if (!match) continue;
                ++same;
                const glm::dvec3 gpu(px[0], px[1], px[2]);
                colours.insert({int(gpu.r * 64.0), int(gpu.g * 64.0), int(gpu.b * 64.0)});
                bool ok = true;
                for (int c = 0; c < 3; ++c) {
                    const double d = std::abs(gpu[c] - cpu.radiance[c]);
                    worstRadiance = std::max(worstRadiance, d / std::max(std::abs(cpu.radiance[c]), 1e-3));
                    ok = ok && d <= std::abs(cpu.radiance[c]) * 0x1p-10 + 1e-4;
                }
                radianceOk += ok;
            }
        }
        const size_t total = size_t(kSize) * kSize;
        std::printf("level %u (%u^3 cells): same hit cell on %zu of %zu pixels (%.2f%%), %zu hits; radiance within "
                    "fp16 rounding on %zu of %zu (worst relative difference %.2e); %zu distinct colours\n",
                    level, view.n, same, total, 100.0 * double(same) / double(total), hits, radianceOk, same,
                    worstRadiance, colours.size());
        EXPECT_GE(double(same), 0.99 * double(total)) << "level " << level;
        EXPECT_EQ(radianceOk, same) << "level " << level;
        EXPECT_GT(hits, total * 9 / 10) << "level " << level << ": the camera is inside a closed room";
        EXPECT_GE(colours.size(), 5u) << "level " << level << ": the view should show the walls' colours";
    }
}

}  // namespace
}  // namespace idk::test
