// wf_trace.h (GLSL include): the two traversal rungs behind one interface, wfTraceClosest / wfOccluded.
// Without PT_RAY_QUERY: our BVH (include/bvh_traverse.glsl, TLAS + BLAS by device address; with PT_BVH_WIDE the
// 8-wide compressed BLASes of include/bvh_traverse_wide.glsl under the same binary TLAS); an alpha-tested
// surface is passed by restarting the closest-hit query just past it. With PT_RAY_QUERY: VK_KHR_ray_query over the
// driver's acceleration structures (engine/vk/acceleration_structure.cpp); alpha is tested on candidates and
// confirmed. Both report the nearest surface that is not alpha-transparent, with the same hit record.
// The includer defines kPtHasAlpha (spec constant) and, for the BVH rung, the BVH stack sizes.
#ifndef IDK_WF_TRACE_H
#define IDK_WF_TRACE_H
#include "wf_common.h"

#ifdef PT_RAY_QUERY
#extension GL_EXT_ray_query : require
#elif defined(PT_BVH_WIDE)
#include "bvh_traverse_wide.glsl"
#define WF_BVH_CLOSEST_TLAS bvhClosestHitTlasWide
#define WF_BVH_ANY_TLAS bvhAnyHitTlasWide
#else
#include "bvh_traverse.glsl"
#define WF_BVH_CLOSEST_TLAS bvhClosestHitTlas
#define WF_BVH_ANY_TLAS bvhAnyHitTlas
#endif

// True when the surface at `hit` is opaque for this ray: MASK compares alpha with the cutoff, BLEND keeps the
// surface with probability alpha (stochastic transparency; `salt` decorrelates the choice per path and bounce,
// the triangle decorrelates surfaces along one ray; both rungs draw the same number for the same surface).
bool wfSurfaceOpaque(GpuPtSceneDesc s, GpuPtHit hit, uint salt) {
    GpuPtTraceInstance inst = WfInstanceRef(s.instances).i[hit.instance];
    uint material = WfUintRef(WfGeometryRef(s.geometries).g[inst.geometry].materials).u[hit.triangle];
    GpuMaterial m = WfMaterialRef(s.materials).m[material];
    if (m.alphaMode == kAlphaOpaque) return true;
    WfHitPoint h = wfHitPoint(s, hit.instance, hit.triangle, hit.u, hit.v);
    float alpha = m.baseColorFactor.a * wfSampleSlot(m.slots[kSlotBaseColor], h).a * h.color.a;
    if (m.alphaMode == kAlphaMask) return alpha >= m.alphaCutoff;
    float coverage = clamp(alpha, 0.0, 1.0);
    return coverage >= 1.0 || wfHashFloat(salt ^ wfHash(hit.triangle * 9781u + hit.instance * 6271u)) < coverage;
}

GpuPtHit wfMiss() {
    GpuPtHit h;
    h.t = uintBitsToFloat(0x7F800000u);  // +inf, as bvh::Hit on a miss
    h.triangle = kPtInvalid;
    h.instance = kPtInvalid;
    h.u = 0.0;
    h.v = 0.0;
    return h;
}

#ifdef PT_RAY_QUERY

GpuPtHit wfQuery(GpuPtSceneDesc s, vec3 origin, vec3 direction, float tMax, uint salt, bool anyHit) {
    rayQueryEXT rq;
    uint flags = kPtHasAlpha != 0u ? gl_RayFlagsNoneEXT : gl_RayFlagsOpaqueEXT;
    if (anyHit) flags |= gl_RayFlagsTerminateOnFirstHitEXT;
    rayQueryInitializeEXT(rq, accelerationStructureEXT(s.accel), flags, 0xFFu, origin, 0.0, direction, tMax);
    while (rayQueryProceedEXT(rq)) {
        if (rayQueryGetIntersectionTypeEXT(rq, false) != gl_RayQueryCandidateIntersectionTriangleEXT) continue;
        GpuPtHit c;
        c.t = rayQueryGetIntersectionTEXT(rq, false);
        c.instance = uint(rayQueryGetIntersectionInstanceCustomIndexEXT(rq, false));
        c.triangle = uint(rayQueryGetIntersectionPrimitiveIndexEXT(rq, false));
        vec2 b = rayQueryGetIntersectionBarycentricsEXT(rq, false);
        c.u = b.x;
        c.v = b.y;
        if (wfSurfaceOpaque(s, c, salt)) rayQueryConfirmIntersectionEXT(rq);
    }
    if (rayQueryGetIntersectionTypeEXT(rq, true) != gl_RayQueryCommittedIntersectionTriangleEXT) return wfMiss();
    GpuPtHit h;
    h.t = rayQueryGetIntersectionTEXT(rq, true);
    h.instance = uint(rayQueryGetIntersectionInstanceCustomIndexEXT(rq, true));
    h.triangle = uint(rayQueryGetIntersectionPrimitiveIndexEXT(rq, true));
    vec2 b = rayQueryGetIntersectionBarycentricsEXT(rq, true);
    h.u = b.x;
    h.v = b.y;
    return h;
}

GpuPtHit wfTraceClosest(GpuPtSceneDesc s, vec3 origin, vec3 direction, float tMax, uint salt) {
    return wfQuery(s, origin, direction, tMax, salt, false);
}
bool wfOccluded(GpuPtSceneDesc s, vec3 origin, vec3 direction, float tMax, uint salt) {
    return wfQuery(s, origin, direction, tMax, salt, true).triangle != kPtInvalid;
}

#else

GpuPtHit wfBvhHit(GpuBvhHit b) {
    GpuPtHit h;
    h.t = b.t;
    h.triangle = b.triangleId;
    h.instance = b.instanceId;
    h.u = b.u;
    h.v = b.v;
    return h;
}

GpuPtHit wfTraceClosest(GpuPtSceneDesc s, vec3 origin, vec3 direction, float tMax, uint salt) {
    GpuTlasDesc tlas = BvhTlasDescRef(s.tlas).d;
    GpuBvhRay ray;
    ray.origin = origin;
    ray.direction = direction;
    ray.tMin = 0.0;
    ray.tMax = tMax;
    for (uint k = 0u; k <= kPtMaxAlphaSkips; ++k) {
        GpuPtHit h = wfBvhHit(WF_BVH_CLOSEST_TLAS(tlas, ray));
        if (h.triangle == kPtInvalid || kPtHasAlpha == 0u || wfSurfaceOpaque(s, h, salt)) return h;
        ray.tMin = h.t;  // open interval: continue just past the transparent surface
    }
    return wfMiss();
}

bool wfOccluded(GpuPtSceneDesc s, vec3 origin, vec3 direction, float tMax, uint salt) {
    if (kPtHasAlpha == 0u) {
        GpuBvhRay ray;
        ray.origin = origin;
        ray.direction = direction;
        ray.tMin = 0.0;
        ray.tMax = tMax;
        return (WF_BVH_ANY_TLAS(BvhTlasDescRef(s.tlas).d, ray).flags & kBvhHitFlagHit) != 0u;
    }
    return wfTraceClosest(s, origin, direction, tMax, salt).triangle != kPtInvalid;
}

#endif

#endif
