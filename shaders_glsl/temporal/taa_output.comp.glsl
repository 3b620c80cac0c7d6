#version 460
// taa_output.comp.glsl: writes the resolved colour into the frame's HDR image (rgb), keeping that image's alpha
// (geometry coverage, which the EXR output stores); the resolved image's alpha is the TAA sample weight.
#extension GL_GOOGLE_include_directive : require
#include "scene_buffers.glsl"
#include "bindless.glsl"
#include "temporal_types.h"

layout(local_size_x = kTemporalGroupSize, local_size_y = kTemporalGroupSize) in;
layout(push_constant, scalar) uniform Push { TaaOutputPush p; };

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(uvec2(pixel), p.extent))) return;
    vec3 rgb = imageLoad(gImagesRgba16f[p.source], pixel).rgb;
    float alpha = imageLoad(gImagesRgba16f[p.target], pixel).a;
    imageStore(gImagesRgba16f[p.target], pixel, vec4(rgb, alpha));
}
