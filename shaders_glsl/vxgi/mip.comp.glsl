#version 460
// mip.comp.glsl: one level of the voxel grid's mip chain: each voxel is the mean of the eight voxels of the finer
// level it covers (rgb is radiance times coverage, so the mean stays premultiplied and a half-empty parent is half
// transparent). Ports IDKEngine's VXGI mipmap shader (4x4x4 groups), which averages 7 trilinear taps instead: a
// plain box keeps each level's total light equal to the finer level's.
#extension GL_GOOGLE_include_directive : require
#include "vxgi_types.h"
#include "voxel_images.glsl"

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
layout(push_constant, scalar) uniform Push { VoxelMipPush p; };

void main() {
    ivec3 voxel = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(voxel, ivec3(p.dstSize)))) return;
    vec4 sum = vec4(0.0);
    for (int i = 0; i < 8; ++i)
        sum += imageLoad(gVoxelsRgba16f[p.src], voxel * 2 + ivec3(i & 1, (i >> 1) & 1, i >> 2));
    imageStore(gVoxelsRgba16f[p.dst], voxel, sum * 0.125);
}
