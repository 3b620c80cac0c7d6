// scene_textures.hpp: connects the asynchronous texture streamer to a renderer: the streamer's pump runs at
// the start of every frame, and each texture it makes ready repoints the GPU scene's materials (placeholders
// until then). `idk render` calls finishSynchronously() for final images; the viewer keeps streaming.
#pragma once
#include <memory>

#include "render/renderer.hpp"
#include "render/texture_streamer.hpp"

namespace idk::render {

class SceneTextureStream {
public:
    // `scene` must outlive the stream. Does nothing for a renderer without a GPU scene (Lambert shading).
    SceneTextureStream(vk::Context& ctx, Renderer& renderer, const scene::Scene& scene,
                       const TextureStreamerOptions& options = {});
    ~SceneTextureStream();  // detaches the frame hook, then stops the streamer
    SceneTextureStream(const SceneTextureStream&) = delete;
    SceneTextureStream& operator=(const SceneTextureStream&) = delete;

    void finishSynchronously();  // every texture decoded, uploaded and patched into the materials
    bool allReady() const;
    const TextureStreamer* streamer() const noexcept { return streamer_.get(); }

private:
    Renderer& renderer_;
    std::unique_ptr<TextureStreamer> streamer_;
};

}  // namespace idk::render
