#version 460
// gbuffer_mesh.task.glsl: the mesh rung's culling of one drawn instance's meshlets, one per invocation: sphere
// against the frustum, normal cone against the eye (single-sided materials under similarity transforms only),
// and in the late occlusion phase the sphere's box against the Hi-Z pyramid; survivors are compacted into the
// payload and launched as mesh workgroups. The culling pass wrote the instance of command gl_DrawID.
// Ports IDKEngine's GBuffer/MeshPath/task.glsl (frustum + optional Hi-Z, subgroupBallot compaction) with the
// normal cone added; the compaction here is a shared counter (a real GPU would use subgroupBallot for order).
#extension GL_EXT_mesh_shader : require
#extension GL_GOOGLE_include_directive : require
#include "scene_buffers.glsl"
#include "culling_types.h"
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

shared uint survivors;
shared uint triangles;

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
    if ((d.flags & kCullAlwaysVisible) != 0u) return true;  // deformed vertices: the bounds do not hold
    vec3 scale = vec3(length(model[0].xyz), length(model[1].xyz), length(model[2].xyz));
    vec3 center = vec3(model * vec4(m.center, 1.0));
    float radius = m.radius * max(scale.x, max(scale.y, scale.z));
    for (int i = 0; i < 6; ++i) {
        vec4 plane = view.planes[i];
        if (dot(plane.xyz, center) + plane.w < -radius * length(plane.xyz)) return false;
    }
    // Normal cone (meshoptimizer's test). Only where "front" is the winding the cone was built from: single-sided
    // materials, no mirroring, uniform scale (a non-uniform scale bends normals away from the cone), perspective.
    bool perspective = view.viewProjection[0][3] != 0.0 || view.viewProjection[1][3] != 0.0 ||
                       view.viewProjection[2][3] != 0.0;
    bool uniformScale = abs(scale.x - scale.y) <= 1e-4 * scale.x && abs(scale.x - scale.z) <= 1e-4 * scale.x;
    bool mirrored = determinant(mat3(model)) < 0.0;
    if ((d.flags & kCullSingleSided) != 0u && perspective && uniformScale && !mirrored && m.coneCutoff < 1.0) {
        vec3 apex = vec3(model * vec4(m.coneApex, 1.0));
        vec3 axis = normalize(mat3(model) * m.coneAxis);
        vec3 eye = FrameBuffer(p.gbuffer.frame).frame.cameraPosition;
        if (dot(normalize(apex - eye), axis) >= m.coneCutoff) return false;
    }
    return p.phase != kCullLate || hizVisible(view, center, vec3(radius));
}

void main() {
    uint instance = DrawInstances(p.drawInstance).data[gl_DrawID];
    GpuCullDraw d = CullDraws(p.draws).data[instance];
    uint local = gl_WorkGroupID.x * kTaskGroupSize + gl_LocalInvocationIndex;
    if (gl_LocalInvocationIndex == 0u) {
        survivors = 0u;
        triangles = 0u;
        payload.instance = instance;
        payload.vertexOffset = d.vertexOffset;
    }
    barrier();
    if (local < d.meshletCount) {
        GpuMeshlet m = Meshlets(p.meshlets).data[d.firstMeshlet + local];
        mat4 model = InstanceBuffer(p.gbuffer.instances).data[instance].model;
        if (meshletVisible(m, d, model, CullViews(p.views).data[p.view])) {
            payload.meshlets[atomicAdd(survivors, 1u)] = d.firstMeshlet + local;
            atomicAdd(triangles, m.triangleCount);
        }
    }
    barrier();
    if (gl_LocalInvocationIndex == 0u) {
        Counters counters = Counters(p.counters);
        atomicAdd(counters.c.meshletsTested, min(d.meshletCount - gl_WorkGroupID.x * kTaskGroupSize, kTaskGroupSize));
        atomicAdd(counters.c.meshletsDrawn, survivors);
        atomicAdd(counters.c.trianglesDrawn, triangles);
    }
    EmitMeshTasksEXT(survivors, 1, 1);
}
