// pbr_frame_test.cpp: whole frames of the deferred PBR renderer (IDKEngine's RasterPipeline frame) on shared glTF
// assets and the embedded Cornell box, 128x128 on lavapipe.
#include <gtest/gtest.h>
//  * properties of the HDR frame with the default environment: no NaN/Inf/negative values, geometry (alpha 1)
//    only inside the projected scene bounds and filling at least a stated fraction of them, radiance below
//    1.1 x the brightest environment texel + the brightest emission (no lights in these assets);
//  * a white furnace: a constant environment L = 0.5 (no lights): no geometry pixel may exceed 1.02 L + emission;
//  * golden images (display PNG, metric in support/golden.hpp) of every asset, textures streamed in completely
//    (render::SceneTextureStream::finishSynchronously) before the frame.
//  * the sky: an empty scene is all environment, matching a CPU bilinear lookup of the equirectangular map.

#include <cmath>

#include "app/default_scene.hpp"
#include "render/renderer.hpp"
#include "render/scene_textures.hpp"
#include "scene/gltf_loader.hpp"
#include "support/frame_checks.hpp"
#include "support/golden.hpp"
#include "support/gpu_fixture.hpp"

namespace idk::test {
namespace {

constexpr uint32_t kSize = 128;

struct Asset {
    const char* name;
    const char* path;  // under ../shared/scenes; nullptr: the embedded Cornell box
    double minFill;    // geometry pixels / projected-bounds pixels
    bool golden;
};

const Asset kAssets[] = {
    {"box", "Box/glTF-Binary/Box.glb", 0.95, true},
    {"box_textured", "BoxTextured/glTF-Binary/BoxTextured.glb", 0.95, true},
    {"metal_rough_spheres", "MetalRoughSpheresNoTextures/glTF-Binary/MetalRoughSpheresNoTextures.glb", 0.35, true},
    {"damaged_helmet", "DamagedHelmet/glTF-Binary/DamagedHelmet.glb", 0.35, true},
    {"cornell_box", nullptr, 0.95, true},
};

void PrintTo(const Asset& a, std::ostream* os) { *os << a.name; }

scene::Scene loadAsset(const Asset& a) {
    return a.path ? scene::loadGltf(std::string(IDK_SHARED_DIR) + "/scenes/" + a.path) : app::loadDefaultScene();
}

float maxEmission(const scene::Scene& s) {
    float m = 0.0f;
    for (const scene::Material& mat : s.materials) m = std::max({m, mat.emissive.r, mat.emissive.g, mat.emissive.b});
    return m;
}

glm::mat4 viewProjection(const scene::CameraView& camera) {
    return scene::projectionMatrix(camera, 1.0f) * scene::viewMatrix(camera);
}

class PbrFrameTest : public GpuTest, public ::testing::WithParamInterface<Asset> {};

TEST_P(PbrFrameTest, HdrFrameIsFiniteCoversItsBoundsAndStaysWithinEnergyBounds) {
    const Asset& a = GetParam();
    scene::Scene scene = loadAsset(a);
    render::RenderSettings settings;
    settings.output = render::OutputKind::Hdr;
    render::Renderer renderer(ctx(), shaders(), settings);
    renderer.setScene(scene);
    scene::CameraView camera = scene::defaultCamera(scene);
    render::FrameResult frame = renderer.renderOffscreen(camera, kSize, kSize);
    FrameStats s = analyzeFrame(frame.image, scene.bounds, viewProjection(camera));

    static const float envMax = [] {
        core::ImageRgba32f env = core::readImage(render::defaultEnvironmentPath());
        float m = 0.0f;
        for (size_t i = 0; i < env.pixels.size(); ++i)
            if (i % 4 != 3) m = std::max(m, env.pixels[i]);
        return m;
    }();
    EXPECT_EQ(s.nonFinite, 0u) << a.name;
    EXPECT_EQ(s.negative, 0u) << a.name;
    EXPECT_GT(s.geometry, 0u) << a.name;
    EXPECT_EQ(s.outsideBounds, 0u) << a.name << ": geometry outside the projected bounds";
    EXPECT_GE(s.fill(), a.minFill) << a.name;
    EXPECT_GT(s.meanGeometryRadiance, 0.02) << a.name << ": geometry is (nearly) black";
    if (scene.lights.empty()) {
        EXPECT_LE(s.maxGeometryRadiance, 1.1 * envMax + maxEmission(scene)) << a.name;
    }
}

TEST_P(PbrFrameTest, WhiteFurnaceReflectsNoMoreThanTheEnvironment) {
    const Asset& a = GetParam();
    scene::Scene scene = loadAsset(a);
    scene.lights.clear();
    render::RenderSettings settings;
    settings.output = render::OutputKind::Hdr;
    settings.environment = std::filesystem::path();  // constant radiance 0.5
    render::Renderer renderer(ctx(), shaders(), settings);
    renderer.setScene(scene);
    scene::CameraView camera = scene::defaultCamera(scene);
    render::FrameResult frame = renderer.renderOffscreen(camera, kSize, kSize);
    FrameStats s = analyzeFrame(frame.image, scene.bounds, viewProjection(camera));
    EXPECT_EQ(s.nonFinite, 0u);
    EXPECT_LE(s.maxGeometryRadiance, 1.02 * 0.5 + maxEmission(scene)) << a.name;
    EXPECT_GT(s.meanGeometryRadiance, 0.05) << a.name;
    // The background is the environment itself.
    EXPECT_NEAR(frame.image.pixels[0], 0.5f, 1e-3f);
}

TEST_P(PbrFrameTest, DisplayFrameMatchesGolden) {
    const Asset& a = GetParam();
    if (!a.golden) GTEST_SKIP() << a.name << ": no golden";
    scene::Scene scene = loadAsset(a);
    render::Renderer renderer(ctx(), shaders());
    renderer.setScene(scene);
    render::SceneTextureStream textures(ctx(), renderer, scene);
    textures.finishSynchronously();
    render::FrameResult frame = renderer.renderOffscreen(scene::defaultCamera(scene), kSize, kSize);
    ASSERT_EQ(frame.display.size(), size_t(kSize) * kSize * 4);
    GoldenResult g = compareWithGolden(std::string("pbr_") + a.name, frame.display, kSize, kSize);
    EXPECT_TRUE(g.passed) << g.message;
}

INSTANTIATE_TEST_SUITE_P(SharedAssets, PbrFrameTest, ::testing::ValuesIn(kAssets),
                         [](const ::testing::TestParamInfo<Asset>& info) { return std::string(info.param.name); });

// CPU bilinear lookup of mip 0 (repeat in u, clamp in v), the texel layout the GPU sampler uses.
glm::vec3 bilinear(const core::ImageRgba32f& img, glm::vec2 uv) {
    float x = uv.x * img.width - 0.5f, y = std::clamp(uv.y * img.height - 0.5f, 0.0f, float(img.height - 1));
    int x0 = int(std::floor(x)), y0 = int(std::floor(y));
    float fx = x - x0, fy = y - y0;
    auto at = [&](int px, int py) {
        px = ((px % int(img.width)) + int(img.width)) % int(img.width);
        py = std::clamp(py, 0, int(img.height) - 1);
        const float* p = &img.pixels[(size_t(py) * img.width + px) * 4];
        return glm::vec3(p[0], p[1], p[2]);
    };
    return glm::mix(glm::mix(at(x0, y0), at(x0 + 1, y0), fx), glm::mix(at(x0, y0 + 1), at(x0 + 1, y0 + 1), fx), fy);
}

class SkyTest : public GpuTest {};

TEST_F(SkyTest, EmptySceneShowsTheEnvironmentAlongEachViewRay) {
    scene::Scene empty;
    render::RenderSettings settings;
    settings.output = render::OutputKind::Hdr;
    render::Renderer renderer(ctx(), shaders(), settings);
    renderer.setScene(empty);
    scene::CameraView camera;  // at the origin looking down -Z
    render::FrameResult frame = renderer.renderOffscreen(camera, 64, 64);
    EXPECT_TRUE(frame.indirectDraws.empty()) << "nothing to draw: no indirect call";
    core::ImageRgba32f env = core::readImage(render::defaultEnvironmentPath());
    glm::mat4 inv = glm::inverse(viewProjection(camera));
    int checked = 0;
    for (uint32_t py = 4; py < 64; py += 9) {
        for (uint32_t px = 4; px < 64; px += 9) {
            glm::vec2 ndc((px + 0.5f) / 64.0f * 2.0f - 1.0f, (py + 0.5f) / 64.0f * 2.0f - 1.0f);
            glm::vec4 a = inv * glm::vec4(ndc, 0.0f, 1.0f), b = inv * glm::vec4(ndc, 0.5f, 1.0f);
            glm::vec3 dir = glm::normalize(glm::vec3(b) / b.w - glm::vec3(a) / a.w);
            glm::vec3 want = bilinear(env, render::equirectUv(dir));
            const float* got = &frame.image.pixels[(size_t(py) * 64 + px) * 4];
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], want[c], 0.01f * want[c] + 2e-3f) << px << "," << py;
            EXPECT_EQ(got[3], 0.0f) << "sky pixels have alpha 0";
            ++checked;
        }
    }
    EXPECT_EQ(checked, 49);
}

}  // namespace
}  // namespace idk::test
