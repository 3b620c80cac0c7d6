// wf_shadow_stage.h (GLSL include): body of shadow_bvh / shadow_rq.comp.glsl (the rung is chosen by PT_RAY_QUERY).
#include "wf_stage_spec.h"
#include "wf_trace.h"

layout(local_size_x = kPtGroupSize) in;

void main() {
    WfQueueRef queue = WfQueueRef(pc.shadow);
    uint i = gl_GlobalInvocationID.x;
    if (i >= queue.count) return;
    uint index = queue.items[i];
    GpuPtShadowRay ray = WfShadowRayRef(pc.shadowRays).r[index];
    GpuPtSceneDesc s = WfSceneRef(pc.scene).d;
    uint salt = wfHash(ray.pixel * 0x9E3779B9u ^ wfHash(pc.sampleIndex * 131u + pc.bounce) ^ pc.seed) ^ 0x5bd1e995u;
    if (wfOccluded(s, ray.origin, ray.direction, ray.tMax, salt)) return;
    WfPathRef paths = WfPathRef(pc.paths);
    paths.p[ray.pixel].radiance += ray.contribution;
}
