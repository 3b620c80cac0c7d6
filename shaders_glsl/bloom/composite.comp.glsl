#version 460
// composite.comp.glsl: blends the bloom into the HDR image: mix(hdr, bloom / levels, strength), the bloom read
// bilinearly from half resolution. The upsample chain sums `levels` blurred copies of the image, each with the
// image's mean, so dividing by their count and blending keeps the image's total energy (CoD: Advanced Warfare's
// energy-conserving bloom). IDKEngine adds the unnormalized bloom in its tonemap pass instead.
#extension GL_GOOGLE_include_directive : require
#include "bindless.glsl"
#include "bloom_types.h"
#include "storage_bilinear.glsl"

layout(local_size_x = kBloomGroupSize, local_size_y = kBloomGroupSize) in;
layout(push_constant, scalar) uniform Push { BloomCompositePush p; };

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(uvec2(pixel), p.dstSize))) return;
    vec4 hdr = imageLoad(gImagesRgba16f[p.hdr], pixel);
    vec2 position = (vec2(pixel) + 0.5) * vec2(p.bloomSize) / vec2(p.dstSize);
    vec3 bloom = storageBilinear(p.bloom, position, p.bloomSize) / p.levels;
    imageStore(gImagesRgba16f[p.hdr], pixel, vec4(mix(hdr.rgb, bloom, p.strength), hdr.a));
}
