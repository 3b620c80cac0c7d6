#version 460
// downsample.comp.glsl: one level of the screen-space transmission's opaque-colour chain (passes/transmission.cpp):
// level 0 copies the lit opaque frame (scale 1), each next level is the box mean of the 2x2 texels of the level above
// (scale 2, clamped at odd edges), so the forward pass can blur the refracted background by roughness. The role of
// the mipmapped transmission framebuffer of the glTF transmission extension's reference renderer (not in IDKEngine).
#extension GL_GOOGLE_include_directive : require
#include "bindless.glsl"
#include "transmission_types.h"

layout(local_size_x = kTransmissionGroupSize, local_size_y = kTransmissionGroupSize) in;
layout(push_constant, scalar) uniform Push { TransmissionDownPush p; };

vec4 load(ivec2 q) { return imageLoad(gImagesRgba16f[p.source], min(q, ivec2(p.sourceSize) - 1)); }

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(uvec2(pixel), p.targetSize))) return;
    vec4 c;
    if (p.scale == 1u) {
        c = load(pixel);
    } else {
        ivec2 s = 2 * pixel;
        c = 0.25 * (load(s) + load(s + ivec2(1, 0)) + load(s + ivec2(0, 1)) + load(s + ivec2(1, 1)));
    }
    imageStore(gImagesRgba16f[p.target], pixel, c);
}
