// wf_trace_stage.h (GLSL include): body of trace_bvh / trace_rq.comp.glsl (the rung is chosen by PT_RAY_QUERY).
#include "wf_stage_spec.h"
#include "wf_trace.h"

layout(local_size_x = kPtGroupSize) in;

// Sort key of a traced ray: hit rays grouped by material, then by direction octant (coherent shading and texture
// access); misses after all hits. Dead queue slots keep kPtSortKeyDead (filled before this stage).
uint wfSortKey(GpuPtSceneDesc s, GpuPtHit hit, vec3 direction) {
    if (hit.triangle == kPtInvalid) return kPtSortKeyMiss;
    GpuPtTraceInstance inst = WfInstanceRef(s.instances).i[hit.instance];
    uint material = WfUintRef(WfGeometryRef(s.geometries).g[inst.geometry].materials).u[hit.triangle];
    uint octant = (direction.x < 0.0 ? 1u : 0u) | (direction.y < 0.0 ? 2u : 0u) | (direction.z < 0.0 ? 4u : 0u);
    return min((material << 3u) | octant, kPtSortKeyMiss - 1u);
}

void main() {
    WfQueueRef queue = WfQueueRef(pc.queueIn);
    uint i = gl_GlobalInvocationID.x;
    if (i >= queue.count) return;
    uint pixel = queue.items[i];
    GpuPtSceneDesc s = WfSceneRef(pc.scene).d;
    GpuPtPath path = WfPathRef(pc.paths).p[pixel];
    uint salt = wfHash(pixel * 0x9E3779B9u ^ wfHash(pc.sampleIndex * 131u + pc.bounce) ^ pc.seed);
    GpuPtHit hit = wfTraceClosest(s, path.origin, path.direction, uintBitsToFloat(0x7F800000u), salt);
    WfHitRef(pc.hits).h[pixel] = hit;
    if (pc.aux != 0ul) WfUintRef(pc.aux).u[i] = wfSortKey(s, hit, path.direction);
}
