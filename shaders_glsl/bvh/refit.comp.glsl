#version 460
// refit.comp.glsl: one level of the bottom-up BLAS refit after the vertices moved (skinning): every node of the
// level gets the union of its triangles' boxes (leaf) or of its child pair's boxes (inner, refit by the previous
// dispatch). Port of IDKEngine BLASRefit/compute.glsl, reorganised per level (no locks, no atomics); the boxes are
// grown in the same order as bvh::refitBlas with the same min/max rule, so they equal the CPU refit bit for bit.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_buffer_reference : require
#include "interop.h"
#include "bvh_trace_types.h"

layout(local_size_x = kBvhRefitGroupSize) in;

layout(buffer_reference, scalar, buffer_reference_align = 16) buffer NodeArray { GpuBlasNode n[]; };
layout(buffer_reference, scalar, buffer_reference_align = 16) readonly buffer TriangleArray { GpuBlasTriangle t[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer FloatArray { float f[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer UintArray { uint u[]; };

layout(push_constant, scalar) uniform Push { BvhRefitPush p; };

// glm::min / glm::max as Box::grow uses them: (b < a) ? b : a, so the result (down to the sign of a zero) follows
// the same order of arguments. The bits are selected, so a compiler cannot turn the select into fmin/fmax.
float pick(bool takeB, float a, float b) { return uintBitsToFloat(takeB ? floatBitsToUint(b) : floatBitsToUint(a)); }
vec3 minOf(vec3 a, vec3 b) { return vec3(pick(b.x < a.x, a.x, b.x), pick(b.y < a.y, a.y, b.y), pick(b.z < a.z, a.z, b.z)); }
vec3 maxOf(vec3 a, vec3 b) { return vec3(pick(a.x < b.x, a.x, b.x), pick(a.y < b.y, a.y, b.y), pick(a.z < b.z, a.z, b.z)); }

vec3 position(uint vertex) {
    FloatArray positions = FloatArray(p.blas.positions);
    uint base = vertex * p.blas.vertexStride;
    return vec3(positions.f[base], positions.f[base + 1u], positions.f[base + 2u]);
}

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= p.levelCount) return;
    NodeArray nodes = NodeArray(p.blas.nodes);
    uint index = UintArray(p.order).u[p.levelStart + i];
    GpuBlasNode node = nodes.n[index];
    const float inf = uintBitsToFloat(0x7F800000u);
    vec3 lo = vec3(inf);
    vec3 hi = vec3(-inf);
    if (node.triCount > 0u) {
        TriangleArray triangles = TriangleArray(p.blas.triangles);
        for (uint k = node.triStartOrChild; k < node.triStartOrChild + node.triCount; ++k) {
            uvec3 v = triangles.t[k].vertexIndices;
            // Triangle::box(): an empty box grown by v0, v1, v2.
            vec3 p0 = position(v.x), p1 = position(v.y), p2 = position(v.z);
            vec3 triLo = minOf(minOf(minOf(vec3(inf), p0), p1), p2);
            vec3 triHi = maxOf(maxOf(maxOf(vec3(-inf), p0), p1), p2);
            lo = minOf(lo, triLo);
            hi = maxOf(hi, triHi);
        }
    } else {
        GpuBlasNode left = nodes.n[node.triStartOrChild];
        GpuBlasNode right = nodes.n[node.triStartOrChild + 1u];
        lo = minOf(left.min, right.min);
        hi = maxOf(left.max, right.max);
    }
    nodes.n[index].min = lo;
    nodes.n[index].max = hi;
}
