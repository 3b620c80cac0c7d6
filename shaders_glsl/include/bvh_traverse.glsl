// bvh_traverse.glsl: closest-hit and any-hit ray traversal of a BLAS, or of a TLAS over BLAS instances, read
// through buffer device addresses (shared/bvh_trace_types.h), for the path tracer, ray-traced shadows and picking.
// Port of IDKEngine include/BVHIntersect.glsl (pair-wise walk, stack top in registers, leaf pairs intersected as
// one range) with the robust tests of engine/bvh/intersect.hpp ported operation for operation: the watertight
// ray/triangle test in single precision with exact edge-function signs (bvh_edge_function.glsl), the robust slab
// test, the same tie rule; hits equal the CPU traversal's. No double precision anywhere: it runs on any Vulkan 1.3
// device (consumer GPUs run fp64 at 1/16-1/64 rate, Intel Arc, Apple and mobile GPUs have none).
//
// The includer may define, before including:
//   BVH_STACK_SIZE       BLAS stack entries (default 32); at least bvh::requiredStackSize() of every BLAS traced.
//                        A specialization constant works (arrays may be sized by one).
//   BVH_TLAS_STACK_SIZE  TLAS stack entries (default 32).
// A push onto a full stack is dropped (the subtree is skipped, never written out of bounds) and reported with
// kBvhHitFlagStackOverflow in the hit's flags. Needs shaderInt64 (64-bit buffer addresses in GpuBlasDesc and the
// exact edge-function fallback), which the engine requires anyway.
//
// Exactness: every float expression that the C++ rounds step by step is `precise`, so no contraction into FMA and
// no reassociation; NaN and infinity tests use the bits, which no fast-math assumption can fold away.
#ifndef IDK_BVH_TRAVERSE_GLSL
#define IDK_BVH_TRAVERSE_GLSL
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#include "bvh_trace_types.h"
#include "bvh_edge_function.glsl"

#ifndef BVH_STACK_SIZE
#define BVH_STACK_SIZE 32
#endif
#ifndef BVH_TLAS_STACK_SIZE
#define BVH_TLAS_STACK_SIZE 32
#endif

