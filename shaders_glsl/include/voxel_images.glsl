// voxel_images.glsl: the bindless storage-image array viewed as 3D images of the formats VXGI uses (aliases of the
// binding bindless.glsl declares as 2D arrays; each element is only ever accessed through the type of its view).
#ifndef IDK_VOXEL_IMAGES_GLSL
#define IDK_VOXEL_IMAGES_GLSL
#include "bindless.glsl"

layout(set = 0, binding = kBindingStorageImages, r32f) uniform image3D gVoxelsR32f[];
layout(set = 0, binding = kBindingStorageImages, r32ui) uniform uimage3D gVoxelsR32ui[];
layout(set = 0, binding = kBindingStorageImages, rgba16f) uniform image3D gVoxelsRgba16f[];

#endif
