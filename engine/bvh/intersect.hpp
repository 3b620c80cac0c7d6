// intersect.hpp: robust ray/box and watertight ray/triangle tests, and a self-intersection-safe ray origin offset.
// Deviation from IDKEngine (Inigo Quilez's Moeller-Trumbore-style test, plain slabs): rays through shared edges
// and vertices never slip between triangles, boxes are never missed by rounding, and zero, -0 and NaN direction
// components are handled. The same rules are meant for the GLSL traversal.
#pragma once

#include "bvh/edge_function.hpp"
#include "bvh/geometry.hpp"

#include <cmath>
#include <cstdint>
#include <utility>

namespace idk::bvh {

// Per-ray constants of both tests.
struct PreparedRay {
    glm::vec3 origin{0.0f};
    glm::vec3 invDirection{0.0f};
    float tMin = 0.0f;
    float tMax = 0.0f;
    int kx = 0, ky = 1, kz = 2;  // watertight test: kz = largest |direction| axis, kx/ky keep the winding
    float sx = 0.0f, sy = 0.0f, sz = 0.0f;
    bool valid = false;          // false for NaN/inf origin or direction, zero direction, NaN or empty interval
};

PreparedRay prepareRay(const Ray& ray);

// Robust slab test (Ize 2013, "Robust BVH Ray Traversal"): the per-axis entry/exit distances are taken from the
// face the direction's sign bit points at (so -0 and +0 both work and an empty box, min > max, never passes), a
// NaN from 0 * inf (origin exactly on a face of a zero-direction axis) constrains nothing, and the exit distance
// is scaled up so rounding can only widen the slab. Ize's 1 + 2 gamma(3) assumes IEEE round-to-nearest for the
// subtraction, the product and the reciprocal 1/d; Vulkan only promises faithful sub/mul (error < 1 ulp, 2u
// relative with u = 2^-24) and 2.5 ulp (5u) for the division, so a computed distance is off by at most
// (1 + 2u)^2 (1 + 5u) - 1 ~ 9u either way, and the scaled exit (one more rounding) needs about 1 + 20u:
// kBoxRobustScale = 1 + 2^-19 = 1 + 32u keeps the test conservative on every Vulkan device. Hit when
// tNear <= tFar within [ray.tMin, tLimit]; `tNear` receives the entry distance.
inline constexpr float kBoxRobustScale = 1.0f + 0x1p-19f;

inline bool intersectBox(const PreparedRay& r, const glm::vec3& boxMin, const glm::vec3& boxMax, float tLimit,
                         float& tNear) {
    float nearT = r.tMin;
    float farT = tLimit;
    for (int axis = 0; axis < 3; ++axis) {
        const bool negative = std::signbit(r.invDirection[axis]);
        const float lo = negative ? boxMax[axis] : boxMin[axis];
        const float hi = negative ? boxMin[axis] : boxMax[axis];
        const float t0 = (lo - r.origin[axis]) * r.invDirection[axis];
        const float t1 = (hi - r.origin[axis]) * r.invDirection[axis] * kBoxRobustScale;
        nearT = t0 > nearT ? t0 : nearT;  // NaN compares false: ignored
        farT = t1 < farT ? t1 : farT;
    }
    tNear = nearT;
    return nearT <= farT;
}

struct TriangleHit {
    float t = 0.0f;
    float u = 0.0f;  // weight of v1
    float v = 0.0f;  // weight of v2 (v0 gets 1 - u - v)
};

// Watertight ray/triangle test after Woop, Benthin & Wald 2013 ("Watertight Ray/Triangle Intersection") in single
// precision: the vertices are sheared into a space where the ray is the +z axis through the origin, and the three
// 2D edge functions get an exact sign from edgeFunction() (edge_function.hpp: fp32 with a certified error bound,
// integers where it cannot decide), so a shared edge gives exactly opposite signs in its two triangles. Two-sided.
// Edges and vertices count as inside, degenerate (zero-area in ray space) triangles miss. t, u, v are fp32 as in
// the paper (det, scaled t, one reciprocal). Reports t > r.tMin only (the caller applies its own upper bound).
// The GLSL twin (bvh_traverse.glsl, bvhIntersectTriangle) performs the same operations in the same order.
inline bool intersectTriangle(const PreparedRay& r, const Triangle& tri, TriangleHit& hit) {
    const glm::vec3 a = tri.v0 - r.origin;
    const glm::vec3 b = tri.v1 - r.origin;
    const glm::vec3 c = tri.v2 - r.origin;
    const float ax = flushSubnormal(a[r.kx] - r.sx * a[r.kz]), ay = flushSubnormal(a[r.ky] - r.sy * a[r.kz]);
    const float bx = flushSubnormal(b[r.kx] - r.sx * b[r.kz]), by = flushSubnormal(b[r.ky] - r.sy * b[r.kz]);
    const float cx = flushSubnormal(c[r.kx] - r.sx * c[r.kz]), cy = flushSubnormal(c[r.ky] - r.sy * c[r.kz]);
    const EdgeValue u = edgeFunction(cx, by, cy, bx);
    const EdgeValue v = edgeFunction(ax, cy, ay, cx);
    const EdgeValue w = edgeFunction(bx, ay, by, ax);
    if ((u.sign < 0 || v.sign < 0 || w.sign < 0) && (u.sign > 0 || v.sign > 0 || w.sign > 0)) return false;
    // The three values share one sign (or are 0), so det only vanishes when all do (degenerate, or underflow).
    const float det = u.value + v.value + w.value;
    if (det == 0.0f) return false;
    const float az = r.sz * a[r.kz], bz = r.sz * b[r.kz], cz = r.sz * c[r.kz];
    const float tScaled = u.value * az + v.value * bz + w.value * cz;
    const float rcp = 1.0f / det;
    const float t = tScaled * rcp;
    if (!(t > r.tMin) || !(t < kInfinity)) return false;
    hit.t = t;
    hit.u = v.value * rcp;
    hit.v = w.value * rcp;
    return true;
}

// Moves a surface point off its surface along the normal `n` (any length-one normal on the side the new ray
// leaves from) so that a ray started there does not hit the same surface again. Wachter & Binder, "A Fast and
// Robust Method for Avoiding Self-Intersection" (Ray Tracing Gems, 2019): the offset is a fixed number of ulps
// (256 * n) away from the origin, and a fixed distance (n / 65536) near it where ulps become too small.
glm::vec3 offsetRayOrigin(const glm::vec3& p, const glm::vec3& n);

}  // namespace idk::bvh
