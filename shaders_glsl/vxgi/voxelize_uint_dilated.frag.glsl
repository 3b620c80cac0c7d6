#version 460
// voxelize_uint_dilated.frag.glsl: voxelize_uint.frag behind voxelize.geom's triangle dilation (the "conservative-raster"
// fallback rung): the same atomics, plus the dilated triangle's bounds test in voxelFragment.
#define IDK_VOXELIZE_DILATED
#extension GL_GOOGLE_include_directive : require
#include "voxelize_fragment.glsl"

void main() {
    ivec3 voxel;
    vec3 radiance;
    if (!voxelFragment(voxel, radiance)) discard;
    imageAtomicMax(gVoxelsR32ui[p.accum[0]], voxel, floatBitsToUint(radiance.r) + 1u);
    imageAtomicMax(gVoxelsR32ui[p.accum[1]], voxel, floatBitsToUint(radiance.g) + 1u);
    imageAtomicMax(gVoxelsR32ui[p.accum[2]], voxel, floatBitsToUint(radiance.b) + 1u);
}
