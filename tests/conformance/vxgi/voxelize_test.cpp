// voxelize_test.cpp: the VXGI voxelization passes against the CPU voxelizer (voxel_oracle.hpp) on a 64^3 grid over
// a scene of quads: an open box of six walls (gaps at the edges so no two walls share a voxel), an emissive
// ceiling, a tilted double-sided quad inside, and two parallel quads 0.01 apart that land in the same voxels (two
// fragments per voxel: the mean and the max differ there). One unshadowed point light.
//  * Native rung (float atomic add + count): occupancy agrees with the oracle on >= 99.5% of the voxels either
//    marks (the oracle's tie-free design makes it 100% here: every mismatch is reported); each occupied voxel's
//    rgb is the oracle's MEAN of its fragments within 0.2% (+1e-5); empty voxels are all-zero.
//  * Portable rung (three r32ui + max, a context with forceFallbackRungs): the same against the oracle's MAX.
//  * Both rungs give the same grid (within 0.1%) on the voxels holding one fragment.
//  (These three use --gi-raster centre, the oracle's thin voxelization.)
//  * Thin wall, conservative raster (the "conservative-raster" ladder; geometry-shader dilation on lavapipe): a
//    wall one voxel thin whose edges stop inside voxels: every voxel column along its normal that the wall touches
//    holds a wall voxel (no holes), and no column it does not touch does. Centre raster misses the edge columns.
#include <gtest/gtest.h>

#include <glm/gtc/packing.hpp>

#include <cmath>
#include <cstring>

#include "render/renderer.hpp"
#include "support/gpu_fixture.hpp"
#include "vk/transfer.hpp"
#include "voxel_oracle.hpp"

