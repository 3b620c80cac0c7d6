#version 450 core
// splat_add.comp.glsl (OpenGL, compiled by the GL driver at run time, not SPIR-V): the GL-interop rung of the
// float-atomics ladder, GL_NV_shader_atomic_float's atomicAdd on a float SSBO that is Vulkan memory
// (engine/render/float_splat.cpp). Same contract as shaders_glsl/shared/splat_push.h, with bindings for buffers.
#extension GL_NV_shader_atomic_float : require
layout(local_size_x = 64) in;
layout(std430, binding = 0) buffer Bins { float bins[]; };
layout(std430, binding = 1) readonly buffer SampleBins { uint sampleBins[]; };
layout(std430, binding = 2) readonly buffer SampleValues { float sampleValues[]; };
uniform uint count;
uniform uint binCount;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= count) return;
    uint bin = sampleBins[i];
    if (bin < binCount) atomicAdd(bins[bin], sampleValues[i]);
}
