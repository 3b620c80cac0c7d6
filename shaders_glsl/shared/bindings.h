// bindings.h: the single global bindless descriptor set (set 0) shared by every pipeline.
// C++ creates the layout from these numbers; GLSL declares its arrays in include/bindless.glsl.
#ifndef IDK_BINDINGS_H
#define IDK_BINDINGS_H
#include "interop.h"

IDK_GPU_BEGIN
IDK_CONST(uint, kBindingSampledImages, 0);   // texture2D / texture3D / textureCube aliases
IDK_CONST(uint, kBindingStorageImages, 1);   // image2D / uimage2D / image3D aliases (format-less where allowed)
IDK_CONST(uint, kBindingSamplers, 2);        // sampler
IDK_CONST(uint, kBindingStorageBuffers, 3);  // untyped storage buffers, aliased per element type
IDK_CONST(uint, kPushConstantBytes, 128);    // portable push-constant budget (Vulkan guarantees 128)
IDK_GPU_END

#endif