namespace idk::test {
namespace {

constexpr uint32_t kVoxels = 64;
constexpr double kRelTolerance = 2e-3, kAbsTolerance = 1e-5;

struct TestScene {
    std::vector<PlacedQuad> quads;
    std::vector<glm::vec3> emissive;
    OracleLight light{{0.2, 0.6, 0.1}, {3.0, 3.0, 3.0}};
};

PlacedQuad quad(glm::vec3 centre, glm::vec3 normal, glm::vec2 half, glm::vec3 color, bool doubleSided = false) {
    PlacedQuad q;
    q.centre = centre;
    q.normal = glm::normalize(normal);
    q.halfSize = half;
    q.baseColor = color;
    q.doubleSided = doubleSided;
    return q;
}

TestScene makeTestScene() {
    TestScene t;
    // The walls lie on the scene bounds [-1, 1]^3 (voxel centres, fitVoxelGrid's half-voxel margin); their
    // edges stop short of the corners at coordinates that are no voxel centre.
    t.quads.push_back(quad({0.0f, -1.0f, 0.0f}, {0, 1, 0}, {0.83f, 0.81f}, {0.8f, 0.8f, 0.8f}));       // floor
    t.quads.push_back(quad({0.05f, 1.0f, -0.02f}, {0, -1, 0}, {0.71f, 0.77f}, {0.9f, 0.9f, 0.9f}));    // ceiling
    t.quads.push_back(quad({-1.0f, 0.02f, 0.03f}, {1, 0, 0}, {0.74f, 0.69f}, {0.8f, 0.1f, 0.1f}));     // left
    t.quads.push_back(quad({1.0f, -0.03f, 0.01f}, {-1, 0, 0}, {0.67f, 0.73f}, {0.1f, 0.8f, 0.1f}));    // right
    t.quads.push_back(quad({0.01f, 0.02f, -1.0f}, {0, 0, 1}, {0.79f, 0.72f}, {0.7f, 0.7f, 0.6f}));     // back
    t.quads.push_back(quad({-0.02f, 0.04f, 1.0f}, {0, 0, -1}, {0.76f, 0.7f}, {0.5f, 0.6f, 0.7f}));     // front
    t.quads.push_back(quad({0.1f, -0.2f, 0.15f}, {0.3f, 0.8f, 0.45f}, {0.4f, 0.3f}, {0.2f, 0.7f, 0.3f}, true));
    t.quads.push_back(quad({-0.3f, 0.30f, -0.2f}, {0, 1, 0}, {0.23f, 0.21f}, {0.9f, 0.2f, 0.2f}));     // thin pair
    t.quads.push_back(quad({-0.3f, 0.31f, -0.2f}, {0, 1, 0}, {0.23f, 0.21f}, {0.1f, 0.3f, 0.9f}));
    t.emissive.assign(t.quads.size(), glm::vec3(0.0f));
    t.emissive[1] = {1.5f, 1.2f, 0.9f};  // the ceiling glows
    return t;
}

scene::Scene toScene(const TestScene& t) {
    scene::Scene s = makePlacedQuadScene(t.quads);
    for (size_t i = 0; i < t.quads.size(); ++i) {
        s.materials[i].metallic = 0.0f;
        s.materials[i].emissive = t.emissive[i];
    }
    s.lights.push_back(pointLight(glm::vec3(t.light.position), float(t.light.intensity.x)));
    return s;
}

// The grid left in GENERAL layout by the frame, as RGBA floats (x fastest).
std::vector<glm::vec4> readGrid(vk::Context& ctx, const vk::Image& grid) {
    const size_t voxels = size_t(grid.extent.width) * grid.extent.height * grid.extent.depth;
    vk::BufferDesc desc;
    desc.size = voxels * 8;
    desc.memory = vk::MemoryUsage::Readback;
    desc.name = "voxel grid readback";
    vk::Buffer staging = ctx.createBuffer(desc);
    ctx.runImmediate([&](VkCommandBuffer cmd) {
        vk::transitionImage(cmd, grid, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
        VkBufferImageCopy copy{};
        copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        copy.imageExtent = grid.extent;
        vkCmdCopyImageToBuffer(cmd, grid.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, staging.buffer, 1, &copy);
        vk::transitionImage(cmd, grid, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL);
    });
    std::vector<uint16_t> halves(voxels * 4);
    vk::downloadBuffer(ctx, staging, halves.data(), desc.size);
    ctx.destroy(staging);
    std::vector<glm::vec4> out(voxels);
    for (size_t i = 0; i < voxels; ++i)
        for (int c = 0; c < 4; ++c) out[i][c] = glm::unpackHalf1x16(halves[i * 4 + c]);
    return out;
}

struct GridResult {
    vk::Rung rung;
    std::vector<glm::vec4> grid;
    passes::VoxelGridBox box;
};

GridResult voxelize(vk::Context& ctx, vk::ShaderLibrary& shaders, const TestScene& t,
                    frame::VoxelRaster raster = frame::VoxelRaster::Centre) {
    render::RenderSettings settings;
    settings.output = render::OutputKind::Hdr;
    settings.pointShadows.maxLights = 0;  // the oracle has no shadows
    settings.vxgi.mode = frame::GiMode::Vxgi;
    settings.vxgi.voxels = kVoxels;
    settings.vxgi.raster = raster;  // Centre: the thin voxelization the oracle computes
    render::Renderer renderer(ctx, shaders, settings);
    renderer.setScene(toScene(t));
    scene::CameraView camera;
    camera.position = {0.0f, 0.0f, 0.9f};
    renderer.renderOffscreen(camera, 16, 16);
    GridResult r;
    r.rung = ctx.ladder("vxgi-atomics").chosen;
    const vk::Image* grid = renderer.vxgi().grid();
    EXPECT_NE(grid, nullptr);
    if (grid) r.grid = readGrid(ctx, *grid);
    r.box = renderer.vxgi().box();
    return r;
}

// Compares a GPU grid with the oracle: `useMax` picks the oracle's max (r32ui rung) or mean (float-add rung).
void expectMatchesOracle(const GridResult& r, const TestScene& t, bool useMax) {
    const std::vector<OracleVoxel> oracle = voxelizeOnCpu(t.quads, t.emissive, {t.light}, r.box);
    ASSERT_EQ(r.grid.size(), oracle.size());
    size_t either = 0, agree = 0, compared = 0, valueFailures = 0, multi = 0, ambiguous = 0;
    for (size_t i = 0; i < oracle.size(); ++i) {
        const OracleVoxel& o = oracle[i];
        const glm::vec4& g = r.grid[i];
        if (o.ambiguous) {
            ++ambiguous;
            continue;
        }
        const bool gpu = g.a > 0.0f, cpu = o.count > 0;
        if (!gpu && !cpu) {
            EXPECT_EQ(g, glm::vec4(0.0f)) << "empty voxel " << i << " is not zero";
            continue;
        }
        ++either;
        if (gpu != cpu) continue;
        ++agree;
        EXPECT_EQ(g.a, 1.0f) << "coverage of voxel " << i;
        multi += o.count > 1;
        const glm::dvec3 want = useMax ? o.max : o.sum / double(o.count);
        for (int c = 0; c < 3; ++c) {
            const double err = std::abs(double(g[c]) - want[c]);
            if (err > kRelTolerance * want[c] + kAbsTolerance && valueFailures++ < 10)
                ADD_FAILURE() << "voxel " << i << " channel " << c << ": gpu " << g[c] << ", oracle " << want[c];
        }
        ++compared;
    }
    const double agreement = double(agree) / double(either);
    std::printf("%s rung: %zu occupied voxels (oracle or GPU), agreement %.4f%%, %zu voxels with 2+ fragments, "
                "%zu tie voxels left out, %zu value failures\n",
                vk::rungName(r.rung), either, 100.0 * agreement, multi, ambiguous, valueFailures);
    EXPECT_GE(agreement, 0.995);
    EXPECT_GT(compared, 10000u) << "the scene should cover many voxels";
    EXPECT_GT(multi, 50u) << "the thin pair should put two fragments in some voxels";
    EXPECT_LT(ambiguous, either / 100) << "the scene is meant to avoid ties";
    EXPECT_EQ(valueFailures, 0u);
}

class VoxelizeTest : public GpuTest {};

TEST_F(VoxelizeTest, RungsMatchCpuVoxelizer) {
    const TestScene t = makeTestScene();
    GridResult native = voxelize(ctx(), shaders(), t);
    expectMatchesOracle(native, t, native.rung == vk::Rung::Fallback);

    vk::ContextDesc desc = ctx().desc();
    desc.forceFallbackRungs = true;
    GridResult fallback;
    uint32_t fallbackErrors = 0;
    {
        vk::Context fallbackCtx(desc);
        vk::ShaderLibrary fallbackShaders(fallbackCtx);
        fallback = voxelize(fallbackCtx, fallbackShaders, t);
        fallbackCtx.waitIdle();
        fallbackErrors = fallbackCtx.validationErrors();
    }
    EXPECT_EQ(fallbackErrors, 0u) << "validation errors on the fallback context";
    ASSERT_EQ(fallback.rung, vk::Rung::Fallback);
    expectMatchesOracle(fallback, t, true);

    if (native.rung != vk::Rung::Native) GTEST_SKIP() << "device lacks float image atomics: only the fallback ran";
    const std::vector<OracleVoxel> oracle = voxelizeOnCpu(t.quads, t.emissive, {t.light}, native.box);
    size_t single = 0, differing = 0, identical = 0;
    for (size_t i = 0; i < oracle.size(); ++i) {
        if (oracle[i].count != 1 || oracle[i].ambiguous) continue;
        ++single;
        identical += std::memcmp(&native.grid[i], &fallback.grid[i], sizeof(glm::vec4)) == 0;
        for (int c = 0; c < 4; ++c)  // the two fragment shaders are compiled apart: allow one fp16 rounding step
            if (std::abs(native.grid[i][c] - fallback.grid[i][c]) > 1e-3f * std::abs(fallback.grid[i][c])) {
                ++differing;
                break;
            }
    }
    std::printf("one-fragment voxels: %zu, bit-identical across rungs: %zu\n", single, identical);
    EXPECT_EQ(differing, 0u) << "of " << single << " one-fragment voxels";
}

// A wall (normal +x, one voxel thin) inside the open box, its edges stopping inside voxels (not at their centres).
// Over the voxel columns along x (inner ones, away from the box's walls) counts those the wall's rectangle touches
// at all, those of them holding a wall voxel (the wall's x layer or a neighbour), and untouched ones holding one.
TEST_F(VoxelizeTest, ThinWallHasNoHolesWithConservativeRaster) {
    TestScene t = makeTestScene();
    t.quads.resize(6);  // the open box's walls only
    t.quads.push_back(quad({0.013f, -0.012f, 0.021f}, {1, 0, 0}, {0.803f, 0.689f}, {0.8f, 0.8f, 0.8f}, true));
    t.emissive.assign(t.quads.size(), glm::vec3(0.0f));
    const PlacedQuad& wall = t.quads.back();
    for (frame::VoxelRaster raster : {frame::VoxelRaster::Centre, frame::VoxelRaster::Conservative}) {
        GridResult r = voxelize(ctx(), shaders(), t, raster);
        ASSERT_EQ(r.grid.size(), size_t(kVoxels) * kVoxels * kVoxels);
        const scene::Aabb wallBounds = makePlacedQuadScene({wall}).bounds;  // the quad's extent in y and z
        const glm::dvec3 vmin(wallBounds.min), vmax(wallBounds.max);
        const int layer = int(std::floor((double(wall.centre.x) - r.box.gridMin.x) / r.box.voxelSize));
        size_t touched = 0, covered = 0, outside = 0;
        for (int z = 1; z + 1 < int(kVoxels); ++z)
            for (int y = 1; y + 1 < int(kVoxels); ++y) {
                const double y0 = r.box.gridMin.y + y * double(r.box.voxelSize), y1 = y0 + r.box.voxelSize;
                const double z0 = r.box.gridMin.z + z * double(r.box.voxelSize), z1 = z0 + r.box.voxelSize;
                const bool touches = y1 > vmin.y && y0 < vmax.y && z1 > vmin.z && z0 < vmax.z;
                bool holds = false;
                for (int x = layer - 1; x <= layer + 1; ++x)
                    holds = holds || r.grid[(size_t(z) * kVoxels + y) * kVoxels + x].a > 0.0f;
                touched += touches;
                covered += touches && holds;
                outside += !touches && holds;
            }
        std::printf("thin wall, %s raster: %zu columns touched, %zu hold a wall voxel, %zu untouched columns do\n",
                    raster == frame::VoxelRaster::Centre ? "centre" : "conservative", touched, covered, outside);
        EXPECT_EQ(outside, 0u);
        if (raster == frame::VoxelRaster::Conservative)
            EXPECT_EQ(covered, touched) << "holes in the thin wall";
        else
            EXPECT_LT(covered, touched) << "the test's wall must have edge columns centre raster misses";
    }
}

}  // namespace
}  // namespace idk::test
