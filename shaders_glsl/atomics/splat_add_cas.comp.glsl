#version 460
// splat_add_cas.comp.glsl: the portable rung of the float-atomics ladder: float add emulated by a
// compare-and-swap loop on the bin's bits (core Vulkan uint atomics only). See shared/splat_push.h.
// On a GPU every colliding invocation retries, so a hot bin costs one round trip per contender; the native
// float atomic (or the GL rung's GL_NV_shader_atomic_float) resolves collisions in the memory unit instead.
#extension GL_GOOGLE_include_directive : require
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
    if (bin >= p.binCount) return;
    float value = gFloats[p.sampleValues].data[i];
    uint expected = gUints[p.bins].data[bin];
    for (;;) {
        uint seen = atomicCompSwap(gUints[p.bins].data[bin], expected, floatBitsToUint(uintBitsToFloat(expected) + value));
        if (seen == expected) break;
        expected = seen;
    }
}
