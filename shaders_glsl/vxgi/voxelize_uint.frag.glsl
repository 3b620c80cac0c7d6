#version 460
// voxelize_uint.frag.glsl: portable rung of "vxgi-atomics" (IDKEngine's fallback): three r32ui images keep the
// per-channel max with integer atomics on the float bits (monotone for non-negative floats), + 1 so that 0 marks
// an empty voxel. A real GPU without float atomics takes this path; the merge pass decodes it.
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
