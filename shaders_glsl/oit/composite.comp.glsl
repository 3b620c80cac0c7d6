#version 460
// composite.comp.glsl: resolves weighted blended OIT over the lit image: transmittance T = exp(-sum -ln(1 - a))
// = prod (1 - a), the weighted average colour sum(c a w) / sum(a w) covering 1 - T of the pixel:
// hdr = avg (1 - T) + hdr T. Exact for one layer; an approximation for more (the error is reported against the
// sorted rung). Ports the resolve of McGuire & Bavoil 2013.
#extension GL_GOOGLE_include_directive : require
#include "bindless.glsl"
#include "oit_types.h"

layout(local_size_x = kOitGroupSize, local_size_y = kOitGroupSize) in;
layout(push_constant, scalar) uniform Push { OitCompositePush p; };

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, imageSize(gImagesRgba16f[p.target])))) return;
    vec4 accum = imageLoad(gImagesRgba16f[p.accum], pixel);
    float logSum = imageLoad(gImagesRgba16f[p.revealage], pixel).r;
    if (accum.a <= 0.0) return;  // no transparent fragment here
    float t = exp(-logSum);
    vec3 average = accum.rgb / max(accum.a, 1e-6);
    vec4 hdr = imageLoad(gImagesRgba16f[p.target], pixel);
    imageStore(gImagesRgba16f[p.target], pixel, vec4(average * (1.0 - t) + hdr.rgb * t, hdr.a));
}
