// vxgi_gl_rung_test.cpp: the GL-interop rung of "vxgi-atomics" (passes/vxgi_gl_accumulate.hpp), forced with
// --rung vxgi-atomics=gl-interop on llvmpipe, against the device's other rungs on the same scene (64^3 voxels): an
// open box of quads, a tilted quad and three parallel quads 0.0002 apart (three fragments in the same voxels, all
// within the front-most rule's tolerance of 1/64 voxel, so all kept: their sum depends on the order), lit by an
// emissive ceiling and a point light.
//  * Grid: the same occupied voxels as the native float-atomics rung, each voxel's rgba within one fp16 step
//    (relative 2^-10, + 1e-6): both are the mean of the same fragments, summed in another order. On voxels holding
//    one fragment (count 1 in the GL sums) the same within one fp16 step as the portable r32ui rung (max = mean).
//    The GL sums count every fragment the voxelization appended, none dropped.
//  * Overflow: a record buffer too small for the frame reports the dropped fragments (appended - capacity), grows
//    to hold them, and the next frame is whole again (same grid as before the overflow); renderStill renders an
//    overflowed still again, so its grid is whole.
//  * Whole frame with --gi vxgi (64x64, point shadows on, conservative raster): the GL rung's image matches the
//    native rung's within a relative RMSE of 1e-3 (measured: 0, bit-identical: a voxel's two fragments sum the same
//    in either order).
//  * No EGL (IDK_GL_INTEROP=off): the rung is absent with the reason and forcing it is refused.
//  Each context runs with validation (sync validation when IDK_SYNC_VALIDATION=1) and must report no message.
#include <gtest/gtest.h>

#include <glm/gtc/packing.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>

#include "conformance/voxel_oracle.hpp"
#include "passes/vxgi_gl_accumulate.hpp"
#include "render/renderer.hpp"
#include "shared/vxgi_types.h"
#include "support/gpu_fixture.hpp"
#include "support/placed_quads.hpp"
#include "vk/transfer.hpp"

