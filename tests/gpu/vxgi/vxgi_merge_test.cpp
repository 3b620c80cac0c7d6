// vxgi_merge_test.cpp: the merge's skip of voxels that stay empty (shaders_glsl/vxgi/merge.comp.glsl) and the level-1
// mip's skip of the cells the merge's mask marks empty (mip.comp.glsl) change no bit. The closed room with its standing
// quad at 64^3 voxels, the grid following the camera (--gi-grid camera): one renderer draws a frame, then moves the
// camera by one grid step along x and y, so the scene shifts by 8 voxels in the grid (voxels turn empty, others turn
// occupied, most stay empty); that frame's grid and all levels of the six directional volumes must equal, bit for
// bit, those of a fresh renderer's first frame at the second position (whose merge stores every voxel). On the
// float-add rung (lavapipe's native one), the r32ui fallback rung and the gl-interop rung (llvmpipe's GL). The merge's
// skip rests on an invariant, checked on the read-back volumes: a voxel whose grid bits are all zero has all-zero bits
// in every direction. And the mip chain, skips included, is checked against a CPU mip of the read-back levels
// (mip.comp.glsl's composite: each level from the GPU's level below; zero exactly where the CPU's is zero, else within
// one storage step of the directions' format: fp16, or 10/11-bit floats and 1/255 for packed volumes).
// Voxelization in z-slabs (frame/vxgi_memory.hpp, --gi-slabs): the same room voxelized in 2 and 4 slabs gives the
// grid and every level of the six directional volumes of 1 slab, bit for bit, on the float-add and the r32ui rungs
// (the gl-interop rung voxelizes in one slab only: VxgiMemoryTest). The room's walls cross every slab boundary.
// Touched-voxel lists (engine/passes/vxgi_merge.cpp): the moving renderer draws four frames (there, moved, back,
// moved again), so the second to the fourth merge only the voxels of the last frame's list and their own; the fourth
// is the one compared with the fresh renderer's. Each list holds exactly its frame's occupied voxels (its append
// count equals the read-back grid's occupied voxels). On the float-add rung also in 4 slabs, and with lists of
// 2000 entries, which every frame overflows (each merge then visits every voxel); on the r32ui rung also in 2 slabs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <string>
#include <memory>

#include "conformance/voxel_oracle.hpp"
#include "frame/vxgi_feature.hpp"
#include "render/renderer.hpp"
#include "support/gpu_fixture.hpp"
#include "support/vxgi_cone_oracle.hpp"
#include "vk/transfer.hpp"
#include "vxgi_room.hpp"

