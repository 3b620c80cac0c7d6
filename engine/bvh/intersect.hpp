// intersect.hpp: robust ray/box and watertight ray/triangle tests, and a self-intersection-safe ray origin offset.
// Deviation from IDKEngine (Inigo Quilez's Moeller-Trumbore-style test, plain slabs): rays through shared edges
// and vertices never slip between triangles, boxes are never missed by rounding, and zero, -0 and NaN direction
// components are handled. The same rules are meant for the GLSL traversal.
#pragma once

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
// is scaled up by 1 + 2 * gamma(3) so rounding can only widen the slab. Hit when tNear <= tFar within
// [ray.tMin, tLimit]; `tNear` receives the entry distance.
inline bool intersectBox(const PreparedRay& r, const glm::vec3& boxMin, const glm::vec3& boxMax, float tLimit,
                         float& tNear) {
    constexpr float kRobustScale = 1.0f + 2.0f * (3.0f * 0x1p-24f) / (1.0f - 3.0f * 0x1p-24f);
    float nearT = r.tMin;
    float farT = tLimit;
    for (int axis = 0; axis < 3; ++axis) {
        const bool negative = std::signbit(r.invDirection[axis]);
        const float lo = negative ? boxMax[axis] : boxMin[axis];
        const float hi = negative ? boxMin[axis] : boxMax[axis];
        const float t0 = (lo - r.origin[axis]) * r.invDirection[axis];
        const float t1 = (hi - r.origin[axis]) * r.invDirection[axis] * kRobustScale;
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

// Watertight ray/triangle test after Woop, Benthin & Wald 2013 ("Watertight Ray/Triangle Intersection"): the
// vertices are sheared into a space where the ray is the +z axis through the origin, and the three 2D edge
// functions are evaluated in double precision (products of two floats are exact in double, so every sign is
// exact, a shared edge gives exactly opposite values in its two triangles, and FMA contraction cannot change
// anything). Two-sided. Edges and vertices count as inside, degenerate (zero-area in ray space) triangles miss.
// Reports t > r.tMin only (the caller applies its own upper bound).
inline bool intersectTriangle(const PreparedRay& r, const Triangle& tri, TriangleHit& hit) {
    const glm::vec3 a = tri.v0 - r.origin;
    const glm::vec3 b = tri.v1 - r.origin;
    const glm::vec3 c = tri.v2 - r.origin;
    const double ax = a[r.kx] - r.sx * a[r.kz], ay = a[r.ky] - r.sy * a[r.kz];
    const double bx = b[r.kx] - r.sx * b[r.kz], by = b[r.ky] - r.sy * b[r.kz];
    const double cx = c[r.kx] - r.sx * c[r.kz], cy = c[r.ky] - r.sy * c[r.kz];
    // ax..cy are floats widened to double: each product below is exact, each difference rounded once.
    const double u = cx * by - cy * bx;
    const double v = ax * cy - ay * cx;
    const double w = bx * ay - by * ax;
    if ((u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0)) return false;
    const double det = u + v + w;
    if (det == 0.0) return false;
    const double az = double(r.sz) * a[r.kz], bz = double(r.sz) * b[r.kz], cz = double(r.sz) * c[r.kz];
    const double rcp = 1.0 / det;
    const double t = (u * az + v * bz + w * cz) * rcp;
    if (!(t > double(r.tMin)) || !(t < double(kInfinity))) return false;
    hit.t = float(t);
    if (!(hit.t > r.tMin)) return false;
    hit.u = float(v * rcp);
    hit.v = float(w * rcp);
    return true;
}

// Moves a surface point off its surface along the normal `n` (any length-one normal on the side the new ray
// leaves from) so that a ray started there does not hit the same surface again. Wachter & Binder, "A Fast and
// Robust Method for Avoiding Self-Intersection" (Ray Tracing Gems, 2019): the offset is a fixed number of ulps
// (256 * n) away from the origin, and a fixed distance (n / 65536) near it where ulps become too small.
glm::vec3 offsetRayOrigin(const glm::vec3& p, const glm::vec3& n);

}  // namespace idk::bvh