namespace idk::test {
namespace {

constexpr uint32_t kVoxels = 64;
constexpr float kHalfStep = 1.0f / 1024.0f;  // one fp16 step, relative

scene::Scene testScene() {
    std::vector<PlacedQuad> q;
    q.push_back(placedQuad({0.0f, -1.0f, 0.0f}, {0, 1, 0}, {0.83f, 0.81f}, {0.8f, 0.8f, 0.8f}));
    q.push_back(placedQuad({0.05f, 1.0f, -0.02f}, {0, -1, 0}, {0.71f, 0.77f}, {0.9f, 0.9f, 0.9f}));
    q.push_back(placedQuad({-1.0f, 0.02f, 0.03f}, {1, 0, 0}, {0.74f, 0.69f}, {0.8f, 0.1f, 0.1f}));
    q.push_back(placedQuad({1.0f, -0.03f, 0.01f}, {-1, 0, 0}, {0.67f, 0.73f}, {0.1f, 0.8f, 0.1f}));
    q.push_back(placedQuad({0.01f, 0.02f, -1.0f}, {0, 0, 1}, {0.79f, 0.72f}, {0.7f, 0.7f, 0.6f}));
    q.push_back(placedQuad({0.1f, -0.2f, 0.15f}, {0.3f, 0.8f, 0.45f}, {0.4f, 0.3f}, {0.2f, 0.7f, 0.3f}, true));
    q.push_back(placedQuad({-0.3f, 0.30f, -0.2f}, {0, 1, 0}, {0.23f, 0.21f}, {0.9f, 0.2f, 0.2f}));
    q.push_back(placedQuad({-0.3f, 0.3004f, -0.2f}, {0, 1, 0}, {0.23f, 0.21f}, {0.1f, 0.3f, 0.9f}));
    q.push_back(placedQuad({-0.3f, 0.3002f, -0.2f}, {0, 1, 0}, {0.23f, 0.21f}, {0.2f, 0.9f, 0.4f}));
    scene::Scene s = makePlacedQuadScene(q);
    for (auto& m : s.materials) m.metallic = 0.0f;
    s.materials[1].emissive = {1.5f, 1.2f, 0.9f};
    s.lights.push_back(pointLight({0.2f, 0.6f, 0.1f}, 3.0f));
    return s;
}

std::unique_ptr<vk::Context> makeContext(std::optional<vk::Rung> forced, bool fallback = false) {
    vk::ContextDesc desc = sharedContext().desc();
    desc.validation = true;
    desc.probeGlInterop = true;
    desc.forceFallbackRungs = fallback;
    if (forced) desc.forcedRungs = {vk::RungForce{"vxgi-atomics", *forced}};
    return std::make_unique<vk::Context>(desc);
}

void expectClean(const vk::Context& ctx, const char* what) {
    EXPECT_EQ(ctx.validationErrors(), 0u) << what;
    for (const std::string& m : ctx.validationMessages()) ADD_FAILURE() << what << ": " << m;
}

// Grid tests: no shadows, centre raster (voxelize_record.frag); whole frames: the defaults, point shadows and
// conservative raster (geometry-shader dilation on lavapipe: voxelize_record_dilated.frag).
render::RenderSettings vxgiSettings(bool wholeFrame) {
    render::RenderSettings settings;
    settings.output = render::OutputKind::Hdr;
    settings.vxgi.mode = frame::GiMode::Vxgi;
    settings.vxgi.voxels = kVoxels;
    if (wholeFrame) return settings;
    settings.pointShadows.maxLights = 0;
    settings.vxgi.raster = frame::VoxelRaster::Centre;
    return settings;
}

scene::CameraView insideCamera() {
    scene::CameraView camera;
    camera.position = {0.0f, 0.0f, 0.9f};
    return camera;
}

struct Voxelized {
    vk::Rung rung = vk::Rung::Fallback;
    std::vector<glm::vec4> grid;
    std::vector<float> counts;  // GL rung only: fragments per voxel, from the GL sums
    passes::VxgiGlStats stats;
};

Voxelized voxelize(std::optional<vk::Rung> forced, bool fallback = false) {
    auto ctx = makeContext(forced, fallback);
    Voxelized v;
    {
        vk::ShaderLibrary shaders(*ctx);
        render::Renderer renderer(*ctx, shaders, vxgiSettings(false));
        renderer.setScene(testScene());
        renderer.renderOffscreen(insideCamera(), 16, 16);
        v.rung = ctx->ladder("vxgi-atomics").chosen;
        v.grid = conformance::readVoxelGrid(*ctx, *renderer.vxgi().grid());
        if (const passes::VxgiGlAccumulator* gl = renderer.vxgi().glAccumulator()) {
            v.stats = gl->lastStats();
            const std::vector<float> sums =
                vk::downloadBuffer<float>(*ctx, gl->sumsBuffer(), v.grid.size() * gpu::kVoxelSumWords);
            for (size_t i = 0; i < v.grid.size(); ++i) v.counts.push_back(sums[i * gpu::kVoxelSumWords + gpu::kVoxelSumCount]);
        }
    }
    ctx->waitIdle();
    expectClean(*ctx, vk::rungName(v.rung));
    return v;
}

bool within(float a, float b) { return std::abs(a - b) <= kHalfStep * std::max(std::abs(a), std::abs(b)) + 1e-6f; }

TEST(VxgiGlRungTest, GridMatchesNativeMeanAndPortableMaxOnSingleFragmentVoxels) {
    const Voxelized gl = voxelize(vk::Rung::GlInterop);
    ASSERT_EQ(gl.rung, vk::Rung::GlInterop) << "the GL-interop rung must be forcible on this device (llvmpipe)";
    const Voxelized native = voxelize(std::nullopt);
    const Voxelized portable = voxelize(std::nullopt, true);
    ASSERT_EQ(portable.rung, vk::Rung::Fallback);
    ASSERT_EQ(gl.grid.size(), native.grid.size());

    EXPECT_EQ(gl.stats.dropped, 0u);
    double fragments = 0;
    for (float c : gl.counts) fragments += c;
    EXPECT_EQ(fragments, double(gl.stats.appended)) << "every appended record lands in one voxel's count";

    size_t occupied = 0, multi = 0, triple = 0, single = 0, nativeDiff = 0, portableDiff = 0, occupancyDiff = 0;
    for (size_t i = 0; i < gl.grid.size(); ++i) {
        const glm::vec4 &g = gl.grid[i], &n = native.grid[i], &p = portable.grid[i];
        if ((g.a > 0.0f) != (n.a > 0.0f)) {
            ++occupancyDiff;
            continue;
        }
        if (g.a == 0.0f) {
            EXPECT_EQ(g, glm::vec4(0.0f)) << "empty voxel " << i;
            continue;
        }
        ++occupied;
        multi += gl.counts[i] > 1.0f;
        triple += gl.counts[i] > 2.0f;
        bool same = true;
        for (int c = 0; c < 4; ++c) same = same && within(g[c], n[c]);
        if (!same && nativeDiff++ < 5)
            ADD_FAILURE() << "voxel " << i << ": gl (" << g.r << ", " << g.g << ", " << g.b << ", " << g.a
                          << ") native (" << n.r << ", " << n.g << ", " << n.b << ", " << n.a << ")";
        if (gl.counts[i] != 1.0f) continue;
        ++single;
        for (int c = 0; c < 4; ++c) same = same && within(g[c], p[c]);
        if (!same && portableDiff++ < 5) ADD_FAILURE() << "one-fragment voxel " << i << " differs from the r32ui rung";
    }
    std::printf("gl-interop rung: %u fragments, %zu occupied voxels (%zu with 2+ fragments, %zu with 3+, %zu with "
                "one); differ from native: %zu, from r32ui on one-fragment voxels: %zu, occupancy: %zu\n",
                gl.stats.appended, occupied, multi, triple, single, nativeDiff, portableDiff, occupancyDiff);
    EXPECT_EQ(occupancyDiff, 0u);
    EXPECT_EQ(nativeDiff, 0u);
    EXPECT_EQ(portableDiff, 0u);
    EXPECT_GT(occupied, 10000u);
    EXPECT_GT(triple, 50u) << "the thin triple should put three fragments in some voxels";
    EXPECT_GT(single, 5000u);
}

TEST(VxgiGlRungTest, OverflowIsReportedAndTheBufferGrows) {
    auto ctx = makeContext(vk::Rung::GlInterop);
    {
        vk::ShaderLibrary shaders(*ctx);
        render::Renderer renderer(*ctx, shaders, vxgiSettings(false));
        renderer.setScene(testScene());
        renderer.renderOffscreen(insideCamera(), 16, 16);
        passes::VxgiGlAccumulator* gl = renderer.vxgi().glAccumulator();
        ASSERT_NE(gl, nullptr);
        const passes::VxgiGlStats whole = gl->lastStats();
        const std::vector<glm::vec4> before = conformance::readVoxelGrid(*ctx, *renderer.vxgi().grid());
        ASSERT_EQ(whole.dropped, 0u);
        ASSERT_GT(whole.appended, 2000u);

        gl->setCapacity(1000);
        renderer.renderOffscreen(insideCamera(), 16, 16);
        const passes::VxgiGlStats over = gl->lastStats();
        EXPECT_EQ(over.appended, whole.appended);
        EXPECT_EQ(over.capacity, 1000u);
        EXPECT_EQ(over.dropped, whole.appended - 1000u);
        size_t occupiedOver = 0;
        for (const glm::vec4& v : conformance::readVoxelGrid(*ctx, *renderer.vxgi().grid())) occupiedOver += v.a > 0.0f;

        renderer.renderOffscreen(insideCamera(), 16, 16);
        const passes::VxgiGlStats after = gl->lastStats();
        EXPECT_EQ(after.dropped, 0u);
        EXPECT_GE(after.capacity, whole.appended);
        const std::vector<glm::vec4> again = conformance::readVoxelGrid(*ctx, *renderer.vxgi().grid());
        size_t occupied = 0, differ = 0;
        for (size_t i = 0; i < before.size(); ++i) {
            occupied += before[i].a > 0.0f;
            for (int c = 0; c < 4; ++c) differ += !within(before[i][c], again[i][c]) ? 1 : 0;
        }
        std::printf("overflow: %u fragments, capacity 1000: %zu voxels kept of %zu; grown to %u records\n",
                    whole.appended, occupiedOver, occupied, after.capacity);
        EXPECT_LT(occupiedOver, occupied);
        EXPECT_EQ(differ, 0u) << "the frame after the growth is whole again";

        // A still (idk render) that overflows renders again with the grown buffer: its grid is whole.
        gl->setCapacity(1000);
        renderer.renderStill(insideCamera(), 16, 16);
        EXPECT_EQ(gl->lastStats().dropped, 0u);
        const std::vector<glm::vec4> still = conformance::readVoxelGrid(*ctx, *renderer.vxgi().grid());
        size_t stillDiffer = 0;
        for (size_t i = 0; i < before.size(); ++i)
            for (int c = 0; c < 4; ++c) stillDiffer += !within(before[i][c], still[i][c]) ? 1 : 0;
        EXPECT_EQ(stillDiffer, 0u) << "renderStill returned the overflowed frame";
    }
    ctx->waitIdle();
    expectClean(*ctx, "overflow");
}

std::vector<float> renderFrame(std::optional<vk::Rung> forced, vk::Rung* ran) {
    auto ctx = makeContext(forced);
    std::vector<float> pixels;
    {
        vk::ShaderLibrary shaders(*ctx);
        render::Renderer renderer(*ctx, shaders, vxgiSettings(true));
        renderer.setScene(testScene());
        pixels = renderer.renderOffscreen(insideCamera(), 64, 64).image.pixels;
        *ran = ctx->ladder("vxgi-atomics").chosen;
    }
    ctx->waitIdle();
    expectClean(*ctx, vk::rungName(*ran));
    return pixels;
}

TEST(VxgiGlRungTest, WholeFrameMatchesTheNativeRung) {
    vk::Rung glRung{}, nativeRung{};
    const std::vector<float> gl = renderFrame(vk::Rung::GlInterop, &glRung);
    const std::vector<float> native = renderFrame(std::nullopt, &nativeRung);
    ASSERT_EQ(glRung, vk::Rung::GlInterop);
    ASSERT_NE(nativeRung, vk::Rung::GlInterop);
    ASSERT_EQ(gl.size(), native.size());
    double mean = 0, squared = 0, maxDiff = 0;
    for (size_t i = 0; i < gl.size(); ++i) {
        if (i % 4 == 3) continue;
        mean += native[i];
        const double d = double(gl[i]) - double(native[i]);
        squared += d * d;
        maxDiff = std::max(maxDiff, std::abs(d));
    }
    const double n = double(gl.size()) * 3 / 4;
    mean /= n;
    const double relRmse = std::sqrt(squared / n) / mean;
    std::printf("whole frame, gl-interop vs %s: mean radiance %.4f, relative RMSE %.3g, max |diff| %.3g\n",
                vk::rungName(nativeRung), mean, relRmse, maxDiff);
    EXPECT_GT(mean, 0.0);
    EXPECT_LT(relRmse, 1e-3);
}

TEST(VxgiGlRungTest, WithoutEglTheRungIsAbsentWithTheReason) {
    ::setenv("IDK_GL_INTEROP", "off", 1);
    auto ctx = makeContext(vk::Rung::GlInterop);
    ::unsetenv("IDK_GL_INTEROP");
    const vk::Ladder& ladder = ctx->ladder("vxgi-atomics");
    for (const vk::RungOption& o : ladder.options) {
        if (o.rung != vk::Rung::GlInterop) continue;
        EXPECT_FALSE(o.available);
        EXPECT_NE(o.note.find("IDK_GL_INTEROP=off"), std::string::npos) << o.note;
    }
    EXPECT_NE(ladder.chosen, vk::Rung::GlInterop);
    EXPECT_NE(ctx->forcedRungError().find("IDK_GL_INTEROP=off"), std::string::npos) << ctx->forcedRungError();
    expectClean(*ctx, "no EGL");
}

}  // namespace
}  // namespace idk::test