namespace idk::test {
namespace {

constexpr uint32_t kVoxels = 64;

render::RenderSettings mergeSettings() {
    render::RenderSettings s;
    s.output = render::OutputKind::Hdr;
    s.pointShadows.maxLights = 0;
    s.vxgi.mode = frame::GiMode::Vxgi;
    s.vxgi.voxels = kVoxels;
    s.vxgi.grid = frame::VoxelGridPlacement::Camera;
    return s;
}

scene::Scene mergeScene() {
    scene::Scene s = closedRoomScene(glm::vec3(4.0f), closedRoomWithStandingQuad());
    s.lights.push_back(pointLight({0.2f, 0.4f, 0.1f}, 2.0f));
    return s;
}

size_t differingWords(const VoxelVolumeData& a, const VoxelVolumeData& b) {
    size_t n = 0;
    for (size_t l = 0; l < a.levels.size(); ++l) {
        if (a.levels[l].size() != b.levels[l].size()) return SIZE_MAX;
        for (size_t i = 0; i < a.levels[l].size(); ++i)
            for (int k = 0; k < 4; ++k) n += std::memcmp(&a.levels[l][i][k], &b.levels[l][i][k], sizeof(float)) != 0;
    }
    return n;
}

size_t occupied(const std::vector<glm::vec4>& grid) {
    size_t n = 0;
    for (const glm::vec4& v : grid) n += v.a > 0.0f;
    return n;
}

glm::vec4 over(glm::vec4 front, glm::vec4 back) { return front + (1.0f - front.a) * back; }

// Cells of levels >= 1 that differ from the CPU mip of the level below (zero where it is not, or more than an fp16
// step away); `zeros` counts the CPU's all-zero cells (the skipped ones among them at level 1).
size_t mipMismatches(const ConeGridData& g, size_t& zeros) {
    size_t bad = 0;
    zeros = 0;
    for (uint32_t d = 0; d < 6; ++d) {
        const int axis = int(d / 2);
        const bool positive = (d & 1u) == 0u;
        const VoxelVolumeData& v = g.directions[d];
        for (size_t level = 1; level < v.levels.size(); ++level) {
            const int n = int(v.size >> level), m = int(v.size >> (level - 1));
            auto at = [&](glm::ivec3 c) {
                return v.levels[level - 1][(size_t(c.z) * m + size_t(c.y)) * m + size_t(c.x)];
            };
            for (int z = 0; z < n; ++z)
                for (int y = 0; y < n; ++y)
                    for (int x = 0; x < n; ++x) {
                        glm::ivec3 step(0), u(0), w(0);
                        step[axis] = 1;
                        u[(axis + 1) % 3] = 1;
                        w[(axis + 2) % 3] = 1;
                        glm::vec4 sum(0.0f);
                        for (int i = 0; i < 4; ++i) {
                            const glm::ivec3 c = glm::ivec3(x, y, z) * 2 + u * (i & 1) + w * (i >> 1);
                            sum += positive ? over(at(c), at(c + step)) : over(at(c + step), at(c));
                        }
                        const glm::vec4 cpu = sum * 0.25f;
                        const glm::vec4 gpu = v.levels[level][(size_t(z) * n + size_t(y)) * n + size_t(x)];
                        const bool cpuZero = cpu == glm::vec4(0.0f);
                        zeros += cpuZero;
                        if (cpuZero) {
                            bad += gpu != glm::vec4(0.0f);
                            continue;
                        }
                        // One storage step of the directions' format (the GPU rounds its float composite).
                        const glm::vec4 ulp = conformance::directionStep(g.directionFormat, cpu);
                        for (int k = 0; k < 4; ++k)
                            if (std::abs(gpu[k] - cpu[k]) > ulp[k] + 1e-7f) {
                                ++bad;
                                break;
                            }
                    }
        }
    }
    return bad;
}

// Voxels whose grid bits are all zero but some direction's are not (the skips' premise: there are none).
size_t zeroGridNonzeroDirections(const ConeGridData& g) {
    size_t n = 0;
    const std::vector<glm::vec4>& grid = g.grid.levels[0];
    for (size_t i = 0; i < grid.size(); ++i) {
        uint32_t bits[4];
        std::memcpy(bits, &grid[i], sizeof(bits));
        if (bits[0] | bits[1] | bits[2] | bits[3]) continue;
        for (uint32_t d = 0; d < 6; ++d) {
            std::memcpy(bits, &g.directions[d].levels[0][i], sizeof(bits));
            if (bits[0] | bits[1] | bits[2] | bits[3]) {
                ++n;
                break;
            }
        }
    }
    return n;
}

// The list's append count (passes::voxelListBytes; word 0).
uint32_t listCount(vk::Context& ctx, const vk::Buffer* list) {
    return list ? vk::downloadBuffer<uint32_t>(ctx, *list, 1)[0] : 0u;
}

// `slabs`: --gi-slabs; `capacity`: the touched-voxel lists' (0: the default, which the room fits).
void expectIncrementalEqualsFull(vk::Context& ctx, vk::ShaderLibrary& shaders, const char* rung, uint32_t slabs = 1,
                                 uint32_t capacity = 0) {
    const scene::Scene scene = mergeScene();
    const glm::vec3 start(0.05f, -0.1f, 0.3f);
    ConeGridData first, moved, fresh;
    passes::VoxelGridBox boxFirst, boxMoved, boxFresh;
    glm::vec3 end{};
    render::RenderSettings settings = mergeSettings();
    settings.vxgi.slabs = slabs;
    const bool lists = ctx.ladder("vxgi-atomics").chosen != vk::Rung::GlInterop;  // that rung keeps no lists
    {
        render::Renderer r(ctx, shaders, settings);
        r.setScene(scene);
        r.vxgi().setVoxelListCapacity(capacity);
        // Four frames, the camera moving there and back: the second merges from the first's list, the third and the
        // fourth from lists of a list-merged frame. The third's and the fourth's grids are compared.
        for (int frameIndex = 0; frameIndex < 3; ++frameIndex) {
            glm::vec3 at = start;
            if (frameIndex == 1) {
                const float step = frame::voxelGridStep(r.vxgi().box());
                end = start + glm::vec3(step, -step, 0.0f);
                at = end;
            }
            r.renderOffscreen(closedRoomCamera(at), 16, 16);
        }
        first = readConeGrid(ctx, r.vxgi());
        boxFirst = r.vxgi().box();
        const uint32_t firstCount = listCount(ctx, r.vxgi().voxelList());
        r.renderOffscreen(closedRoomCamera(end), 16, 16);
        moved = readConeGrid(ctx, r.vxgi());
        boxMoved = r.vxgi().box();
        // The lists hold each frame's occupied voxels exactly (one append per voxel, in whichever slab), or count
        // past the capacity (then every voxel was merged).
        if (lists) {
            EXPECT_EQ(listCount(ctx, r.vxgi().voxelList(true)), firstCount) << rung;
            const uint32_t count = listCount(ctx, r.vxgi().voxelList());
            if (capacity == 0) {
                EXPECT_EQ(firstCount, occupied(first.grid.levels[0])) << rung;
                EXPECT_EQ(count, occupied(moved.grid.levels[0])) << rung;
            } else {
                EXPECT_GT(firstCount, capacity) << rung << ": the lists should overflow";
                EXPECT_GT(count, capacity) << rung << ": the lists should overflow";
            }
        } else {
            EXPECT_EQ(r.vxgi().voxelList(), nullptr) << rung;
        }
    }
    {
        render::Renderer r(ctx, shaders, settings);
        r.setScene(scene);
        r.renderOffscreen(closedRoomCamera(end), 16, 16);
        fresh = readConeGrid(ctx, r.vxgi());
        boxFresh = r.vxgi().box();
    }
    ASSERT_NE(boxFirst.gridMin, boxMoved.gridMin) << rung << ": the move must shift the grid";
    ASSERT_EQ(boxMoved.gridMin, boxFresh.gridMin) << rung;

    // The move exercises every case: voxels turning empty, turning occupied, and staying empty (skipped).
    const std::vector<glm::vec4>& a = first.grid.levels[0];
    const std::vector<glm::vec4>& b = moved.grid.levels[0];
    size_t emptied = 0, filled = 0, stayedEmpty = 0;
    for (size_t i = 0; i < a.size(); ++i) {
        emptied += a[i].a > 0.0f && b[i].a == 0.0f;
        filled += a[i].a == 0.0f && b[i].a > 0.0f;
        stayedEmpty += a[i].a == 0.0f && b[i].a == 0.0f;
    }
    EXPECT_GT(occupied(b), 5000u) << rung << ": the grid should hold the room";
    EXPECT_GT(emptied, 1000u) << rung;
    EXPECT_GT(filled, 1000u) << rung;
    EXPECT_GT(stayedEmpty, a.size() / 2) << rung;

    EXPECT_EQ(zeroGridNonzeroDirections(moved), 0u) << rung;
    size_t zeros = 0;
    EXPECT_EQ(mipMismatches(moved, zeros), 0u) << rung << ": the mip chain against the CPU's";
    EXPECT_GT(zeros, 1000u) << rung << ": empty cells the level-1 mip skips";

    EXPECT_EQ(differingWords(moved.grid, fresh.grid), 0u) << rung << ": grid";
    for (uint32_t d = 0; d < 6; ++d) {
        ASSERT_EQ(moved.directions[d].levels.size(), fresh.directions[d].levels.size());
        EXPECT_EQ(differingWords(moved.directions[d], fresh.directions[d]), 0u)
            << rung << ": directional volume " << d << " (all levels)";
    }
}

class VxgiMergeTest : public GpuTest {};

// The room in 1, 2 and 4 slabs: each fragment lands in the slab of its integer voxel z (voxelize_fragment.glsl), so
// every voxel sees the same fragments in the same draw order as with one slab; the r32ui rung's max is
// order-free anyway, and the float-add rung's sums were bit-identical run to run on lavapipe (the test above).
void expectSlabsGiveOneSlabsGrid(vk::Context& ctx, vk::ShaderLibrary& shaders, const char* rung) {
    const scene::Scene scene = mergeScene();
    const glm::vec3 camera(0.05f, -0.1f, 0.3f);
    auto voxelize = [&](uint32_t slabs) {
        render::RenderSettings settings = mergeSettings();
        settings.vxgi.slabs = slabs;
        render::Renderer r(ctx, shaders, settings);
        r.setScene(scene);
        const render::FrameResult frame = r.renderOffscreen(closedRoomCamera(camera), 16, 16);
        EXPECT_EQ(r.vxgi().slabs(), slabs) << rung;
        // Each slab's passes ran: the last slab's merge is there ("vxgi_merge" alone with one slab).
        const std::string lastMerge = slabs == 1 ? "vxgi_merge" : "vxgi_merge slab " + std::to_string(slabs - 1);
        EXPECT_NE(std::find(frame.passesRun.begin(), frame.passesRun.end(), lastMerge), frame.passesRun.end())
            << rung << ": " << lastMerge;
        return readConeGrid(ctx, r.vxgi());
    };
    const ConeGridData one = voxelize(1);
    const std::vector<glm::vec4>& grid = one.grid.levels[0];
    ASSERT_GT(occupied(grid), 5000u) << rung << ": the grid should hold the room";
    // Occupied voxels on both sides of every slab boundary of 4 slabs (z = 15|16, 31|32, 47|48).
    for (uint32_t z : {15u, 16u, 31u, 32u, 47u, 48u}) {
        size_t inSlice = 0;
        const size_t slice = size_t(kVoxels) * kVoxels;
        for (size_t i = z * slice; i < (z + 1) * slice; ++i) inSlice += grid[i].a > 0.0f;
        EXPECT_GT(inSlice, 50u) << rung << ": z " << z;
    }
    for (uint32_t slabs : {2u, 4u}) {
        const ConeGridData sliced = voxelize(slabs);
        EXPECT_EQ(differingWords(sliced.grid, one.grid), 0u) << rung << ": grid, " << slabs << " slabs";
        for (uint32_t d = 0; d < 6; ++d) {
            ASSERT_EQ(sliced.directions[d].levels.size(), one.directions[d].levels.size());
            EXPECT_EQ(differingWords(sliced.directions[d], one.directions[d]), 0u)
                << rung << ": directional volume " << d << " (all levels), " << slabs << " slabs";
        }
    }
}

TEST_F(VxgiMergeTest, SkippingEmptyVoxelsGivesTheFullMergeBitForBit) {
    ASSERT_EQ(ctx().ladder("vxgi-atomics").chosen, vk::Rung::Native) << "lavapipe has float image atomic add";
    ASSERT_EQ(ctx().ladder("vxgi-volume-format").chosen, vk::Rung::Native) << "lavapipe stores B10G11R11 and R8";
    expectIncrementalEqualsFull(ctx(), shaders(), "float-add rung");
    expectIncrementalEqualsFull(ctx(), shaders(), "float-add rung", 4);
    // Lists of 2000 entries: each frame's overflows, its merge and the next frame's visit every voxel.
    expectIncrementalEqualsFull(ctx(), shaders(), "float-add rung", 2, 2000);
}

// A context of its own with `ladder` ("vxgi-atomics" unless named) forced to `rung`.
void expectIncrementalEqualsFullOn(vk::Rung rung, const char* what, const char* ladder = "vxgi-atomics") {
    vk::ContextDesc desc = sharedContext().desc();
    desc.validation = true;
    desc.probeGlInterop = rung == vk::Rung::GlInterop;
    desc.forcedRungs = {vk::RungForce{ladder, rung}};
    auto ctx = std::make_unique<vk::Context>(desc);
    ASSERT_EQ(ctx->ladder(ladder).chosen, rung) << what << " must be forcible on lavapipe + llvmpipe";
    {
        vk::ShaderLibrary shaders(*ctx);
        expectIncrementalEqualsFull(*ctx, shaders, what);
        if (rung == vk::Rung::Fallback && std::string(ladder) == "vxgi-atomics")
            expectIncrementalEqualsFull(*ctx, shaders, what, 2);
    }
    ctx->waitIdle();
    EXPECT_EQ(ctx->validationErrors(), 0u);
    for (const std::string& m : ctx->validationMessages()) ADD_FAILURE() << m;
}

TEST_F(VxgiMergeTest, SkippingEmptyVoxelsGivesTheFullMergeBitForBitOnTheUintRung) {
    expectIncrementalEqualsFullOn(vk::Rung::Fallback, "r32ui rung");
}

// The RGBA16F directional volumes ("vxgi-volume-format" fallback: one image per direction, coverage in alpha).
TEST_F(VxgiMergeTest, SkippingEmptyVoxelsGivesTheFullMergeBitForBitWithRgba16fDirections) {
    expectIncrementalEqualsFullOn(vk::Rung::Fallback, "RGBA16F directions", "vxgi-volume-format");
}

TEST_F(VxgiMergeTest, SkippingEmptyVoxelsGivesTheFullMergeBitForBitOnTheGlRung) {
    expectIncrementalEqualsFullOn(vk::Rung::GlInterop, "gl-interop rung");
}

TEST_F(VxgiMergeTest, SlabsGiveTheOneSlabGridBitForBit) {
    ASSERT_EQ(ctx().ladder("vxgi-atomics").chosen, vk::Rung::Native) << "lavapipe has float image atomic add";
    expectSlabsGiveOneSlabsGrid(ctx(), shaders(), "float-add rung");
}

TEST_F(VxgiMergeTest, SlabsGiveTheOneSlabGridBitForBitOnTheUintRung) {
    vk::ContextDesc desc = sharedContext().desc();
    desc.validation = true;
    desc.forcedRungs = {vk::RungForce{"vxgi-atomics", vk::Rung::Fallback}};
    auto ctx = std::make_unique<vk::Context>(desc);
    ASSERT_EQ(ctx->ladder("vxgi-atomics").chosen, vk::Rung::Fallback);
    {
        vk::ShaderLibrary shaders(*ctx);
        expectSlabsGiveOneSlabsGrid(*ctx, shaders, "r32ui rung");
    }
    ctx->waitIdle();
    EXPECT_EQ(ctx->validationErrors(), 0u);
    for (const std::string& m : ctx->validationMessages()) ADD_FAILURE() << m;
}

}  // namespace
}  // namespace idk::test
