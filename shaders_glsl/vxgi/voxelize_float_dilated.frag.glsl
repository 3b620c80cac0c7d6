#version 460
// voxelize_float_dilated.frag.glsl: voxelize_float.frag behind voxelize.geom's triangle dilation (the "conservative-raster"
// fallback rung): the same atomics, plus the dilated triangle's bounds test in voxelFragment.
#define IDK_VOXELIZE_DILATED
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_atomic_float : require
#include "voxelize_fragment.glsl"

void main() {
    ivec3 voxel;
    vec3 radiance;
    vec4 facing;
    if (!voxelFragment(voxel, radiance, facing)) discard;
    imageAtomicAdd(gVoxelsR32f[p.accum[0]], voxel, radiance.r);
    imageAtomicAdd(gVoxelsR32f[p.accum[1]], voxel, radiance.g);
    imageAtomicAdd(gVoxelsR32f[p.accum[2]], voxel, radiance.b);
    for (uint c = 0u; c < 4u; ++c) imageAtomicAdd(gVoxelsR32f[p.accum[kVoxelAccumFacing + c]], voxel, facing[c]);
    // The count is exact (whole numbers): the one add that returns 0 is the voxel's first fragment this frame.
    if (imageAtomicAdd(gVoxelsR32f[p.accum[kVoxelAccumCount]], voxel, 1.0) == 0.0) appendTouchedVoxel(voxel);
}
