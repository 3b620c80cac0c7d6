#version 460
// camera.comp.glsl: wavefront stage 1, one invocation per pixel: starts this sample's path (camera ray through a
// jittered pixel position, throughput 1, radiance 0), puts every pixel in the first ray queue and empties the
// other queues. Port of IDKEngine PathTracing/FirstHit (which also traced and shaded; here tracing and shading
// are the following stages, the same for every bounce).
#extension GL_GOOGLE_include_directive : require
#include "wf_shading.h"

layout(local_size_x = kPtGroupSize) in;

void main() {
    uint pixel = gl_GlobalInvocationID.x;
    uint pixels = pc.extent.x * pc.extent.y;
    WfQueueRef queue = WfQueueRef(pc.queueIn);
    if (pixel == 0u) {
        queue.count = pixels;
        WfArgsRef(pc.argsOut).groups = uvec3((pixels + kPtGroupSize - 1u) / kPtGroupSize, 1u, 1u);
        WfQueueRef(pc.queueOut).count = 0u;
        WfQueueRef(pc.shadow).count = 0u;
        WfQueueRef(pc.aux).count = 0u;
    }
    if (pixel >= pixels) return;
    queue.items[pixel] = pixel;
    GpuPtCamera cam = WfCameraRef(pc.accum).c;
    WfPathRef(pc.paths).p[pixel] = wfStartPath(cam, pixel, pc.extent, pc.sampleIndex, pc.seed, pc.flags);
}
