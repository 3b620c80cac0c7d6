// texture_loader.hpp: a synchronous stand-in for the asynchronous texture streamer (tests only): decodes every
// scene image with OpenImageIO (embedded bytes or file), uploads mip 0 as RGBA8 (sRGB view for textures used
// as colour, UNORM for data; both when used as both) and hands them to GpuScene::setTexture. Exercises the
// streamer's API and lets tests and developers see fully textured frames before the streamer lands.
#pragma once
#include <vector>

#include "render/gpu_scene.hpp"
#include "scene/scene.hpp"
#include "vk/context.hpp"

namespace idk::test {

// Owns the uploaded images; release() (or the destructor) returns them after the GPU is idle.
class SyncTextures {
public:
    SyncTextures(vk::Context& ctx, const scene::Scene& scene, render::GpuScene& gpuScene);
    ~SyncTextures();
    SyncTextures(const SyncTextures&) = delete;
    SyncTextures& operator=(const SyncTextures&) = delete;
    uint32_t loaded() const { return loaded_; }  // scene textures whose image decoded

private:
    vk::Context& ctx_;
    std::vector<vk::Image> images_;
    std::vector<vk::SampledIndex> indices_;
    uint32_t loaded_ = 0;
};

// A solid-colour RGBA8 texture (sRGB or UNORM), for tests of GpuScene::setTexture.
vk::Image makeSolidTexture(vk::Context& ctx, const uint8_t rgba[4], bool srgb);

}  // namespace idk::test
