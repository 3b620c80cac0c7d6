#version 460
// voxelize_uint.frag.glsl: portable rung of "vxgi-atomics" (IDKEngine's fallback): r32ui images keep the
// per-channel max of the radiance and the facing with integer atomics on the float bits (monotone for non-negative
// floats), + 1 (the facing: + 2) so that 0 marks an empty voxel. A real GPU without float atomics takes this path; the merge pass decodes it.
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
