#version 460
// camera_motion.comp.glsl: per-pixel motion in UV units per frame from camera movement alone: the pixel's surface
// point (from the G-buffer depth) re-projected with the previous frame's view-projection. A stand-in for the
// motion vectors of issue 12 (which add object and skinned motion); background pixels move with the camera's
// rotation (depth 1 re-projects a point on the far plane). The VRS classifier reads the result.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_buffer_reference : require
#include "bindless.glsl"
#include "vrs_types.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push { VrsMotionPush p; };
layout(buffer_reference, scalar, buffer_reference_align = 8) writeonly buffer VelocityRef { vec2 v[]; };

void main() {
    uvec2 pixel = gl_GlobalInvocationID.xy;
    if (pixel.x >= p.width || pixel.y >= p.height) return;
    float depth = imageLoad(gImagesR32f[p.depth], ivec2(pixel)).r;
    vec2 uv = (vec2(pixel) + 0.5) / vec2(p.width, p.height);
    vec4 previous = p.currentToPrevious * vec4(uv * 2.0 - 1.0, depth, 1.0);
    vec2 previousUv = previous.w > 0.0 ? (previous.xy / previous.w) * 0.5 + 0.5 : uv;  // behind the old eye: none
    VelocityRef(p.velocity).v[pixel.y * p.width + pixel.x] = uv - previousUv;
}
