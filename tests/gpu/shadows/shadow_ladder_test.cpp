// shadow_ladder_test.cpp: the two rungs of the ladder "point-shadow cube faces" agree. The shared context takes
// the native rung where the device has shaderOutputLayer (lavapipe does: one instanced draw per light, gl_Layer
// from the vertex shader); a second context with ContextDesc::forceFallbackRungs takes the six-draw rung. Both
// render the Cornell box; every texel of every face of the light's D32 cube must be bit-identical (both rungs run
// the same vertex arithmetic, include/point_shadow_vertex.glsl), and so must the lit frames. Also checks what
// each rung records: 1 vs 6 indirect calls per light.
#include <gtest/gtest.h>

#include <cstring>

#include "app/default_scene.hpp"
#include "render/renderer.hpp"
#include "support/cube_readback.hpp"
#include "support/gpu_fixture.hpp"
#include "vk/context.hpp"
#include "vk/transfer.hpp"

namespace idk::test {
namespace {

constexpr uint32_t kFrame = 64, kCube = 128;

struct RungResult {
    vk::Rung rung;
    std::vector<float> cube;
    render::FrameResult frame;
    uint32_t shadowCalls = 0;
};

RungResult renderCornell(vk::Context& ctx, vk::ShaderLibrary& shaders) {
    scene::Scene scene = app::loadDefaultScene();
    render::RenderSettings settings;
    settings.output = render::OutputKind::Hdr;
    settings.pointShadows.resolution = kCube;
    settings.culling.mode = frame::CullingMode::Off;  // culled cubes are drawn face by face on both rungs
    render::Renderer renderer(ctx, shaders, settings);
    renderer.setScene(scene);
    RungResult r;
    r.rung = ctx.ladder("point-shadow cube faces").chosen;
    r.frame = renderer.renderOffscreen(scene::defaultCamera(scene), kFrame, kFrame);
    for (const auto& e : r.frame.indirectDraws)
        if (e.pass == "point_shadows") r.shadowCalls = e.calls;
    const render::PointShadowMaps* maps = renderer.pointShadowMaps();
    EXPECT_NE(maps, nullptr);
    if (maps) {
        EXPECT_EQ(maps->casters().size(), 1u) << "the Cornell box has one point light";
        EXPECT_EQ(maps->layered(), r.rung == vk::Rung::Native);
        r.cube = readCube(ctx, maps->cube(0));
    }
    return r;
}

class ShadowLadderTest : public GpuTest {};

TEST_F(ShadowLadderTest, NativeAndSixDrawRungsRenderIdenticalCubesAndFrames) {
    RungResult native = renderCornell(ctx(), shaders());
    if (native.rung != vk::Rung::Native) GTEST_SKIP() << "device lacks shaderOutputLayer: only the fallback runs";
    EXPECT_EQ(native.shadowCalls, 1u) << "native: one instanced indirect draw per light";

    vk::ContextDesc desc = ctx().desc();
    desc.forceFallbackRungs = true;  // what `idk info --fallback` / `idk render --fallback` select
    RungResult fallback;
    uint32_t fallbackErrors = 0;
    {
        vk::Context fallbackCtx(desc);
        vk::ShaderLibrary fallbackShaders(fallbackCtx);
        fallback = renderCornell(fallbackCtx, fallbackShaders);
        fallbackCtx.waitIdle();
        fallbackErrors = fallbackCtx.validationErrors();
    }
    EXPECT_EQ(fallbackErrors, 0u) << "validation errors on the fallback context";
    EXPECT_EQ(fallback.rung, vk::Rung::Fallback);
    EXPECT_EQ(fallback.shadowCalls, 6u) << "fallback: six indirect draws per light";

    ASSERT_EQ(native.cube.size(), size_t(kCube) * kCube * 6);
    ASSERT_EQ(fallback.cube.size(), native.cube.size());
    size_t differing = 0, covered = 0;
    for (size_t i = 0; i < native.cube.size(); ++i) {
        differing += std::memcmp(&native.cube[i], &fallback.cube[i], sizeof(float)) != 0;
        covered += native.cube[i] < 1.0f;
    }
    EXPECT_EQ(differing, 0u) << "texels that differ between the rungs";
    EXPECT_GT(covered, native.cube.size() * 3 / 4) << "the box (open at the front) fills most of the cube";
    for (float d : native.cube) ASSERT_TRUE(d >= 0.0f && d <= 1.0f);

    ASSERT_EQ(native.frame.image.pixels.size(), fallback.frame.image.pixels.size());
    EXPECT_EQ(std::memcmp(native.frame.image.pixels.data(), fallback.frame.image.pixels.data(),
                          native.frame.image.pixels.size() * sizeof(float)),
              0)
        << "the lit frames differ";
}

}  // namespace
}  // namespace idk::test
