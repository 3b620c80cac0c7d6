#version 460
// args.comp.glsl: one invocation after each shade stage: turns the append counts of the next ray queue and of
// this bounce's shadow queue into exact indirect dispatch sizes, and empties the queues the next bounce appends
// to (the consumed input queue and the other shadow queue). Replaces IDKEngine's CPU glBufferSubData between
// bounces (reference section 5: a CPU round trip per bounce) with a GPU-side step.
#extension GL_GOOGLE_include_directive : require
#include "wf_common.h"

layout(local_size_x = 1) in;

void main() {
    uint next = WfQueueRef(pc.queueOut).count;
    uint shadow = WfQueueRef(pc.shadow).count;
    WfArgsRef(pc.argsOut).groups = uvec3((next + kPtGroupSize - 1u) / kPtGroupSize, 1u, 1u);
    WfArgsRef(pc.argsShadow).groups = uvec3((shadow + kPtGroupSize - 1u) / kPtGroupSize, 1u, 1u);
    WfQueueRef(pc.queueIn).count = 0u;
    WfQueueRef(pc.aux).count = 0u;
}
