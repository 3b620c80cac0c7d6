// bindless.glsl: GLSL side of the global descriptor set (shared/bindings.h). Each binding is declared once per
// element type it is read as (aliasing is allowed for runtime arrays of the same descriptor type).
#ifndef IDK_BINDLESS_GLSL
#define IDK_BINDLESS_GLSL
#extension GL_EXT_nonuniform_qualifier : require
#include "bindings.h"

layout(set = 0, binding = kBindingSampledImages) uniform texture2D gTextures2D[];
layout(set = 0, binding = kBindingSampledImages) uniform texture3D gTextures3D[];
layout(set = 0, binding = kBindingSampledImages) uniform textureCube gTexturesCube[];
// Storage images are declared per format so no device feature for format-less loads is needed.
layout(set = 0, binding = kBindingStorageImages, rgba16f) uniform image2D gImagesRgba16f[];
layout(set = 0, binding = kBindingStorageImages, rgba8) uniform image2D gImagesRgba8[];
layout(set = 0, binding = kBindingStorageImages, r32f) uniform image2D gImagesR32f[];
layout(set = 0, binding = kBindingStorageImages, r32ui) uniform uimage2D gImagesR32ui[];
layout(set = 0, binding = kBindingStorageImages, rgba32ui) uniform uimage2D gImagesRgba32ui[];
// rg32ui is one of SPIR-V's "extended" storage formats; Vulkan requires storage support for R32G32_UINT itself.
layout(set = 0, binding = kBindingStorageImages, rg32ui) uniform uimage2D gImagesRg32ui[];
layout(set = 0, binding = kBindingSamplers) uniform sampler gSamplers[];

// Declares `name[]`, the storage-buffer binding viewed as arrays of `type`: name[index].data[i].
#define IDK_BINDLESS_BUFFER(name, type) \
    layout(set = 0, binding = kBindingStorageBuffers, scalar) buffer name##Block { type data[]; } name[]
#define IDK_BINDLESS_BUFFER_READONLY(name, type) \
    layout(set = 0, binding = kBindingStorageBuffers, scalar) readonly buffer name##Block { type data[]; } name[]

#define IDK_SAMPLE_2D(textureIndex, samplerIndex, uv) \
    texture(sampler2D(gTextures2D[nonuniformEXT(textureIndex)], gSamplers[nonuniformEXT(samplerIndex)]), uv)

#endif
