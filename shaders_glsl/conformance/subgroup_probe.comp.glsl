#version 460
// subgroup_probe.comp.glsl: records, for every invocation of one 256-wide workgroup, the subgroup facts the
// compute primitives rely on (size, id, count, lane, active lanes) so a conformance test can check them and print
// the device's actual subgroup size.
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#include "interop.h"
#include "bindless.glsl"
#include "compute_push.h"

layout(local_size_x = kComputeGroupSize) in;
layout(push_constant, scalar) uniform Push { ProbePush p; };

IDK_BINDLESS_BUFFER(gRecords, SubgroupProbeRecord);

void main() {
    SubgroupProbeRecord r;
    r.subgroupSize = gl_SubgroupSize;
    r.subgroupId = gl_SubgroupID;
    r.numSubgroups = gl_NumSubgroups;
    r.subgroupInvocationId = gl_SubgroupInvocationID;
    r.subgroupSum = subgroupAdd(1u);
    gRecords[p.records].data[p.recordsOffset + gl_LocalInvocationIndex] = r;
}
