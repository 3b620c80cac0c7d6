// traverse.hpp: CPU ray traversal of a BLAS (closest hit, any hit) and the brute-force oracle it is tested
// against. The CPU traversal is itself the oracle of the later GLSL traversal. Port of IDKEngine BVH.Intersect /
// BVHIntersect.glsl with the robust tests of intersect.hpp. Closest hit is the smallest t, ties broken by the
// smaller instance id (TLAS) and then the smaller triangle id, so the answer does not depend on the visiting order.
#pragma once

#include "bvh/blas.hpp"
#include "bvh/geometry.hpp"
#include "bvh/intersect.hpp"

#include <cstdint>
#include <span>

namespace idk::bvh {

struct Hit {
    uint32_t triangleId = kInvalidIndex;  // original triangle index in the mesh
    uint32_t instanceId = kInvalidIndex;  // TLAS traversal only
    float t = kInfinity;
    float u = 0.0f;  // barycentric weight of v1
    float v = 0.0f;  // barycentric weight of v2
    bool hit() const { return triangleId != kInvalidIndex; }
};

// Closest hit with ray.tMin < t < ray.tMax, against the BLAS's own copy of its triangles (leafTriangles).
// An invalid ray (NaN/inf components, zero direction) hits nothing.
Hit closestHit(const Blas& blas, const Ray& ray);

// True when any triangle is hit with ray.tMin < t < ray.tMax (returns at the first one found).
bool anyHit(const Blas& blas, const Ray& ray);

// Every triangle tested in index order with the same intersector and tie rule: the oracle for tests.
Hit closestHitBruteForce(std::span<const Triangle> triangles, const Ray& ray);

namespace detail {

// Traverses `blas` with an already prepared ray and improves `best` (t, then triangle id, then instance id).
// Returns true as soon as any hit is found when `anyHit` is set.
bool traverseBlas(const Blas& blas, const PreparedRay& ray, uint32_t instanceId, bool anyHit, Hit& best);

}  // namespace detail
}  // namespace idk::bvh
