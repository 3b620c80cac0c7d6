// gl_modify_kernel.hpp: the GL compute kernel of the interop round-trip tests (gl_interop_test.cpp and
// gl_sync_test.cpp): it maps every uint b[i] of the shared buffer to 3 b[i] + i and inverts every channel of the
// shared RGBA8 image, so a round trip that loses or repeats a step is visible in the bytes.
#pragma once

namespace idk::test {

inline constexpr const char* kModify = R"(#version 450 core
layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba8, binding = 0) uniform image2D image;
layout(std430, binding = 1) buffer Values { uint values[]; };
uniform uint count;
void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (all(lessThan(p, imageSize(image)))) imageStore(image, p, vec4(1.0) - imageLoad(image, p));
    uint i = gl_GlobalInvocationID.y * gl_NumWorkGroups.x * 8u + gl_GlobalInvocationID.x;
    if (i < count) values[i] = values[i] * 3u + i;
}
)";

}  // namespace idk::test
