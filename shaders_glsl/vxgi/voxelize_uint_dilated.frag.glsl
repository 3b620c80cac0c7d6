#version 460
// voxelize_uint_dilated.frag.glsl: voxelize_uint.frag behind voxelize.geom's triangle dilation (the "conservative-raster"
// fallback rung): the same atomics, plus the dilated triangle's bounds test in voxelFragment.
#define IDK_VOXELIZE_DILATED
#extension GL_GOOGLE_include_directive : require
#include "voxelize_fragment.glsl"

void main() {
    ivec3 voxel;
    vec3 radiance;
    vec4 facing;
    if (!voxelFragment(voxel, radiance, facing)) discard;
    // Stored values are never 0: the one max that returns 0 is the voxel's first fragment this frame.
    if (imageAtomicMax(gVoxelsR32ui[p.accum[0]], voxel, floatBitsToUint(radiance.r) + 1u) == 0u)
        appendTouchedVoxel(voxel);
    imageAtomicMax(gVoxelsR32ui[p.accum[1]], voxel, floatBitsToUint(radiance.g) + 1u);
    imageAtomicMax(gVoxelsR32ui[p.accum[2]], voxel, floatBitsToUint(radiance.b) + 1u);
    for (uint c = 0u; c < 4u; ++c)  // biased positive: the bits order like the floats and are never 0
        imageAtomicMax(gVoxelsR32ui[p.accum[kVoxelAccumFacing + c]], voxel, floatBitsToUint(facing[c] + kVoxelFacingBias));
}
