#version 460
// upscale_output.comp.glsl: writes the temporal upscaler's reconstruction (rgb) into the frame's output-size HDR
// image, with the geometry coverage (alpha) of the nearest render pixel, which the EXR output stores.
#extension GL_GOOGLE_include_directive : require
#include "scene_buffers.glsl"
#include "bindless.glsl"
#include "temporal_types.h"
#include "upscale_types.h"

layout(local_size_x = kTemporalGroupSize, local_size_y = kTemporalGroupSize) in;
layout(push_constant, scalar) uniform Push { UpscaleOutputPush p; };

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(uvec2(pixel), p.extent))) return;
    vec3 rgb = imageLoad(gImagesRgba16f[p.source], pixel).rgb;
    vec2 uv = (vec2(pixel) + 0.5) / vec2(p.extent);
    ivec2 q = min(ivec2(uv * vec2(p.renderExtent)), ivec2(p.renderExtent) - 1);
    float alpha = imageLoad(gImagesRgba16f[p.renderColor], q).a;
    imageStore(gImagesRgba16f[p.target], pixel, vec4(rgb, alpha));
}
