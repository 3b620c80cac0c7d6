#version 450 core
// vxgi_accumulate.comp.glsl (OpenGL, compiled by the GL driver at run time, not SPIR-V): the gl-interop rung of
// "vxgi-atomics" (engine/passes/vxgi_gl_accumulate.cpp). Adds each record the voxelization appended (layout:
// shaders_glsl/shared/vxgi_types.h, kVoxelRecord*) into its voxel's sums with GL_NV_shader_atomic_float's float
// atomicAdd on Vulkan memory: premultiplied r, g, b, coverage, the facing's 4 components and a count
// (kVoxelSumWords = 9 per voxel). Vulkan's
// merge pass averages them. The count of records comes from the header (word 0 counts every fragment, also those
// past the capacity): with semaphore hand-offs (engine/gl/gl_sync.hpp) the host does not know it when it
// dispatches, and dispatches for the whole capacity.
#extension GL_NV_shader_atomic_float : require
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Records { uint records[]; };
layout(std430, binding = 1) buffer Sums { float sums[]; };
uniform uint capacity;    // records the buffer holds
uniform uint voxelCount;  // n^3: a record's voxel index is below it
const uint kHeaderWords = 4u, kRecordWords = 9u, kSumWords = 9u;

void main() {
    // 2D dispatch: more records than one dimension's 65535 groups of 64 hold.
    uint i = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * 64u + gl_LocalInvocationIndex;
    if (i >= min(records[0], capacity)) return;
    uint base = kHeaderWords + i * kRecordWords;
    uint voxel = records[base];
    if (voxel >= voxelCount) return;
    uint dst = voxel * kSumWords;
    for (uint c = 0u; c < 8u; ++c) atomicAdd(sums[dst + c], uintBitsToFloat(records[base + 1u + c]));
    atomicAdd(sums[dst + 8u], 1.0);
}
