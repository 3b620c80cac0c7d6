#version 460
// velocity.comp.glsl: the VRS classifier's speed input: each pixel's motion in UV units per frame (current uv -
// previous uv), from the temporal motion vectors (passes/motion_vectors.cpp: instance, skinned/morphed and camera
// motion of the surface the G-buffer kept) and, for background pixels (which the motion pass leaves at zero), the
// camera's reprojection: pixelMotion of include/temporal_common.glsl, the same definition TAA and the upscaler use.
// Written as a plain vec2 field so the classifier's input is the one its CPU oracle takes (frame/vrs_oracle.hpp).
// A real GPU would fold this into the classifier's loads (one 8-byte write and read per pixel fewer); lavapipe's
// cost is the same either way.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_buffer_reference : require
#include "bindless.glsl"
#include "temporal_types.h"
#include "temporal_common.glsl"
#include "vrs_types.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push { VrsVelocityPush p; };
layout(buffer_reference, scalar, buffer_reference_align = 8) writeonly buffer VelocityRef { vec2 v[]; };

void main() {
    uvec2 pixel = gl_GlobalInvocationID.xy;
    if (pixel.x >= p.width || pixel.y >= p.height) return;
    GpuTemporalFrame t = TemporalBuffer(p.temporal).t;
    VelocityRef(p.velocity).v[pixel.y * p.width + pixel.x] = pixelMotion(t, p.motion, p.depth, ivec2(pixel));
}
