#version 460
// trace_rays_rq.comp.glsl: the peer of trace_rays(_wide).comp.glsl in the BVH benchmarks: closest hit of each ray
// with VK_KHR_ray_query against the driver's acceleration structure (engine/vk/acceleration_structure.hpp), opaque
// triangles, same ray and hit records. BvhTracePush::tlas holds the top-level structure's device address. The
// driver's interval is closed ([tMin, tMax]) where ours is open, so rays ending exactly on a surface may differ.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_ray_query : require
#extension GL_EXT_buffer_reference : require
#include "interop.h"
#include "bvh_trace_types.h"

layout(local_size_x = kBvhTraceGroupSize) in;

layout(buffer_reference, scalar, buffer_reference_align = 16) readonly buffer RayArray { GpuBvhRay r[]; };
layout(buffer_reference, scalar, buffer_reference_align = 8) writeonly buffer HitArray { GpuBvhHit h[]; };

layout(push_constant, scalar) uniform Push { BvhTracePush p; };

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= p.count) return;
    GpuBvhRay ray = RayArray(p.rays).r[i];
    rayQueryEXT rq;
    rayQueryInitializeEXT(rq, accelerationStructureEXT(p.tlas), gl_RayFlagsOpaqueEXT, 0xFFu, ray.origin, ray.tMin,
                          ray.direction, ray.tMax);
    while (rayQueryProceedEXT(rq)) {
    }
    GpuBvhHit hit;
    hit.t = uintBitsToFloat(0x7F800000u);
    hit.triangleId = kBvhInvalidIndex;
    hit.instanceId = kBvhInvalidIndex;
    hit.flags = 0u;
    hit.u = 0.0;
    hit.v = 0.0;
    if (rayQueryGetIntersectionTypeEXT(rq, true) == gl_RayQueryCommittedIntersectionTriangleEXT) {
        hit.t = rayQueryGetIntersectionTEXT(rq, true);
        hit.triangleId = uint(rayQueryGetIntersectionPrimitiveIndexEXT(rq, true));
        vec2 b = rayQueryGetIntersectionBarycentricsEXT(rq, true);
        hit.u = b.x;
        hit.v = b.y;
        hit.flags = kBvhHitFlagHit;
    }
    HitArray(p.hits).h[i] = hit;
}
