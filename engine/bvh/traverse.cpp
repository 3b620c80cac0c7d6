// traverse.cpp: BLAS traversal (the loop is walk.hpp) and the brute-force oracle.
#include "bvh/traverse.hpp"

#include "bvh/walk.hpp"

namespace idk::bvh {
namespace {

bool closer(float t, uint32_t instanceId, uint32_t triangleId, const Hit& best) {
    if (t != best.t) return t < best.t;
    if (instanceId != best.instanceId) return instanceId < best.instanceId;
    return triangleId < best.triangleId;
}

}  // namespace

namespace detail {

bool traverseBlas(const Blas& blas, const PreparedRay& ray, uint32_t instanceId, bool anyHit, Hit& best) {
    if (!ray.valid || blas.nodes.empty()) return false;
    const uint32_t* triIds = blas.triIds.data();
    const Triangle* triangles = blas.leafTriangles.data();
    auto range = [&](uint32_t first, uint32_t count) {
        bool found = false;
        for (uint32_t k = first; k < first + count; ++k) {
            TriangleHit h;
            if (!intersectTriangle(ray, triangles[k], h) || !(h.t < ray.tMax)) continue;
            const uint32_t id = triIds[k];
            if (!closer(h.t, instanceId, id, best)) continue;
            best = {id, instanceId, h.t, h.u, h.v};
            found = true;
            if (anyHit) break;
        }
        return found && anyHit;
    };
    auto bestT = [&] { return best.t; };
    if (!blas.wideNodes.empty()) {
        return walkWide(blas.wideNodes.data(), blas.nodes[0], ray, range, bestT,
                        [&](uint32_t first) { return static_cast<const void*>(triangles + first); });
    }
    return walkTree(blas.nodes.data(), ray, [&](const Node& node) { return range(node.first, node.count); }, bestT,
                    [&](const Node& node) { return static_cast<const void*>(triangles + node.first); });
}

}  // namespace detail

Hit closestHit(const Blas& blas, const Ray& ray) {
    Hit best;
    const PreparedRay prepared = prepareRay(ray);
    best.t = prepared.valid ? ray.tMax : kInfinity;
    detail::traverseBlas(blas, prepared, kInvalidIndex, false, best);
    if (!best.hit()) best = Hit{};
    return best;
}

bool anyHit(const Blas& blas, const Ray& ray) {
    Hit best;
    const PreparedRay prepared = prepareRay(ray);
    best.t = prepared.valid ? ray.tMax : kInfinity;
    return detail::traverseBlas(blas, prepared, kInvalidIndex, true, best);
}

Hit closestHitBruteForce(std::span<const Triangle> triangles, const Ray& ray) {
    Hit best;
    const PreparedRay prepared = prepareRay(ray);
    if (!prepared.valid) return best;
    best.t = ray.tMax;
    for (uint32_t id = 0; id < triangles.size(); ++id) {
        TriangleHit h;
        if (!triangles[id].isFinite()) continue;  // never referenced by a BLAS either
        if (!intersectTriangle(prepared, triangles[id], h) || !(h.t < ray.tMax)) continue;
        if (closer(h.t, kInvalidIndex, id, best)) best = {id, kInvalidIndex, h.t, h.u, h.v};
    }
    if (!best.hit()) best = Hit{};
    return best;
}

}  // namespace idk::bvh
