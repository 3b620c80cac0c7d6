#version 460
// layers_resolve.comp.glsl: the fixed-layer OIT rung's resolve: the pixel's slots are already in front-to-back
// order (include/oit_layers.glsl), so they are composited front to back ("under": C += T a c, T *= 1 - a) in fp32 and
// the result laid over the lit image once: hdr = C + T hdr. Equal to the sorted "over" chain up to rounding.
// Ports IDKEngine's ResolveTransparent/compute.glsl (which first insertion-sorts its arrival-ordered slots).
#extension GL_GOOGLE_include_directive : require
#include "bindless.glsl"
#include "oit_layers.glsl"

layout(local_size_x = kOitGroupSize, local_size_y = kOitGroupSize) in;
layout(push_constant, scalar) uniform Push { OitResolvePush p; };

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, imageSize(gImagesRgba16f[p.target])))) return;
    uint i = oitPixel(p.layers, pixel);
    uint claimed = OitWords(p.layers.claims).data[i];
    if (claimed == 0u) return;  // no transparent fragment here: the pixel is left alone
    vec3 c = vec3(0.0);
    float t = 1.0;
    for (uint s = 0u; s < kOitLayerCount; ++s) {
        if ((claimed & (1u << s)) == 0u) continue;
        uvec2 packed = OitColors(p.layers.colors).data[s * p.layers.pixelCount + i];
        vec2 rg = unpackHalf2x16(packed.x), ba = unpackHalf2x16(packed.y);
        float a = clamp(ba.y, 0.0, 1.0);
        c += t * a * vec3(rg, ba.x);
        t *= 1.0 - a;
    }
    vec4 hdr = imageLoad(gImagesRgba16f[p.target], pixel);
    imageStore(gImagesRgba16f[p.target], pixel, vec4(c + t * hdr.rgb, hdr.a));
}
