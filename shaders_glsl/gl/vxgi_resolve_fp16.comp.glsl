#version 450 core
// vxgi_resolve_fp16.comp.glsl (OpenGL, compiled at run time): the second step of the RGBA16F-image variant of the
// gl-interop rung (after vxgi_accumulate_fp16.comp; engine/passes/vxgi_gl_accumulate.cpp): per voxel, the two
// RGBA16F sums and the uint count become the shared float sums buffer's kVoxelSumWords = 9 words
// (shaders_glsl/shared/vxgi_types.h), the layout Vulkan's merge pass averages, as the float program writes it.
// Needs no extension (llvmpipe compiles and runs it: tests/conformance/gl).
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
layout(std430, binding = 1) readonly buffer Counts { uint counts[]; };
layout(std430, binding = 2) writeonly buffer Sums { float sums[]; };
layout(binding = 0, rgba16f) uniform readonly image3D radianceSums;
layout(binding = 1, rgba16f) uniform readonly image3D facingSums;
uniform uint gridSize;
const uint kSumWords = 9u;

void main() {
    uvec3 v = gl_GlobalInvocationID;
    if (any(greaterThanEqual(v, uvec3(gridSize)))) return;
    uint voxel = v.x + gridSize * (v.y + gridSize * v.z);
    vec4 radiance = imageLoad(radianceSums, ivec3(v));
    vec4 facing = imageLoad(facingSums, ivec3(v));
    uint dst = voxel * kSumWords;
    for (uint c = 0u; c < 4u; ++c) {
        sums[dst + c] = radiance[c];
        sums[dst + 4u + c] = facing[c];
    }
    sums[dst + 8u] = float(counts[voxel]);
}
