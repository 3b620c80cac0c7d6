// voxel_images.glsl: the bindless storage-image array viewed as 3D images of the formats VXGI uses (aliases of the
// binding bindless.glsl declares as 2D arrays; each element is only ever accessed through the type of its view).
#ifndef IDK_VOXEL_IMAGES_GLSL
#define IDK_VOXEL_IMAGES_GLSL
#include "bindless.glsl"

layout(set = 0, binding = kBindingStorageImages, r32f) uniform image3D gVoxelsR32f[];
layout(set = 0, binding = kBindingStorageImages, r32ui) uniform uimage3D gVoxelsR32ui[];
layout(set = 0, binding = kBindingStorageImages, rgba16f) uniform image3D gVoxelsRgba16f[];
layout(set = 0, binding = kBindingStorageImages, r11f_g11f_b10f) uniform image3D gVoxelsR11g11b10f[];
layout(set = 0, binding = kBindingStorageImages, r8) uniform image3D gVoxelsR8[];

// A voxel of a directional volume (premultiplied rgb, coverage a) through the storage views of one level: `colour`
// and `opacity` are a B10G11R11_UFLOAT and an R8_UNORM image (ladder "vxgi-volume-format" native), or the same
// index, one RGBA16F image (its fallback). The indices come from push constants, uniform over the dispatch, so the
// branch costs nothing on a GPU.
vec4 loadDirectionVoxel(uint colour, uint opacity, ivec3 voxel) {
    if (colour == opacity) return imageLoad(gVoxelsRgba16f[colour], voxel);
    return vec4(imageLoad(gVoxelsR11g11b10f[colour], voxel).rgb, imageLoad(gVoxelsR8[opacity], voxel).r);
}

void storeDirectionVoxel(uint colour, uint opacity, ivec3 voxel, vec4 value) {
    if (colour == opacity) {
        imageStore(gVoxelsRgba16f[colour], voxel, value);
        return;
    }
    imageStore(gVoxelsR11g11b10f[colour], voxel, vec4(value.rgb, 0.0));
    imageStore(gVoxelsR8[opacity], voxel, vec4(value.a));
}

#endif