layout(buffer_reference, scalar, buffer_reference_align = 16) readonly buffer BvhNodeRef { GpuBlasNode n[]; };
layout(buffer_reference, scalar, buffer_reference_align = 16) readonly buffer BvhTriangleRef { GpuBlasTriangle t[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer BvhFloatRef { float f[]; };
layout(buffer_reference, scalar, buffer_reference_align = 16) readonly buffer BvhTlasNodeRef { GpuTlasNode n[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer BvhUintRef { uint u[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer BvhInstanceRef { GpuBvhInstance i[]; };
layout(buffer_reference, scalar, buffer_reference_align = 8) readonly buffer BvhBlasDescRef { GpuBlasDesc d[]; };
layout(buffer_reference, scalar, buffer_reference_align = 8) readonly buffer BvhTlasDescRef { GpuTlasDesc d; };

#define kBvhInfinity uintBitsToFloat(0x7F800000u)
const float kBvhRobustScale = 1.0000019073486328125;          // bvh::kBoxRobustScale = 1 + 2^-19 (0x3F800010)
const float kBvhTieSlack = 9.5367431640625e-7;               // 2^-20: walk.hpp boxLimit()

bool bvhIsFinite(float x) { return (floatBitsToUint(x) & 0x7F800000u) != 0x7F800000u; }
bool bvhIsNan(float x) { return (floatBitsToUint(x) & 0x7FFFFFFFu) > 0x7F800000u; }

// Per-ray constants of both tests (bvh::PreparedRay).
struct BvhPreparedRay {
    vec3 origin;
    vec3 invDirection;
    float tMin;
    float tMax;
    int kx, ky, kz;
    float sx, sy, sz;
    bool valid;
};

// bvh::prepareRay. An invalid ray (non-finite origin/direction/tMin, NaN tMax, empty interval, zero direction)
// hits nothing.
BvhPreparedRay bvhPrepareRay(vec3 origin, vec3 direction, float tMin, float tMax) {
    BvhPreparedRay r;
    r.origin = vec3(0.0);
    r.invDirection = vec3(0.0);
    r.tMin = 0.0;
    r.tMax = 0.0;
    r.kx = 0;
    r.ky = 1;
    r.kz = 2;
    r.sx = 0.0;
    r.sy = 0.0;
    r.sz = 0.0;
    r.valid = false;
    bool finite = bvhIsFinite(tMin) && !bvhIsNan(tMax) && tMin < tMax;
    for (int i = 0; i < 3; ++i) finite = finite && bvhIsFinite(origin[i]) && bvhIsFinite(direction[i]);
    if (!finite || (direction.x == 0.0 && direction.y == 0.0 && direction.z == 0.0)) return r;
    r.origin = origin;
    precise vec3 inv = vec3(1.0) / direction;  // +-0 -> +-inf, which the slab test handles
    r.invDirection = inv;
    r.tMin = tMin;
    r.tMax = tMax;
    vec3 ad = abs(direction);
    r.kz = ad.x >= ad.y && ad.x >= ad.z ? 0 : (ad.y >= ad.z ? 1 : 2);
    r.kx = (r.kz + 1) % 3;
    r.ky = (r.kx + 1) % 3;
    if (direction[r.kz] < 0.0) {  // keep the winding, so edge function signs keep their meaning
        int swap = r.kx;
        r.kx = r.ky;
        r.ky = swap;
    }
    precise float sx = direction[r.kx] / direction[r.kz];
    precise float sy = direction[r.ky] / direction[r.kz];
    precise float sz = 1.0 / direction[r.kz];
    r.sx = sx;
    r.sy = sy;
    r.sz = sz;
    r.valid = true;
    return r;
}

// bvh::intersectBox: robust slabs (Ize 2013, widened for Vulkan's faithful rounding and 2.5-ulp division). The
// face is picked by the sign bit of the inverse direction, a NaN from 0 * inf constrains nothing (the comparisons
// below are false for NaN), the exit distance is widened.
bool bvhIntersectBox(BvhPreparedRay r, vec3 boxMin, vec3 boxMax, float tLimit, out float tNear) {
    precise float nearT = r.tMin;
    precise float farT = tLimit;
    for (int axis = 0; axis < 3; ++axis) {
        bool negative = (floatBitsToUint(r.invDirection[axis]) & 0x80000000u) != 0u;
        float lo = negative ? boxMax[axis] : boxMin[axis];
        float hi = negative ? boxMin[axis] : boxMax[axis];
        precise float t0 = (lo - r.origin[axis]) * r.invDirection[axis];
        precise float t1 = ((hi - r.origin[axis]) * r.invDirection[axis]) * kBvhRobustScale;
        // C++: t0 > nearT ? t0 : nearT. The explicit NaN test keeps a compiler from turning the select into an
        // fmax whose NaN rule might differ.
        if (!bvhIsNan(t0) && t0 > nearT) nearT = t0;
        if (!bvhIsNan(t1) && t1 < farT) farT = t1;
    }
    tNear = nearT;
    return nearT <= farT;
}

// bvh::intersectTriangle: watertight test (Woop, Benthin & Wald 2013) in single precision; the edge functions have
// exact signs (bvhEdgeFunction). Two-sided; edges and vertices inside; degenerate triangles miss. Reports
// t > r.tMin only; u, v are the weights of v1 and v2.
bool bvhIntersectTriangle(BvhPreparedRay r, vec3 v0, vec3 v1, vec3 v2, out float tHit, out float uHit,
                          out float vHit) {
    tHit = 0.0;
    uHit = 0.0;
    vHit = 0.0;
    precise vec3 a = v0 - r.origin;
    precise vec3 b = v1 - r.origin;
    precise vec3 c = v2 - r.origin;
    precise float axs = a[r.kx] - r.sx * a[r.kz];
    precise float ays = a[r.ky] - r.sy * a[r.kz];
    precise float bxs = b[r.kx] - r.sx * b[r.kz];
    precise float bys = b[r.ky] - r.sy * b[r.kz];
    precise float cxs = c[r.kx] - r.sx * c[r.kz];
    precise float cys = c[r.ky] - r.sy * c[r.kz];
    float ax = bvhFlushSubnormal(axs), ay = bvhFlushSubnormal(ays), bx = bvhFlushSubnormal(bxs),
          by = bvhFlushSubnormal(bys), cx = bvhFlushSubnormal(cxs), cy = bvhFlushSubnormal(cys);
    int su, sv, sw;
    float u = bvhEdgeFunction(cx, by, cy, bx, su);
    float v = bvhEdgeFunction(ax, cy, ay, cx, sv);
    float w = bvhEdgeFunction(bx, ay, by, ax, sw);
    if ((su < 0 || sv < 0 || sw < 0) && (su > 0 || sv > 0 || sw > 0)) return false;
    precise float det = u + v + w;
    if (det == 0.0) return false;
    precise float az = r.sz * a[r.kz];
    precise float bz = r.sz * b[r.kz];
    precise float cz = r.sz * c[r.kz];
    precise float tScaled = u * az + v * bz + w * cz;
    precise float rcp = 1.0 / det;
    precise float t = tScaled * rcp;
    if (!(t > r.tMin) || !(t < kBvhInfinity)) return false;
    tHit = t;
    precise float uw = v * rcp;
    precise float vw = w * rcp;
    uHit = uw;
    vHit = vw;
    return true;
}

// walk.hpp boxLimit(): boxes are accepted up to a hair beyond the current hit so that a triangle tying with it
// (same t, smaller id) is still reached.
float bvhBoxLimit(float bestT) {
    precise float limit = bestT + abs(bestT) * kBvhTieSlack;
    return limit;
}

// The closest hit so far; ties at equal t go to the smaller instance id, then the smaller triangle id.
struct BvhBest {
    float t;
    uint triangleId;
    uint instanceId;
    float u;
    float v;
    uint flags;
};

bool bvhCloser(float t, uint instanceId, uint triangleId, BvhBest best) {
    if (t != best.t) return t < best.t;
    if (instanceId != best.instanceId) return instanceId < best.instanceId;
    return triangleId < best.triangleId;
}

vec3 bvhLoadPosition(BvhFloatRef positions, uint stride, uint vertex) {
    uint base = vertex * stride;
    return vec3(positions.f[base], positions.f[base + 1u], positions.f[base + 2u]);
}

// Intersects triangle references [start, end) and improves `best`; true when anyHit is set and a hit was found.
bool bvhIntersectRange(GpuBlasDesc blas, BvhPreparedRay r, uint instanceId, bool anyHit, uint start, uint end,
                       inout BvhBest best) {
    BvhTriangleRef triangles = BvhTriangleRef(blas.triangles);
    BvhFloatRef positions = BvhFloatRef(blas.positions);
    for (uint k = start; k < end; ++k) {
        GpuBlasTriangle tri = triangles.t[k];
        vec3 v0 = bvhLoadPosition(positions, blas.vertexStride, tri.vertexIndices.x);
        vec3 v1 = bvhLoadPosition(positions, blas.vertexStride, tri.vertexIndices.y);
        vec3 v2 = bvhLoadPosition(positions, blas.vertexStride, tri.vertexIndices.z);
        float t, u, v;
        if (!bvhIntersectTriangle(r, v0, v1, v2, t, u, v) || !(t < r.tMax)) continue;
        if (!bvhCloser(t, instanceId, tri.triangleId, best)) continue;
        best.t = t;
        best.triangleId = tri.triangleId;
        best.instanceId = instanceId;
        best.u = u;
        best.v = v;
        best.flags |= kBvhHitFlagHit;
        if (anyHit) return true;
    }
    return false;
}

// Walks one BLAS with a prepared (object-space) ray: both children of the current pair are tested; hit leaves are
// intersected at once (a leaf pair as one range); of two hit inner children the nearer is entered and the farther
// pushed with its entry distance; popped entries that start beyond the current hit are skipped.
bool bvhTraverseBlas(GpuBlasDesc blas, BvhPreparedRay r, uint instanceId, bool anyHit, inout BvhBest best) {
    if (!r.valid) return false;
    BvhNodeRef nodes = BvhNodeRef(blas.nodes);
    GpuBlasNode root = nodes.n[kBvhRootNode];
    float tRoot;
    if (!bvhIntersectBox(r, root.min, root.max, bvhBoxLimit(best.t), tRoot)) return false;
    uint stackPair[BVH_STACK_SIZE];
    float stackT[BVH_STACK_SIZE];
    uint size = 0u;
    uint pair = root.triStartOrChild;
    for (;;) {
        GpuBlasNode left = nodes.n[pair];
        GpuBlasNode right = nodes.n[pair + 1u];
        float limit = bvhBoxLimit(best.t);
        float tLeft, tRight;
        bool hitLeft = bvhIntersectBox(r, left.min, left.max, limit, tLeft);
        bool hitRight = bvhIntersectBox(r, right.min, right.max, limit, tRight);
        bool leafLeft = hitLeft && left.triCount > 0u;
        bool leafRight = hitRight && right.triCount > 0u;
        if (leafLeft || leafRight) {
            // The two leaves of a leaf pair cover adjacent ranges, left first.
            uint start = leafLeft ? left.triStartOrChild : right.triStartOrChild;
            uint end = leafRight ? right.triStartOrChild + right.triCount : left.triStartOrChild + left.triCount;
            if (bvhIntersectRange(blas, r, instanceId, anyHit, start, end, best)) return true;
        }
        bool innerLeft = hitLeft && left.triCount == 0u;
        bool innerRight = hitRight && right.triCount == 0u;
        if (innerLeft && innerRight) {
            bool leftFirst = tLeft <= tRight;
            if (size < uint(BVH_STACK_SIZE)) {
                stackPair[size] = leftFirst ? right.triStartOrChild : left.triStartOrChild;
                stackT[size] = leftFirst ? tRight : tLeft;
                ++size;
            } else {
                best.flags |= kBvhHitFlagStackOverflow;
            }
            pair = leftFirst ? left.triStartOrChild : right.triStartOrChild;
            continue;
        }
        if (innerLeft || innerRight) {
            pair = innerLeft ? left.triStartOrChild : right.triStartOrChild;
            continue;
        }
        bool found = false;
        while (size > 0u) {
            --size;
            if (stackT[size] <= bvhBoxLimit(best.t)) {
                pair = stackPair[size];
                found = true;
                break;
            }
        }
        if (!found) return false;
    }
    return false;
}

// The world ray in an instance's object space, as bvh::closestHit(Tlas...) computes it with glm:
// m * vec4(p, w) = (c0 * x + c1 * y) + (c2 * z + c3 * w). The interval stays the same (no renormalisation).
vec3 bvhTransform(vec3 c0, vec3 c1, vec3 c2, vec3 c3, vec3 p, float w) {
    precise vec3 m0 = c0 * p.x;
    precise vec3 m1 = c1 * p.y;
    precise vec3 m2 = c2 * p.z;
    precise vec3 m3 = c3 * w;
    precise vec3 result = (m0 + m1) + (m2 + m3);
    return result;
}

#define BVH_TLAS_WALK bvhTraverseTlas
#define BVH_TLAS_BLAS_WALK bvhTraverseBlas
#include "bvh_tlas_walk.glsl"

BvhBest bvhStart(float tMin, float tMax) {
    BvhBest best;
    best.t = tMax;
    best.triangleId = kBvhInvalidIndex;
    best.instanceId = kBvhInvalidIndex;
    best.u = 0.0;
    best.v = 0.0;
    best.flags = 0u;
    return best;
}

// bvh::Hit{} on a miss: t = +inf, ids invalid.
GpuBvhHit bvhFinish(BvhBest best) {
    GpuBvhHit hit;
    bool found = (best.flags & kBvhHitFlagHit) != 0u;
    hit.t = found ? best.t : kBvhInfinity;
    hit.triangleId = found ? best.triangleId : kBvhInvalidIndex;
    hit.instanceId = found ? best.instanceId : kBvhInvalidIndex;
    hit.flags = best.flags;
    hit.u = found ? best.u : 0.0;
    hit.v = found ? best.v : 0.0;
    return hit;
}

// ---- public entry points ---------------------------------------------------------------------------------------

// Closest hit with ray.tMin < t < ray.tMax (bvh::closestHit(const Blas&, ...)); instanceId stays invalid.
GpuBvhHit bvhClosestHit(GpuBlasDesc blas, GpuBvhRay ray) {
    BvhBest best = bvhStart(ray.tMin, ray.tMax);
    bvhTraverseBlas(blas, bvhPrepareRay(ray.origin, ray.direction, ray.tMin, ray.tMax), kBvhInvalidIndex, false, best);
    return bvhFinish(best);
}

// Any hit with ray.tMin < t < ray.tMax (bvh::anyHit); the hit's flags say hit / stack overflow, the first
// triangle found is reported (which one depends on the visiting order).
GpuBvhHit bvhAnyHit(GpuBlasDesc blas, GpuBvhRay ray) {
    BvhBest best = bvhStart(ray.tMin, ray.tMax);
    bvhTraverseBlas(blas, bvhPrepareRay(ray.origin, ray.direction, ray.tMin, ray.tMax), kBvhInvalidIndex, true, best);
    return bvhFinish(best);
}

// Two-level versions (bvh::closestHit / anyHit over a Tlas): instanceId is the index into the instance array.
GpuBvhHit bvhClosestHitTlas(GpuTlasDesc tlas, GpuBvhRay ray) {
    BvhBest best = bvhStart(ray.tMin, ray.tMax);
    bvhTraverseTlas(tlas, ray.origin, ray.direction, ray.tMin, ray.tMax, false, best);
    return bvhFinish(best);
}

GpuBvhHit bvhAnyHitTlas(GpuTlasDesc tlas, GpuBvhRay ray) {
    BvhBest best = bvhStart(ray.tMin, ray.tMax);
    bvhTraverseTlas(tlas, ray.origin, ray.direction, ray.tMin, ray.tMax, true, best);
    return bvhFinish(best);
}

// bvh::offsetRayOrigin (Waechter & Binder, Ray Tracing Gems 2019): moves a surface point off its surface along the
// unit normal n by 256 * n ulps, or by n / 65536 near the origin where ulps are too small.
vec3 bvhOffsetRayOrigin(vec3 p, vec3 n) {
    const float kOrigin = 1.0 / 32.0;
    const float kFloatScale = 1.0 / 65536.0;
    const float kIntScale = 256.0;
    vec3 result;
    for (int i = 0; i < 3; ++i) {
        precise float scaled = kIntScale * n[i];
        int ulps = int(scaled);
        int bits = floatBitsToInt(p[i]);
        float stepped = intBitsToFloat(bits + (p[i] < 0.0 ? -ulps : ulps));
        precise float near = p[i] + kFloatScale * n[i];
        result[i] = abs(p[i]) < kOrigin ? near : stepped;
    }
    return result;
}

#endif
