#version 460
// fill_address.comp.glsl: writes value + i into `count` uints reached through a buffer device address (the path
// the engine uses for scene buffers larger than a storage-buffer descriptor's range, 128 MiB on lavapipe).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_buffer_reference : require
#include "interop.h"

layout(local_size_x = 64) in;
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer UintArray { uint data[]; };
layout(push_constant, scalar) uniform Push { UintArray target; uint count; uint value; } p;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i < p.count) p.target.data[i] = p.value + i;
}
