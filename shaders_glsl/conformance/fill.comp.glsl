#version 460
// fill.comp.glsl: writes one value into the first `count` elements of a bindless buffer (device-layer smoke test).
#extension GL_GOOGLE_include_directive : require
#include "interop.h"
#include "bindless.glsl"

layout(local_size_x = 64) in;
layout(push_constant, scalar) uniform Push { uint count; uint value; uint bufferIndex; } p;
IDK_BINDLESS_BUFFER(gUints, uint);

void main() {
    if (gl_GlobalInvocationID.x < p.count) gUints[p.bufferIndex].data[gl_GlobalInvocationID.x] = p.value;
}
