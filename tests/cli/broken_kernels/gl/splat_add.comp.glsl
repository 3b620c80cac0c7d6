#version 450 core
// BROKEN ON PURPOSE (tests/cli/conformance_checks.sh broken_kernel): the GL splat dropping the samples of bin 7
// (the hot bin). `idk conformance --shader-dir tests/cli/broken_kernels` must fail naming
// "float-atomics/splat [gl-interop]".
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
    if (bin < binCount && bin != 7u) atomicAdd(bins[bin], sampleValues[i]);
}
