// rt_shadow_switch_test.cpp: switching the shadow mode to ray-traced after the scene was loaded (the viewer's shadow
// mode switch): Renderer::prepareSourceScene builds the ray-traced shadows' geometry on demand
// (frame/rt_shadow_feature.cpp ensureGeometry). Embedded Cornell box, 64x64 HDR:
//  * loaded with shadow maps: no rt_shadows pass; switched to ray-traced without prepareSourceScene: still none (the
//    geometry does not exist; the frame warns);
//  * after prepareSourceScene: the rt_shadows pass runs and the frame equals, bit for bit, the frame of a renderer
//    that had ray-traced shadows on from the start (same geometry, same masks);
//  * back to maps and on again: the geometry is kept (prepareSourceScene is a no-op) and the frame is the same again.
#include <gtest/gtest.h>

#include <algorithm>

#include "app/default_scene.hpp"
#include "render/renderer.hpp"
#include "support/gpu_fixture.hpp"

namespace idk::test {
namespace {

constexpr uint32_t kSize = 64;

bool ran(const render::FrameResult& frame, const char* pass) {
    return std::find(frame.passesRun.begin(), frame.passesRun.end(), pass) != frame.passesRun.end();
}

class RtShadowSwitchTest : public GpuTest {};

TEST_F(RtShadowSwitchTest, SwitchingToRayTracedBuildsTheGeometryOnDemand) {
    const scene::Scene scene = app::loadDefaultScene();
    const scene::CameraView camera = scene::defaultCamera(scene);
    render::RenderSettings settings;
    settings.output = render::OutputKind::Hdr;
    render::RenderSettings traced = settings;
    traced.lightShadows.rayTraced = true;

    render::Renderer fromStart(ctx(), shaders(), traced);
    fromStart.setScene(scene);
    const render::FrameResult expected = fromStart.renderOffscreen(camera, kSize, kSize);
    ASSERT_TRUE(ran(expected, "rt_shadows"));

    render::Renderer renderer(ctx(), shaders(), settings);
    renderer.setScene(scene);
    const render::FrameResult maps = renderer.renderOffscreen(camera, kSize, kSize);
    EXPECT_FALSE(ran(maps, "rt_shadows"));
    renderer.settings().lightShadows.rayTraced = true;
    EXPECT_FALSE(ran(renderer.renderOffscreen(camera, kSize, kSize), "rt_shadows")) << "no geometry was built yet";

    renderer.prepareSourceScene(scene);
    const render::FrameResult switched = renderer.renderOffscreen(camera, kSize, kSize);
    EXPECT_TRUE(ran(switched, "rt_shadows"));
    EXPECT_EQ(switched.image.pixels, expected.image.pixels) << "the on-demand geometry gives other shadows";
    EXPECT_NE(switched.image.pixels, maps.image.pixels) << "the mode switch changed nothing";

    renderer.settings().lightShadows.rayTraced = false;
    renderer.prepareSourceScene(scene);
    EXPECT_FALSE(ran(renderer.renderOffscreen(camera, kSize, kSize), "rt_shadows"));
    renderer.settings().lightShadows.rayTraced = true;
    renderer.prepareSourceScene(scene);
    const render::FrameResult again = renderer.renderOffscreen(camera, kSize, kSize);
    EXPECT_TRUE(ran(again, "rt_shadows"));
    EXPECT_EQ(again.image.pixels, expected.image.pixels);
}

}  // namespace
}  // namespace idk::test
