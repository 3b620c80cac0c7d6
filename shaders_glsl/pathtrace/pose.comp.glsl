#version 460
// pose.comp.glsl: one invocation per vertex: copies a posed vertex (position, normal, tangent in node space) from
// the rasterizer's deformed copy (skinning/skinning.comp.glsl wrote it) into a GPU-posed path-tracing geometry:
// the shading vertex and the BLAS position the refit (bvh/refit.comp.glsl) reads next. UVs and colours do not
// move with the pose and stay as uploaded. No IDKEngine counterpart: its path tracer traces the rasterizer's
// vertex buffer directly, ours keeps its own layout (GpuPtVertex) and triangle numbering.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_buffer_reference : require
#include "interop.h"
#include "scene_types.h"
#include "pt_wavefront.h"
#include "pt_pose_types.h"

layout(local_size_x = kPtPoseGroupSize) in;
layout(push_constant, scalar) uniform Push { PtPosePush p; };

layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer Source { GpuVertex data[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Vertices { GpuPtVertex data[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Positions { vec3 data[]; };

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= p.count) return;
    GpuVertex v = Source(p.source).data[p.sourceFirst + i];
    uint d = p.destFirst + i;
    Vertices(p.vertices).data[d].position = v.position;
    Vertices(p.vertices).data[d].normal = v.normal;
    Vertices(p.vertices).data[d].tangent = v.tangent;
    Positions(p.positions).data[d] = v.position;
}
