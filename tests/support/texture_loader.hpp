// texture_loader.hpp: solid-colour textures for tests of GpuScene::setTexture (real scene textures come through
// render::SceneTextureStream).
#pragma once
#include <vector>

#include "render/gpu_scene.hpp"
#include "scene/scene.hpp"
#include "vk/context.hpp"

namespace idk::test {

// A solid-colour RGBA8 texture (sRGB or UNORM), for tests of GpuScene::setTexture.
vk::Image makeSolidTexture(vk::Context& ctx, const uint8_t rgba[4], bool srgb);

}  // namespace idk::test
