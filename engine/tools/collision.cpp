// collision.cpp: the collision world (world-space triangles + BVH), its box query, ray picking and the
// closest point on a triangle. The sphere motion itself is in sphere_move.cpp.
#include "tools/collision.hpp"

#include <algorithm>
#include <cmath>

#include "bvh/traverse.hpp"
#include "tools/scene_triangles.hpp"

namespace idk::tools {

CollisionWorld CollisionWorld::fromScene(const scene::Scene& scene) {
    std::vector<uint32_t> instanceOf;
    std::vector<bvh::Triangle> triangles = sceneWorldTriangles(scene, &instanceOf);
    return fromTriangles(std::move(triangles), std::move(instanceOf));
}

CollisionWorld CollisionWorld::fromTriangles(std::vector<bvh::Triangle> triangles, std::vector<uint32_t> instanceOf) {
    CollisionWorld world;
    world.triangles_ = std::move(triangles);
    world.instanceOf_ = std::move(instanceOf);
    // Triangles with a non-finite corner are left out by the builder (never referenced, never collide).
    world.blas_ = bvh::buildBlas(world.triangles_);
    return world;
}

void CollisionWorld::overlapping(const bvh::Box& box, std::vector<uint32_t>& out) const {
    if (blas_.nodes.empty() || box.isEmpty()) return;
    uint32_t stack[64];
    std::vector<uint32_t> spill;  // only for degenerate trees deeper than 64
    uint32_t size = 0;
    auto push = [&](uint32_t n) {
        if (size < 64) stack[size] = n; else spill.push_back(n);
        ++size;
    };
    auto pop = [&]() {
        --size;
        if (size < 64) return stack[size];
        const uint32_t n = spill.back();
        spill.pop_back();
        return n;
    };
    push(0);
    while (size > 0) {
        const bvh::Node& node = blas_.nodes[pop()];
        if (!node.box().overlaps(box)) continue;
        if (node.isLeaf()) {
            for (uint32_t i = node.first; i < node.first + node.count; ++i) {
                if (blas_.leafTriangles[i].box().overlaps(box)) out.push_back(blas_.triIds[i]);
            }
        } else {
            push(node.first);
            push(node.first + 1);
        }
    }
}

std::optional<RayHit> castRay(const CollisionWorld& world, glm::vec3 origin, glm::vec3 direction, float tMax) {
    if (world.empty()) return std::nullopt;
    bvh::Ray ray;
    ray.origin = origin;
    ray.direction = direction;
    ray.tMax = tMax;
    const bvh::Hit hit = bvh::closestHit(world.blas(), ray);
    if (!hit.hit()) return std::nullopt;
    const bvh::Triangle& tri = world.triangles()[hit.triangleId];
    glm::vec3 n = glm::cross(tri.v1 - tri.v0, tri.v2 - tri.v0);
    const float len = glm::length(n);
    n = len > 0.0f ? n / len : -glm::normalize(direction);
    if (glm::dot(n, direction) > 0.0f) n = -n;
    return RayHit{hit.t, hit.triangleId, world.instanceOfTriangle(hit.triangleId), n};
}

namespace {

glm::dvec3 closestOnSegment(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& p) {
    const glm::dvec3 e = b - a;
    const double ee = glm::dot(e, e);
    if (ee <= 0.0) return a;
    return a + e * std::clamp(glm::dot(p - a, e) / ee, 0.0, 1.0);
}

}  // namespace

glm::dvec3 closestPointOnTriangle(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, const glm::dvec3& p) {
    const glm::dvec3 ab = b - a, ac = c - a;
    const glm::dvec3 n = glm::cross(ab, ac);
    const double nn = glm::dot(n, n);
    // Degenerate (zero-area) triangles: the nearest of the three edges. The threshold is relative so that tiny
    // but proper triangles keep their face.
    if (!(nn > 1e-24 * glm::dot(ab, ab) * glm::dot(ac, ac)) || nn == 0.0) {
        glm::dvec3 best = closestOnSegment(a, b, p);
        for (const glm::dvec3& q : {closestOnSegment(b, c, p), closestOnSegment(c, a, p)}) {
            if (glm::dot(q - p, q - p) < glm::dot(best - p, best - p)) best = q;
        }
        return best;
    }
    // Inside the prism over the face: the projection onto the plane; else the nearest edge point.
    const glm::dvec3 ap = p - a;
    const glm::dvec3 projected = p - n * (glm::dot(ap, n) / nn);
    const bool inside = glm::dot(glm::cross(b - a, projected - a), n) >= 0.0 &&
                        glm::dot(glm::cross(c - b, projected - b), n) >= 0.0 &&
                        glm::dot(glm::cross(a - c, projected - c), n) >= 0.0;
    if (inside) return projected;
    glm::dvec3 best = closestOnSegment(a, b, p);
    for (const glm::dvec3& q : {closestOnSegment(b, c, p), closestOnSegment(c, a, p)}) {
        if (glm::dot(q - p, q - p) < glm::dot(best - p, best - p)) best = q;
    }
    return best;
}

glm::vec3 closestPointOnTriangle(const bvh::Triangle& tri, glm::vec3 p) {
    return glm::vec3(closestPointOnTriangle(glm::dvec3(tri.v0), glm::dvec3(tri.v1), glm::dvec3(tri.v2), glm::dvec3(p)));
}

}  // namespace idk::tools
