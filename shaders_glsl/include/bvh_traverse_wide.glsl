// bvh_traverse_wide.glsl: closest-hit and any-hit traversal of the 8-wide compressed BLAS (shared/bvh_wide_types.h,
// built by engine/bvh/wide8.cpp), alone or under the binary TLAS, for the path tracer's BVH rung and the trace-rays
// kernel. Ray preparation, the robust slab test, the watertight triangle test, the tie rule and the leaf loop are
// those of include/bvh_traverse.glsl (called, not copied), so the hits equal the binary walk's; the C++ oracle of
// this walk, step for step, is engine/bvh/wide8_traverse.cpp.
//
// Walk (ordered, after Ylitie, Karras & Laine 2017, without their octant trick): per node, every used slot's box is
// decoded and slab-tested; hit slots are ordered nearest first by entry distance (equal distances keep
// slot order; done by pushing the farthest remaining hit until one is left); all but the nearest are pushed with
// that distance, the nearest is entered; a leaf is intersected
// when it is entered; popped entries that start beyond the current hit are skipped.
//
// Decoding: origin + float(q) * 2^e. float(q) * 2^e is exact (q < 2^8, a power-of-two scale), so the result is
// one correctly rounded addition, the same with or without FMA contraction and the same in C++, where the builder
// chose q so that this decoded value bounds the child box (conservative; its unit test checks every slot).
//
// The includer may define BVH_WIDE_STACK_SIZE (default 64): at least Bvh8::stackSize of every BLAS traced. A push
// onto a full stack is dropped and reported with kBvhHitFlagStackOverflow, as in the binary walk.
// On a real GPU: the per-slot values are indexed by unrolled loop counters only (registers) and the ordering is a
// hit mask with selection passes, but the stack is a per-thread array indexed dynamically, which compilers put in
// scratch memory (as the binary walk's); Ylitie et al. push node groups (a base index and a hit mask, one entry per
// node instead of up to 7) and order by ray octant instead of distance, which cuts the stack traffic further.
#ifndef IDK_BVH_TRAVERSE_WIDE_GLSL
#define IDK_BVH_TRAVERSE_WIDE_GLSL
#extension GL_EXT_control_flow_attributes : require
#include "bvh_traverse.glsl"
#include "bvh_wide_types.h"

#ifndef BVH_WIDE_STACK_SIZE
#define BVH_WIDE_STACK_SIZE 64
#endif

layout(buffer_reference, scalar, buffer_reference_align = 16) readonly buffer BvhWideNodeRef { GpuWideNode n[]; };

