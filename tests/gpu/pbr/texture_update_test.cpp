// texture_update_test.cpp: GpuScene::setTexture, the async texture streamer's entry point: patching a scene
// texture re-points every material slot that uses it, the next frame carries a scene_update pass (and only that
// frame), and the frame shows the texture; hostile indices throw. Also renders fully textured frames through the
// synchronous test loader (DamagedHelmet: base colour, metal-rough, normal, occlusion, emissive maps) and checks
// them for finiteness and coverage; the PNGs land in the build tree for inspection.
#include <gtest/gtest.h>

#include "core/image_file.hpp"
#include "render/renderer.hpp"
#include "scene/gltf_loader.hpp"
#include "support/frame_checks.hpp"
#include "support/gpu_fixture.hpp"
#include "render/scene_textures.hpp"
#include "support/texture_loader.hpp"

namespace idk::test {
namespace {

class TextureUpdateTest : public GpuTest {};

const float* pixel(const render::FrameResult& f, uint32_t x, uint32_t y) {
    return &f.image.pixels[(size_t(y) * f.image.width + x) * 4];
}

TEST_F(TextureUpdateTest, SetTexturePatchesMaterialsAndTheNextFrameShowsIt) {
    scene::Scene scene =
        scene::loadGltf(std::string(IDK_SHARED_DIR) + "/scenes/BoxTextured/glTF-Binary/BoxTextured.glb");
    ASSERT_EQ(scene.textures.size(), 1u);
    render::RenderSettings settings;
    settings.output = render::OutputKind::Hdr;
    render::Renderer renderer(ctx(), shaders(), settings);
    renderer.setScene(scene);
    render::GpuScene& gpu = *renderer.gpuScene();
    EXPECT_TRUE(gpu.textureIsColor(0));
    EXPECT_FALSE(gpu.textureIsData(0));
    EXPECT_THROW(gpu.setTexture(1, vk::SampledIndex{0}), std::out_of_range);

    scene::CameraView camera = scene::defaultCamera(scene);
    render::FrameResult before = renderer.renderOffscreen(camera, 32, 32);
    const float* b = pixel(before, 16, 16);
    EXPECT_NEAR(b[0], b[1], 0.05f * b[1]) << "placeholder white: grey box";

    const uint8_t red[4] = {255, 0, 0, 255};
    vk::Image texture = makeSolidTexture(ctx(), red, true);
    vk::SampledIndex index = ctx().bindless().addSampled(texture.view);
    gpu.setTexture(0, index);
    EXPECT_EQ(gpu.materials()[scene.meshes[0].primitives[0].material.value()].slots[gpu::kSlotBaseColor].texture,
              index.value);

    render::FrameResult after = renderer.renderOffscreen(camera, 32, 32);
    EXPECT_EQ(after.passesRun.front(), "scene_update");
    const float* a = pixel(after, 16, 16);
    EXPECT_GT(a[0], 4.0f * a[1]) << "the base colour texture is red";
    EXPECT_EQ(a[3], 1.0f);

    render::FrameResult next = renderer.renderOffscreen(camera, 32, 32);
    EXPECT_EQ(next.passesRun.front(), "cull_reset_early") << "nothing changed: no scene_update before the G-buffer";
    EXPECT_EQ(next.image.pixels, after.image.pixels);
    ctx().waitIdle();
    ctx().bindless().release(index);
    ctx().destroyDeferred(texture);
}

// The texture streamer's path: setTexture (with the streamer's sampler) called from the before-frame hook, inside
// the frame's command buffer, reaches the same frame.
TEST_F(TextureUpdateTest, TextureReadyInTheBeforeFrameHookShowsInThatFrame) {
    scene::Scene scene =
        scene::loadGltf(std::string(IDK_SHARED_DIR) + "/scenes/BoxTextured/glTF-Binary/BoxTextured.glb");
    render::RenderSettings settings;
    settings.output = render::OutputKind::Hdr;
    render::Renderer renderer(ctx(), shaders(), settings);
    renderer.setScene(scene);
    const uint8_t green[4] = {0, 255, 0, 255};
    vk::Image texture = makeSolidTexture(ctx(), green, true);
    vk::SampledIndex index = ctx().bindless().addSampled(texture.view);
    vk::SamplerDesc nearest;
    nearest.filter = VK_FILTER_NEAREST;
    vk::SamplerIndex sampler = ctx().bindless().addSampler(nearest);
    bool called = false;
    renderer.setBeforeFrame([&](VkCommandBuffer) {
        if (!called) renderer.gpuScene()->setTexture(0, index, sampler);
        called = true;
    });
    render::FrameResult frame = renderer.renderOffscreen(scene::defaultCamera(scene), 32, 32);
    EXPECT_TRUE(called);
    EXPECT_EQ(frame.passesRun.front(), "scene_update");
    const float* p = pixel(frame, 16, 16);
    EXPECT_GT(p[1], 4.0f * p[0]) << "the base colour texture is green";
    uint32_t material = scene.meshes[0].primitives[0].material.value();
    EXPECT_EQ(renderer.gpuScene()->materials()[material].slots[gpu::kSlotBaseColor].samplerIndex, sampler.value);
    ctx().waitIdle();
    ctx().bindless().release(index);
    ctx().bindless().release(sampler);
    ctx().destroyDeferred(texture);
}

TEST_F(TextureUpdateTest, FullyTexturedDamagedHelmetIsFiniteAndCovered) {
    scene::Scene scene =
        scene::loadGltf(std::string(IDK_SHARED_DIR) + "/scenes/DamagedHelmet/glTF-Binary/DamagedHelmet.glb");
    render::RenderSettings settings;
    settings.output = render::OutputKind::Hdr;
    render::Renderer renderer(ctx(), shaders(), settings);
    renderer.setScene(scene);
    render::SceneTextureStream textures(ctx(), renderer, scene);
    textures.finishSynchronously();
    ASSERT_NE(textures.streamer(), nullptr);
    EXPECT_EQ(textures.streamer()->stats().placeholders, 0u);
    scene::CameraView camera = scene::defaultCamera(scene);
    render::FrameResult hdr = renderer.renderOffscreen(camera, 128, 128);
    FrameStats s =
        analyzeFrame(hdr.image, scene.bounds, scene::projectionMatrix(camera, 1.0f) * scene::viewMatrix(camera));
    EXPECT_EQ(s.nonFinite, 0u);
    EXPECT_EQ(s.negative, 0u);
    EXPECT_EQ(s.outsideBounds, 0u);
    EXPECT_GT(s.fill(), 0.35);
    renderer.settings().output = render::OutputKind::Display;
    render::FrameResult display = renderer.renderOffscreen(camera, 256, 256);
    core::writeImage(std::string(IDK_BINARY_DIR) + "/damaged_helmet_textured.png", display.image);
}

// NormalTangentMirrorTest (normal maps with mirrored UVs) under a directional light, twice: with the file's vertex
// tangents and with none (the fragment shader's screen-space cotangent frame). Two independent tangent frames
// must shade alike: mean difference <= 1 code of 255 and at most 1% of the pixels off by more than 8 codes.
TEST_F(TextureUpdateTest, DerivedTangentFrameShadesLikeVertexTangents) {
    scene::Scene scene = scene::loadGltf(std::string(IDK_SHARED_DIR) +
                                         "/scenes/NormalTangentMirrorTest/glTF-Binary/NormalTangentMirrorTest.glb");
    scene::Light sun;
    sun.type = scene::LightType::Directional;
    sun.direction = glm::normalize(glm::vec3(-1.0f, -1.0f, -1.0f));
    sun.intensity = 3.0f;
    scene.lights.push_back(sun);
    auto render = [&](const scene::Scene& s) {
        render::Renderer renderer(ctx(), shaders());
        renderer.settings().environmentIntensity = 0.2f;
        renderer.setScene(s);
        render::SceneTextureStream textures(ctx(), renderer, s);
        textures.finishSynchronously();
        EXPECT_TRUE(textures.allReady());
        return renderer.renderOffscreen(scene::defaultCamera(s), 192, 192).display;
    };
    std::vector<uint8_t> withTangents = render(scene);
    size_t vertexTangents = 0;
    for (scene::Mesh& m : scene.meshes)
        for (scene::Primitive& p : m.primitives) {
            vertexTangents += p.tangents.size();
            p.tangents.clear();
        }
    ASSERT_GT(vertexTangents, 0u);
    std::vector<uint8_t> derived = render(scene);
    ASSERT_EQ(withTangents.size(), derived.size());
    size_t off = 0;
    double sum = 0.0;
    for (size_t p = 0; p < withTangents.size() / 4; ++p) {
        int worst = 0;
        for (int c = 0; c < 3; ++c) {
            int d = std::abs(int(withTangents[p * 4 + c]) - int(derived[p * 4 + c]));
            worst = std::max(worst, d);
            sum += d;
        }
        off += worst > 8;
    }
    EXPECT_LE(sum / double(withTangents.size() / 4 * 3), 1.0);
    EXPECT_LE(double(off) / double(withTangents.size() / 4), 0.01);
}

}  // namespace
}  // namespace idk::test
