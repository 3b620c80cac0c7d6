#version 460
// offset_ray_origin.comp.glsl: applies bvhOffsetRayOrigin (include/bvh_traverse.glsl, the port of
// bvh::offsetRayOrigin: Waechter & Binder's self-intersection offset) to arrays of points and normals, so the
// conformance test can compare it bit for bit with the C++ function.
#extension GL_GOOGLE_include_directive : require
#include "interop.h"
#include "bvh_trace_types.h"
#include "bvh_traverse.glsl"

layout(local_size_x = 64) in;
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer Vec3In { vec3 v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) writeonly buffer Vec3Out { vec3 v[]; };
layout(push_constant, scalar) uniform Push { BvhOffsetPush p; };

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= p.count) return;
    Vec3Out(p.results).v[i] = bvhOffsetRayOrigin(Vec3In(p.points).v[i], Vec3In(p.normals).v[i]);
}
