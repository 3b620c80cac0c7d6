#version 460
// trace_rays.comp.glsl: one invocation per ray: closest hit or any hit (spec constant) against one BLAS or a TLAS
// over BLAS instances, through include/bvh_traverse.glsl; rays and hits by buffer device address. The test and
// benchmark kernel of the GLSL traversal (the counterpart of IDKEngine's path-tracer FirstHit/NHit ray loops).
#extension GL_GOOGLE_include_directive : require
#include "interop.h"
#include "bvh_trace_types.h"

layout(constant_id = kSpecBvhStackSize) const uint kStackSize = 32;
layout(constant_id = kSpecBvhTlasStackSize) const uint kTlasStackSize = 32;
layout(constant_id = kSpecBvhTraceMode) const uint kTraceMode = kBvhTraceClosest;
layout(constant_id = kSpecBvhUseTlas) const uint kUseTlas = 0;
#define BVH_STACK_SIZE kStackSize
#define BVH_TLAS_STACK_SIZE kTlasStackSize
#include "bvh_traverse.glsl"

layout(local_size_x = kBvhTraceGroupSize) in;

layout(buffer_reference, scalar, buffer_reference_align = 16) readonly buffer RayArray { GpuBvhRay r[]; };
layout(buffer_reference, scalar, buffer_reference_align = 8) writeonly buffer HitArray { GpuBvhHit h[]; };

layout(push_constant, scalar) uniform Push { BvhTracePush p; };

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= p.count) return;
    GpuBvhRay ray = RayArray(p.rays).r[i];
    GpuBvhHit hit;
    if (kUseTlas != 0u) {
        GpuTlasDesc tlas = BvhTlasDescRef(p.tlas).d;
        hit = kTraceMode == kBvhTraceAny ? bvhAnyHitTlas(tlas, ray) : bvhClosestHitTlas(tlas, ray);
    } else {
        hit = kTraceMode == kBvhTraceAny ? bvhAnyHit(p.blas, ray) : bvhClosestHit(p.blas, ray);
    }
    HitArray(p.hits).h[i] = hit;
}
