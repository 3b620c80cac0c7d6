#version 450 core
// vxgi_accumulate_fp16.comp.glsl (OpenGL, compiled by the GL driver at run time, not SPIR-V): the RGBA16F-image
// variant of the gl-interop rung of "vxgi-atomics" ("vxgi-gl-accumulate" = native; the float-buffer program,
// vxgi_accumulate.comp, is its fallback; engine/passes/vxgi_gl_accumulate.cpp). Adds each record the voxelization
// appended (shaders_glsl/shared/vxgi_types.h, kVoxelRecord*) into two GL RGBA16F 3D images with
// GL_NV_shader_atomic_fp16_vector's f16vec4 imageAtomicAdd: premultiplied (r, g, b, coverage) and the facing's
// (x, y, z, w), one vector atomic each where the float program takes eight scalar float atomics, plus the count
// with a core uint atomicAdd. vxgi_resolve_fp16.comp then writes them as the float sums Vulkan's merge averages.
// Half precision: 11 significant bits per sum (the grid itself is RGBA16F), exact counts to 2048 fragments in the
// coverage sum (the uint count stays exact), and a radiance sum above 65504 saturates to infinity (an emitter of
// that radiance would need the float program).
// The rung's extension first: a driver without it names it in the compile error (tests/conformance/gl).
#extension GL_NV_shader_atomic_fp16_vector : require
#extension GL_NV_gpu_shader5 : require  // f16vec4
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Records { uint records[]; };
layout(std430, binding = 1) buffer Counts { uint counts[]; };
layout(binding = 0, rgba16f) uniform coherent image3D radianceSums;  // premultiplied rgb, coverage
layout(binding = 1, rgba16f) uniform coherent image3D facingSums;
uniform uint capacity;  // records the buffer holds
uniform uint gridSize;  // n: a record's voxel index is below n^3
const uint kHeaderWords = 4u, kRecordWords = 9u;

float recordFloat(uint word) { return uintBitsToFloat(records[word]); }

void main() {
    // 2D dispatch: more records than one dimension's 65535 groups of 64 hold.
    uint i = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * 64u + gl_LocalInvocationIndex;
    if (i >= min(records[0], capacity)) return;
    uint base = kHeaderWords + i * kRecordWords;
    uint voxel = records[base];
    if (voxel >= gridSize * gridSize * gridSize) return;
    ivec3 p = ivec3(voxel % gridSize, (voxel / gridSize) % gridSize, voxel / (gridSize * gridSize));
    f16vec4 radiance = f16vec4(recordFloat(base + 1u), recordFloat(base + 2u), recordFloat(base + 3u),
                               recordFloat(base + 4u));
    f16vec4 facing = f16vec4(recordFloat(base + 5u), recordFloat(base + 6u), recordFloat(base + 7u),
                             recordFloat(base + 8u));
    imageAtomicAdd(radianceSums, p, radiance);
    imageAtomicAdd(facingSums, p, facing);
    atomicAdd(counts[voxel], 1u);
}
