#version 460
// shade.comp.glsl: wavefront shading stage, one invocation per ray of the input queue (indirect dispatch): adds
// what the ray found (emission, or the environment on a miss), writes the first-hit guides at bounce 0, emits a
// next-event shadow ray into the shadow queue and the extension ray into the next queue (alive-ray compaction by
// atomic append), with Russian roulette. Port of the shading half of IDKEngine NHit / FirstHit, with light
// sampling and MIS that the original lacks (reference 2.1, section 5).
#extension GL_GOOGLE_include_directive : require
#include "wf_stage_spec.h"
#include "wf_shading.h"

layout(local_size_x = kPtGroupSize) in;

void main() {
    WfQueueRef queue = WfQueueRef(pc.queueIn);
    uint i = gl_GlobalInvocationID.x;
    if (i >= queue.count) return;
    uint pixel = queue.items[i];
    GpuPtSceneDesc s = WfSceneRef(pc.scene).d;
    gPtAlbedoTables = s.albedoTables;
    GpuPtPath path = WfPathRef(pc.paths).p[pixel];
    GpuPtHit hit = WfHitRef(pc.hits).h[pixel];
    PtRng rng = wfResumeRng(path.rngState, pixel, pc.sampleIndex, pc.seed, pc.flags);
    WfShadeResult r = wfShade(s, path, hit, rng, pc.bounce, pc.maxDepth, pc.rouletteDepth, kPtNee != 0u);
    WfPathRef(pc.paths).p[pixel] = path;
    if (pc.bounce == 0u) WfGuideRef(WfAccumRef(pc.accum).a.guides).g[pixel] = r.guide;
    if (r.hasShadowRay) {
        r.shadowRay.pixel = pixel;
        WfShadowRayRef(pc.shadowRays).r[pixel] = r.shadowRay;
        wfQueueAppend(WfQueueRef(pc.shadow), pixel);
    }
    if (r.extend) wfQueueAppend(WfQueueRef(pc.queueOut), pixel);
}
