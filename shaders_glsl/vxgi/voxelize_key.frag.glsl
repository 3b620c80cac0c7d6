#version 460
// voxelize_key.frag.glsl: the voxelization's key pass (every rung of "vxgi-atomics", before the accumulating draw):
// each fragment raises its voxel's depth key of its facing class to its own (include/voxelize_key.glsl,
// shared/vxgi_depth_key.h), so the accumulating pass keeps only each class's front-most surface. No lighting: the
// pass costs the raster and the material's alpha test, not the shadow lookups.
#define IDK_VOXELIZE_KEY_PASS
#extension GL_GOOGLE_include_directive : require
#include "voxelize_fragment.glsl"

void main() {
    ivec3 voxel;
    vec3 radiance;
    vec4 facing;
    voxelFragment(voxel, radiance, facing);  // raises the key and keeps nothing
    discard;
}
