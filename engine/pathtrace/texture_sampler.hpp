// texture_sampler.hpp: the path tracer's CPU textures: every scene texture decoded once (scene/texture_decode,
// mip 0 only is read), sampled bilinearly (or nearest, per the glTF sampler) with the glTF wrap modes per axis and
// KHR_texture_transform, sRGB texels decoded to linear before filtering (as an sRGB image view does on the GPU).
// The CPU side of the raster's sampleMaterialSlot (include/material_eval.glsl); the path tracers read mip 0.
#pragma once
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.hpp"
#include "scene/texture_decode.hpp"

namespace idk::pathtrace {

struct CpuTexture {
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<uint8_t> texels;  // RGBA8, level 0, row 0 = top (v = 0)
    scene::Sampler sampler;
    glm::vec4 mean{1.0f};         // average texel (linear for colour use; the 1x1 mip), for light power
};

// Decodes every Scene::textures entry (worker threads; placeholders for images that fail, with the decoder's
// warning appended to `warnings`). A texture without an image is a 1x1 white texel.
std::vector<CpuTexture> decodeSceneTextures(const scene::Scene& scene, std::vector<std::string>& warnings);

// uv after KHR_texture_transform (textureTransformRows applied to (uv, 1)).
glm::vec2 transformUv(const scene::TextureRef& ref, const glm::vec2& uv);

// Bilinear/nearest sample at uv (the ref's transform applied by the caller). `srgb`: decode RGB from sRGB first.
glm::vec4 sampleTexture(const CpuTexture& texture, const glm::vec2& uv, bool srgb);

// The 2x3 affine matrix rows of a TextureRef's transform (GpuTextureSlot::row0/row1 convention).
void textureTransformRows(const scene::TextureRef& ref, glm::vec3& row0, glm::vec3& row1);

}  // namespace idk::pathtrace
