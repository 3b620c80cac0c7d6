#version 460
// voxelize_key_dilated.frag.glsl: voxelize_key.frag behind voxelize.geom's triangle dilation (the
// "conservative-raster" fallback rung): the same keys, plus the dilated triangle's bounds test in voxelFragment.
#define IDK_VOXELIZE_KEY_PASS
#define IDK_VOXELIZE_DILATED
#extension GL_GOOGLE_include_directive : require
#include "voxelize_fragment.glsl"

void main() {
    ivec3 voxel;
    vec3 radiance;
    vec4 facing;
    voxelFragment(voxel, radiance, facing);  // raises the key and keeps nothing
    discard;
}