// One wide BLAS (desc.nodes: GpuWideNode[], desc.triangles: its regrouped references) with a prepared ray.
bool bvhTraverseBlasWide(GpuBlasDesc blas, BvhPreparedRay r, uint instanceId, bool anyHit, inout BvhBest best) {
    if (!r.valid) return false;
    BvhWideNodeRef nodes = BvhWideNodeRef(blas.nodes);
    uint stackFirst[BVH_WIDE_STACK_SIZE];
    uint stackCount[BVH_WIDE_STACK_SIZE];
    float stackT[BVH_WIDE_STACK_SIZE];
    uint size = 0u;
    uint first = 0u;  // inner: wide node; leaf: first triangle reference
    uint count = 0u;  // 0: inner
    for (;;) {
        if (count > 0u) {
            if (bvhIntersectRange(blas, r, instanceId, anyHit, first, first + count, best)) return true;
        } else {
            GpuWideNode node = nodes.n[first];
            float limit = bvhBoxLimit(best.t);
            vec3 scale = vec3(uintBitsToFloat((node.exponents & 0xFFu) << 23),
                              uintBitsToFloat(((node.exponents >> 8) & 0xFFu) << 23),
                              uintBitsToFloat(((node.exponents >> 16) & 0xFFu) << 23));
            uint innerMask = node.exponents >> 24;
            // Per-slot values live in arrays indexed only by the unrolled loop counter (registers, no scratch).
            uint slotFirst[kWideArity];
            uint slotCount[kWideArity];
            float slotT[kWideArity];
            uint hitMask = 0u;
            uint inner = 0u;
            uint triangle = node.triangleBase;
            [[unroll]] for (uint i = 0u; i < kWideArity; ++i) {
                bool isInner = ((innerMask >> i) & 1u) != 0u;
                uint shift = 8u * (i & 3u);
                uint word = i >> 2;
                slotCount[i] = (node.counts[word] >> shift) & 0xFFu;
                slotFirst[i] = isInner ? node.childBase + inner : triangle;
                slotT[i] = 0.0;
                inner += isInner ? 1u : 0u;
                triangle += slotCount[i];
                if (!isInner && slotCount[i] == 0u) continue;
                vec3 qlo = vec3(float((node.qmin[word] >> shift) & 0xFFu), float((node.qmin[2u + word] >> shift) & 0xFFu),
                                float((node.qmin[4u + word] >> shift) & 0xFFu));
                vec3 qhi = vec3(float((node.qmax[word] >> shift) & 0xFFu), float((node.qmax[2u + word] >> shift) & 0xFFu),
                                float((node.qmax[4u + word] >> shift) & 0xFFu));
                precise vec3 lo = node.origin + qlo * scale;
                precise vec3 hi = node.origin + qhi * scale;
                float t;
                if (bvhIntersectBox(r, lo, hi, limit, t)) {
                    hitMask |= 1u << i;
                    slotT[i] = t;
                }
            }
            if (hitMask != 0u) {
                // Push the farthest hit slot until one is left (ties: the higher slot is pushed first, so equal
                // distances are popped in slot order, as the C++ walk's stable sort visits them), enter that one.
                while (bitCount(hitMask) > 1) {
                    uint far = 0u, farFirst = 0u, farCount = 0u;
                    float farT = -kBvhInfinity;
                    [[unroll]] for (uint i = 0u; i < kWideArity; ++i) {
                        if (((hitMask >> i) & 1u) != 0u && slotT[i] >= farT) {
                            far = i;
                            farT = slotT[i];
                            farFirst = slotFirst[i];
                            farCount = slotCount[i];
                        }
                    }
                    hitMask &= ~(1u << far);
                    if (size < uint(BVH_WIDE_STACK_SIZE)) {
                        stackFirst[size] = farFirst;
                        stackCount[size] = farCount;
                        stackT[size] = farT;
                        ++size;
                    } else {
                        best.flags |= kBvhHitFlagStackOverflow;
                    }
                }
                [[unroll]] for (uint i = 0u; i < kWideArity; ++i) {
                    if (((hitMask >> i) & 1u) != 0u) {
                        first = slotFirst[i];
                        count = slotCount[i];
                    }
                }
                continue;
            }
        }
        bool found = false;
        while (size > 0u) {
            --size;
            if (stackT[size] <= bvhBoxLimit(best.t)) {
                first = stackFirst[size];
                count = stackCount[size];
                found = true;
                break;
            }
        }
        if (!found) return false;
    }
    return false;
}

// The binary TLAS walk (include/bvh_tlas_walk.glsl) over wide BLASes (tlas.blases holds wide BLAS descriptors).
#define BVH_TLAS_WALK bvhTraverseTlasWide
#define BVH_TLAS_BLAS_WALK bvhTraverseBlasWide
#include "bvh_tlas_walk.glsl"

// ---- public entry points (as those of bvh_traverse.glsl) ------------------------------------------------------

GpuBvhHit bvhClosestHitWide(GpuBlasDesc blas, GpuBvhRay ray) {
    BvhBest best = bvhStart(ray.tMin, ray.tMax);
    bvhTraverseBlasWide(blas, bvhPrepareRay(ray.origin, ray.direction, ray.tMin, ray.tMax), kBvhInvalidIndex, false,
                        best);
    return bvhFinish(best);
}

GpuBvhHit bvhAnyHitWide(GpuBlasDesc blas, GpuBvhRay ray) {
    BvhBest best = bvhStart(ray.tMin, ray.tMax);
    bvhTraverseBlasWide(blas, bvhPrepareRay(ray.origin, ray.direction, ray.tMin, ray.tMax), kBvhInvalidIndex, true,
                        best);
    return bvhFinish(best);
}

GpuBvhHit bvhClosestHitTlasWide(GpuTlasDesc tlas, GpuBvhRay ray) {
    BvhBest best = bvhStart(ray.tMin, ray.tMax);
    bvhTraverseTlasWide(tlas, ray.origin, ray.direction, ray.tMin, ray.tMax, false, best);
    return bvhFinish(best);
}

GpuBvhHit bvhAnyHitTlasWide(GpuTlasDesc tlas, GpuBvhRay ray) {
    BvhBest best = bvhStart(ray.tMin, ray.tMax);
    bvhTraverseTlasWide(tlas, ray.origin, ray.direction, ray.tMin, ray.tMax, true, best);
    return bvhFinish(best);
}

#endif
