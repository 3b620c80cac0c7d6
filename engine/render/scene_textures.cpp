// scene_textures.cpp: TextureStreamer -> GpuScene::setTexture, pumped in the renderer's before-frame hook.
#include "render/scene_textures.hpp"

namespace idk::render {

SceneTextureStream::SceneTextureStream(vk::Context& ctx, Renderer& renderer, const scene::Scene& scene,
                                       const TextureStreamerOptions& options)
    : renderer_(renderer) {
    GpuScene* gpuScene = renderer.gpuScene();
    if (!gpuScene) return;
    streamer_ = std::make_unique<TextureStreamer>(
        ctx, scene,
        [gpuScene](uint32_t texture, vk::SampledIndex image, vk::SamplerIndex sampler) {
            gpuScene->setTexture(texture, image, sampler);
        },
        options);
    TextureStreamer* streamer = streamer_.get();
    renderer.setBeforeFrame([streamer](VkCommandBuffer cmd) { streamer->pump(cmd); });
}

SceneTextureStream::~SceneTextureStream() {
    if (streamer_) renderer_.setBeforeFrame({});
}

void SceneTextureStream::finishSynchronously() {
    if (streamer_) streamer_->finishSynchronously();
}

bool SceneTextureStream::allReady() const { return !streamer_ || streamer_->allReady(); }

}  // namespace idk::render
