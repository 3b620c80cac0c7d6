#version 460
// splat_add_native.comp.glsl: the "native" rung of the float-atomics ladder: one float atomicAdd per sample into
// its bin (VK_EXT_shader_atomic_float, shaderBufferFloat32AtomicAdd). See shared/splat_push.h.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_atomic_float : require
#include "interop.h"
#include "bindless.glsl"
#include "splat_push.h"

layout(local_size_x = kSplatGroupSize) in;
layout(push_constant, scalar) uniform Push { SplatPush p; };

IDK_BINDLESS_BUFFER(gFloats, float);
IDK_BINDLESS_BUFFER(gUints, uint);

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= p.count) return;
    uint bin = gUints[p.sampleBins].data[i];
    if (bin < p.binCount) atomicAdd(gFloats[p.bins].data[bin], gFloats[p.sampleValues].data[i]);
}
