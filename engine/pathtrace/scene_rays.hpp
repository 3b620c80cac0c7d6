// scene_rays.hpp: ray queries of the CPU path tracer against a PathTraceScene's TLAS: the closest surface that
// is not an alpha pass-through (MASK below its cutoff, BLEND with probability 1 - alpha), and shadow-ray
// visibility with the same rule. IDKEngine's path tracer lets alpha skips consume bounces (reference section 5);
// here they do not.
#pragma once
#include <glm/glm.hpp>

#include "pathtrace/pt_material.hpp"
#include "pathtrace/pt_scene.hpp"
#include "shared/pt_common.h"

namespace idk::pathtrace {

// Bounds the number of alpha pass-throughs along one ray (a stack of cut-out leaves), so it always terminates.
constexpr uint32_t kMaxAlphaSkips = 64;

struct SceneHit {
    bool hit = false;
    float t = 0.0f;              // distance from the ray origin (unit direction)
    PtHitPoint point;
    PtMaterialHit material;
};

// Closest opaque-enough hit along origin + t * direction, t in (0, tMax); `direction` unit. BLEND coverage
// draws from `rng`. The material is evaluated for wo = -direction.
SceneHit closestSurface(const PathTraceScene& pts, glm::vec3 origin, glm::vec3 direction, float tMax,
                        gpu::PtRng& rng);

// True when nothing blocks the segment from origin to origin + distance * direction (exclusive of both ends).
bool visible(const PathTraceScene& pts, glm::vec3 origin, glm::vec3 direction, float distance, gpu::PtRng& rng);

// A ray origin just off a surface point on the side `towards` points to (bvh::offsetRayOrigin).
glm::vec3 offsetOrigin(const glm::vec3& p, const glm::vec3& geometricNormal, const glm::vec3& towards);

}  // namespace idk::pathtrace
