#version 460
// BROKEN ON PURPOSE (tests/cli/conformance_checks.sh broken_bvh_walk): the 8-wide walk losing one closest hit in 97.
// `idk conformance --shader-dir tests/cli/broken_kernels --filter bvh/blas` must fail naming "bvh/blas 8-wide"
// while "bvh/blas binary" (another shader) passes.
#extension GL_GOOGLE_include_directive : require
#include "interop.h"
#include "bvh_trace_types.h"

layout(constant_id = kSpecBvhStackSize) const uint kStackSize = 64;
layout(constant_id = kSpecBvhTlasStackSize) const uint kTlasStackSize = 32;
layout(constant_id = kSpecBvhTraceMode) const uint kTraceMode = kBvhTraceClosest;
layout(constant_id = kSpecBvhUseTlas) const uint kUseTlas = 0;
#define BVH_WIDE_STACK_SIZE kStackSize
#define BVH_TLAS_STACK_SIZE kTlasStackSize
#include "bvh_traverse_wide.glsl"

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
        hit = kTraceMode == kBvhTraceAny ? bvhAnyHitTlasWide(tlas, ray) : bvhClosestHitTlasWide(tlas, ray);
    } else {
        hit = kTraceMode == kBvhTraceAny ? bvhAnyHitWide(p.blas, ray) : bvhClosestHitWide(p.blas, ray);
    }
    if (kTraceMode == kBvhTraceClosest && i % 97u == 3u) hit.flags = 0u;  // the planted bug: a miss
    HitArray(p.hits).h[i] = hit;
}
