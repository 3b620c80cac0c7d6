// wf_common.h (GLSL include of the wavefront path tracer stages): buffer-reference views of shared/pt_wavefront.h
// and PT-A's tables (shared/pt_types.h), the push block, ray-queue append, and the hit attributes at a hit
// (GLSL twin of pathtrace::hitPoint in engine/pathtrace/pt_material.cpp, operation for operation). Replaces
// IDKEngine's PathTracing/include headers and the vertex fetch in FirstHit/NHit (reference 2.1).
#ifndef IDK_WF_COMMON_H
#define IDK_WF_COMMON_H
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_nonuniform_qualifier : require
#include "interop.h"
#include "scene_types.h"
#include "bvh_trace_types.h"
#include "pt_types.h"
#include "pt_wavefront.h"
#include "bindless.glsl"

layout(buffer_reference, scalar, buffer_reference_align = 8) readonly buffer WfSceneRef { GpuPtSceneDesc d; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer WfPathRef { GpuPtPath p[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer WfHitRef { GpuPtHit h[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer WfShadowRayRef { GpuPtShadowRay r[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer WfQueueRef {
    uint count;
    uint pad0;
    uint pad1;
    uint pad2;
    uint items[];
};
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer WfArgsRef { uvec3 groups; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer WfVec4Ref { vec4 v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer WfFloatRef { float f[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer WfUintRef { uint u[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer WfGuideRef { GpuPtGuide g[]; };
layout(buffer_reference, scalar, buffer_reference_align = 8) readonly buffer WfAccumRef { GpuPtAccum a; };
layout(buffer_reference, scalar, buffer_reference_align = 8) readonly buffer WfCameraRef { GpuPtCamera c; };
layout(buffer_reference, scalar, buffer_reference_align = 8) readonly buffer WfGeometryRef { GpuPtGeometry g[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer WfVertexRef { GpuPtVertex v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer WfTriangleRef { uvec3 t[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer WfMaterialRef { GpuMaterial m[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer WfPtMaterialRef { GpuPtMaterial m[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer WfInstanceRef { GpuPtTraceInstance i[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer WfLightRef { GpuPtLight l[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer WfAliasRef { GpuPtAliasEntry e[]; };

#ifndef WF_CUSTOM_PUSH  // users of the traversal alone (rt_shadows/) declare their own push block
layout(push_constant, scalar) uniform Push { GpuPtStagePush pc; };
#endif

// Appends `item` to a queue (alive-ray compaction: survivors are packed densely in arrival order). The next
// stage's dispatch size is derived on the GPU by args.comp.glsl, never read back by the CPU.
void wfQueueAppend(WfQueueRef queue, uint item) {
    uint slot = atomicAdd(queue.count, 1u);
    queue.items[slot] = item;
}

// pathtrace::PtHitPoint.
struct WfHitPoint {
    vec3 position;
    vec3 geometricNormal;  // unit, the front face's side (winding, mirroring included)
    vec3 normal;           // interpolated vertex normal, world, unit
    vec4 tangent;          // world xyz + handedness w; w = 0: none
    vec2 uv0;
    vec2 uv1;
    vec4 color;
    uint material;
};

vec3 wfSafeNormalize(vec3 v, vec3 fallback) {
    float l2 = dot(v, v);
    return l2 > 1e-30 && !isinf(l2) && !isnan(l2) ? v / sqrt(l2) : fallback;
}

vec3 wfTransformPoint(GpuPtTraceInstance inst, vec3 p) {
    return inst.objectToWorld[0] * p.x + inst.objectToWorld[1] * p.y + inst.objectToWorld[2] * p.z +
           inst.objectToWorld[3];
}

// Attributes at barycentrics (u of vertex 1, v of vertex 2) of `triangle` of `instance` (pathtrace::hitPoint).
WfHitPoint wfHitPoint(GpuPtSceneDesc s, uint instance, uint triangle, float u, float v) {
    WfHitPoint h;
    GpuPtTraceInstance inst = WfInstanceRef(s.instances).i[instance];
    GpuPtGeometry geo = WfGeometryRef(s.geometries).g[inst.geometry];
    uvec3 tri = WfTriangleRef(geo.triangles).t[triangle];
    h.material = WfUintRef(geo.materials).u[triangle];
    WfVertexRef verts = WfVertexRef(geo.vertices);
    GpuPtVertex a = verts.v[tri.x], b = verts.v[tri.y], c = verts.v[tri.z];
    float w = 1.0 - u - v;
    vec3 p0 = wfTransformPoint(inst, a.position), p1 = wfTransformPoint(inst, b.position),
         p2 = wfTransformPoint(inst, c.position);
    h.position = w * p0 + u * p1 + v * p2;
    float flip = (inst.flags & kPtInstanceMirrored) != 0u ? -1.0 : 1.0;
    vec3 ng = wfSafeNormalize(cross(p1 - p0, p2 - p0) * flip, vec3(0.0, 0.0, 1.0));
    h.geometricNormal = ng;
    mat3 nm = mat3(inst.normalToWorld[0], inst.normalToWorld[1], inst.normalToWorld[2]);
    h.normal = wfSafeNormalize(nm * (w * a.normal + u * b.normal + v * c.normal), ng);
    vec4 t = w * a.tangent + u * b.tangent + v * c.tangent;
    float handedness = a.tangent.w;
    mat3 m3 = mat3(inst.objectToWorld[0], inst.objectToWorld[1], inst.objectToWorld[2]);
    h.tangent = handedness != 0.0 ? vec4(m3 * t.xyz, handedness < 0.0 ? -1.0 : 1.0) : vec4(0.0);
    h.uv0 = w * a.uv0 + u * b.uv0 + v * c.uv0;
    h.uv1 = w * a.uv1 + u * b.uv1 + v * c.uv1;
    h.color = w * a.color + u * b.color + v * c.color;
    return h;
}

// A material texture slot at mip 0 (compute shaders have no derivatives; the CPU reference samples mip 0 too),
// with its KHR_texture_transform and texcoord set; sRGB slots decode through the view's sRGB format.
vec4 wfSampleSlot(GpuTextureSlot slot, WfHitPoint h) {
    vec3 q = vec3(slot.texCoord == 1u ? h.uv1 : h.uv0, 1.0);
    vec2 st = vec2(dot(slot.row0, q), dot(slot.row1, q));
    return textureLod(sampler2D(gTextures2D[nonuniformEXT(slot.texture)], gSamplers[nonuniformEXT(slot.samplerIndex)]),
                      st, 0.0);
}

// 32-bit hash (PCG output permutation) for the trace stages' own random choices (BLEND stochastic transparency).
uint wfHash(uint v) {
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}
float wfHashFloat(uint v) { return float(wfHash(v) >> 8) * (1.0 / 16777216.0); }

#endif
