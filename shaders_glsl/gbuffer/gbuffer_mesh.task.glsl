#version 460
// gbuffer_mesh.task.glsl: the mesh rung's culling of one drawn instance's meshlets, one per invocation: sphere
// against the frustum, normal cone against the eye (single-sided materials under similarity transforms only),
// and in the late occlusion phase the meshlet's vertex box against the Hi-Z pyramid; survivors are compacted into the
// payload and launched as mesh workgroups. The culling pass wrote the instance of command gl_DrawID.
// Two-phase occlusion per meshlet (niagara's scheme): one visibility bit per meshlet persists between frames; the
// early phase draws only the meshlets visible last frame, the late phase tests all of them against the pyramid
// of the early depth, rewrites the bits and draws the visible ones the early phase did not draw. Bits never decide
// correctness, only what the early phase draws: a stale or cleared bit (first frame, camera cut) leaves the
// meshlet to the late phase, whose pyramid is never nearer than the final depth.
// Ports IDKEngine's GBuffer/MeshPath/task.glsl (frustum + optional Hi-Z, subgroupBallot compaction) with the
// normal cone and the meshlet bits added; the compaction here is a shared counter (a real GPU would use
// subgroupBallot for order and skip the shared atomics).
#extension GL_EXT_mesh_shader : require
#extension GL_GOOGLE_include_directive : require
#include "scene_buffers.glsl"
#include "culling_types.h"
#include "meshlet_culling.h"
#include "depth_pyramid.h"
#include "meshlet_payload.glsl"

layout(local_size_x = kTaskGroupSize) in;
layout(push_constant, scalar) uniform Push { GBufferMeshPush p; };
taskPayloadSharedEXT MeshTaskPayload payload;

layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer DrawInstances { uint data[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer CullDraws { GpuCullDraw data[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer CullViews { GpuCullView data[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer Pyramid { float data[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Counters { GpuCullCounters c; };

layout(buffer_reference, scalar, buffer_reference_align = 4) buffer MeshletBits { uint data[]; };

shared uint survivors;
shared uint triangles;
shared uint tested;
shared uint newBits;  // late phase: the meshlets found visible (next frame's early set)

bool hizVisible(GpuCullView view, vec3 center, vec3 extent) {
    vec4 rect;
    float nearest;
    if (!hizFootprint(view.viewProjection, center, extent, vec2(view.viewport), rect, nearest)) return true;
    uvec4 t;
    uint level = hizTexels(rect, view.viewport, t);
    uint offset = hizLevelOffset(view.viewport, level);
    uint width = hizLevelSize(view.viewport, level).x;
    Pyramid pyramid = Pyramid(p.pyramid);
    float farthest = max(max(pyramid.data[offset + t.y * width + t.x], pyramid.data[offset + t.y * width + t.z]),
                         max(pyramid.data[offset + t.w * width + t.x], pyramid.data[offset + t.w * width + t.z]));
    return nearest <= farthest;
}

bool meshletVisible(GpuMeshlet m, GpuCullDraw d, mat4 model, GpuCullView view) {
    vec3 eye = FrameBuffer(p.gbuffer.frame).frame.cameraPosition;
    if (!meshletInView(m, d.flags, model, view, eye)) return false;
    if (p.phase != kCullLate || (d.flags & kCullAlwaysVisible) != 0u) return true;
    vec3 center, extent;
    meshletBox(m, model, center, extent);
    return hizVisible(view, center, extent);
}

void main() {
    uint command = DrawInstances(p.drawInstance).data[gl_DrawID];
    uint instance = command & ~kDrawnEarly;
    GpuCullDraw d = CullDraws(p.draws).data[instance];
    uint local = gl_WorkGroupID.x * kTaskGroupSize + gl_LocalInvocationIndex;
    uint word = d.meshletVisibilityWord + gl_WorkGroupID.x;  // this workgroup's 32 meshlet bits
    uint bit = 1u << gl_LocalInvocationIndex;
    uint lastBits = p.phase != kCullFrustum ? MeshletBits(p.meshletVisibility).data[word] : 0u;
    if (gl_LocalInvocationIndex == 0u) {
        survivors = 0u;
        triangles = 0u;
        tested = 0u;
        newBits = 0u;
        payload.instance = instance;
        payload.vertexOffset = d.vertexOffset;
    }
    barrier();
    // Early: only the meshlets drawn last frame. Late: every meshlet, except that those the early phase drew (bit
    // set and the instance drawn early: they passed the same frustum and cone tests then) are not drawn twice.
    bool wasVisible = (lastBits & bit) != 0u;
    bool test = local < d.meshletCount && (p.phase != kCullEarly || wasVisible);
    bool drawnEarly = p.phase == kCullLate && (command & kDrawnEarly) != 0u && wasVisible;
    if (test) {
        GpuMeshlet m = Meshlets(p.meshlets).data[d.firstMeshlet + local];
        mat4 model = InstanceBuffer(p.gbuffer.instances).data[instance].model;
        bool visible = meshletVisible(m, d, model, CullViews(p.views).data[p.view]);
        if (visible && p.phase == kCullLate) atomicOr(newBits, bit);
        if (!drawnEarly) atomicAdd(tested, 1u);
        if (visible && !drawnEarly) {
            payload.meshlets[atomicAdd(survivors, 1u)] = d.firstMeshlet + local;
            atomicAdd(triangles, m.triangleCount);
        }
    }
    barrier();
    if (gl_LocalInvocationIndex == 0u) {
        // The late phase rewrites the whole word (this workgroup's meshlets; bits past meshletCount stay 0).
        if (p.phase == kCullLate) MeshletBits(p.meshletVisibility).data[word] = newBits;
        Counters counters = Counters(p.counters);
        atomicAdd(counters.c.meshletsTested, tested);
        atomicAdd(counters.c.meshletsDrawn, survivors);
        atomicAdd(counters.c.trianglesDrawn, triangles);
    }
    EmitMeshTasksEXT(survivors, 1, 1);
}
