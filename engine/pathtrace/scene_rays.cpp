// scene_rays.cpp: closest-hit and visibility queries with alpha pass-through for the CPU path tracer.
#include "pathtrace/scene_rays.hpp"

#include <cmath>

#include "bvh/intersect.hpp"

namespace idk::pathtrace {

glm::vec3 offsetOrigin(const glm::vec3& p, const glm::vec3& geometricNormal, const glm::vec3& towards) {
    return bvh::offsetRayOrigin(p, glm::dot(towards, geometricNormal) >= 0.0f ? geometricNormal : -geometricNormal);
}

SceneHit closestSurface(const PathTraceScene& pts, glm::vec3 origin, glm::vec3 direction, float tMax,
                        gpu::PtRng& rng) {
    SceneHit out;
    float travelled = 0.0f;
    for (uint32_t skip = 0; skip <= kMaxAlphaSkips; ++skip) {
        bvh::Ray ray;
        ray.origin = origin;
        ray.direction = direction;
        ray.tMax = tMax - travelled;
        const bvh::Hit hit = bvh::closestHit(pts.tlas, pts.instances, pts.blases, ray);
        if (!hit.hit()) return out;
        PtHitPoint point = hitPoint(pts, hit.instanceId, hit.triangleId, hit.u, hit.v);
        PtMaterialHit material = evaluateMaterial(pts, point, -direction);
        bool pass = material.passThrough;
        if (!pass && material.blendAlpha < 1.0f) pass = gpu::ptRandom(rng) >= material.blendAlpha;
        if (!pass) {
            out.hit = true;
            out.t = travelled + hit.t;
            out.point = point;
            out.material = material;
            return out;
        }
        travelled += hit.t;
        origin = offsetOrigin(point.position, point.geometricNormal, direction);
    }
    return out;
}

bool visible(const PathTraceScene& pts, glm::vec3 origin, glm::vec3 direction, float distance, gpu::PtRng& rng) {
    // Stop a little short of the light so the emitter itself (or the surface the point lies on) does not count.
    const float tMax = distance >= gpu::kPtFar ? bvh::kInfinity : distance * (1.0f - 1e-4f);
    if (!pts.alphaTesting) {
        bvh::Ray ray;
        ray.origin = origin;
        ray.direction = direction;
        ray.tMax = tMax;
        return !bvh::anyHit(pts.tlas, pts.instances, pts.blases, ray);
    }
    const SceneHit hit = closestSurface(pts, origin, direction, tMax, rng);
    return !hit.hit;
}

}  // namespace idk::pathtrace
