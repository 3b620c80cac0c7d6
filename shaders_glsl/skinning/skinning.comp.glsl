#version 460
// skinning.comp.glsl: one invocation per deformed vertex: rest pose + weighted morph deltas, then 4-joint linear
// blend skinning, written to the vertex's deformed copy (node space; the draw's model matrix places it). Ports
// IDKEngine's Skinning/compute.glsl (WG 64, mat4x3 joints) plus morph targets. Normals: the skin matrix's cofactor
// (det * inverse-transpose, sign-corrected); tangents: the matrix; both renormalised. Order and sums match
// scene::deformedPosition (morph, then skin).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_buffer_reference : require
#include "interop.h"
#include "scene_types.h"
#include "skinning_types.h"

layout(local_size_x = kSkinningGroupSize) in;
layout(push_constant, scalar) uniform Push { SkinningPush p; };

layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Vertices { GpuVertex data[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer Jobs { GpuDeformJob data[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer Influences { GpuSkinInfluence data[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer Deltas { vec3 data[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer Joints { mat4x3 data[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer Weights { float data[]; };

// The last job whose firstThread <= thread (jobs are sorted by firstThread, job 0 starts at 0).
uint findJob(uint thread) {
    uint lo = 0, hi = p.jobCount - 1;
    while (lo < hi) {
        uint mid = (lo + hi + 1) / 2;
        if (Jobs(p.jobs).data[mid].firstThread <= thread) lo = mid; else hi = mid - 1;
    }
    return lo;
}

vec3 normalizedOr(vec3 v, vec3 fallback) {
    float len = length(v);
    return len > 0.0 ? v / len : fallback;
}

void main() {
    uint thread = gl_GlobalInvocationID.x;
    if (thread >= p.threadCount) return;
    GpuDeformJob job = Jobs(p.jobs).data[findJob(thread)];
    uint v = thread - job.firstThread;
    GpuVertex vertex = Vertices(p.vertices).data[job.srcVertex + v];
    vec3 position = vertex.position, normal = vertex.normal, tangent = vertex.tangent.xyz;

    if (job.deltas != kDeformNone) {
        uint attributes = bitCount(job.morphAttributes);
        for (uint t = 0; t < job.targetCount; ++t) {
            float w = Weights(p.weights).data[job.firstWeight + t];
            if (w == 0.0) continue;
            uint base = job.deltas + t * attributes * job.vertexCount + v;
            uint slot = 0;
            if ((job.morphAttributes & kMorphPositions) != 0)
                position += w * Deltas(p.deltas).data[base + (slot++) * job.vertexCount];
            if ((job.morphAttributes & kMorphNormals) != 0)
                normal += w * Deltas(p.deltas).data[base + (slot++) * job.vertexCount];
            if ((job.morphAttributes & kMorphTangents) != 0)
                tangent += w * Deltas(p.deltas).data[base + slot * job.vertexCount];
        }
    }

    if (job.influences != kDeformNone) {
        GpuSkinInfluence inf = Influences(p.influences).data[job.influences + v];
        mat4x3 skin = mat4x3(0.0);
        for (uint c = 0; c < 4; ++c) {
            uint j = (inf.joints >> (8 * c)) & 0xFFu;
            if (j < job.jointCount) skin += inf.weights[c] * Joints(p.jointMatrices).data[job.firstJoint + j];
        }
        mat3 m = mat3(skin);
        position = skin * vec4(position, 1.0);
        mat3 cofactor = mat3(cross(m[1], m[2]), cross(m[2], m[0]), cross(m[0], m[1]));
        normal = cofactor * normal * (determinant(m) < 0.0 ? -1.0 : 1.0);
        tangent = m * tangent;
    }

    vertex.position = position;
    vertex.normal = normalizedOr(normal, vertex.normal);
    if (vertex.tangent.w != 0.0) vertex.tangent.xyz = normalizedOr(tangent, vertex.tangent.xyz);
    Vertices(p.vertices).data[job.dstVertex + v] = vertex;
}
