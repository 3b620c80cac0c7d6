#version 460
// voxelize_record_dilated.frag.glsl: voxelize_record.frag behind voxelize.geom's triangle dilation (the
// "conservative-raster" fallback rung): the same records, plus the dilated triangle's bounds test in voxelFragment.
#define IDK_VOXELIZE_DILATED
#extension GL_GOOGLE_include_directive : require
#include "voxelize_fragment.glsl"
#include "voxelize_record.glsl"

void main() {
    ivec3 voxel;
    vec3 radiance;
    vec4 facing;
    if (!voxelFragment(voxel, radiance, facing)) discard;
    appendVoxelRecord(voxel, radiance, facing);
}
