#version 460
// BROKEN ON PURPOSE (tests/cli/conformance_checks.sh broken_kernel): the native splat adding every value twice.
// `idk conformance --shader-dir tests/cli/broken_kernels` must fail naming "float-atomics/splat [native]".
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
    if (bin < p.binCount) atomicAdd(gFloats[p.bins].data[bin], 2.0 * gFloats[p.sampleValues].data[i]);
}
