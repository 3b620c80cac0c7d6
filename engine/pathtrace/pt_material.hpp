// pt_material.hpp: the glTF material at a ray hit for the CPU path tracer: hit attributes interpolated from the
// geometry (world position, front-face geometric normal, vertex normal and tangent, both UV sets, COLOR_0), then
// base colour x vertex colour x texture, metallic-roughness, normal map (tangent frame with handedness),
// emission, transmission and volume, each texture with its KHR_texture_transform and texcoord set, into a
// gpu::PtSurface for pt_sampling.h. The CPU twin of include/material_eval.glsl + gbuffer.frag.glsl, fixing
// IDKEngine's normal-map bugs (reference section 5) the same way.
#pragma once
#include <cstdint>

#include <glm/glm.hpp>

#include "pathtrace/pt_scene.hpp"
#include "shared/pt_types.h"

namespace idk::pathtrace {

struct PtHitPoint {
    glm::vec3 position{0.0f};         // world
    glm::vec3 geometricNormal{0.0f, 0.0f, 1.0f};  // unit, the front face's side (winding, mirroring included)
    glm::vec3 normal{0.0f, 0.0f, 1.0f};           // interpolated vertex normal, world, unit
    glm::vec4 tangent{0.0f};          // world xyz (unit) + handedness w; w = 0: none
    glm::vec2 uv0{0.0f}, uv1{0.0f};
    glm::vec4 color{1.0f};
    uint32_t material = 0;
    uint32_t instance = 0, triangle = 0;
};

// Attributes at barycentrics (u of vertex 1, v of vertex 2) of `triangle` of `instance` (bvh::Hit numbering).
PtHitPoint hitPoint(const PathTraceScene& pts, uint32_t instance, uint32_t triangle, float u, float v);

// Everything the tracer needs about the material at a hit seen from direction wo (unit, pointing away).
struct PtMaterialHit {
    gpu::PtSurface surface{};
    float alpha = 1.0f;                 // base colour alpha (texture x factor x vertex colour)
    bool passThrough = false;           // MASK with alpha < cutoff
    float blendAlpha = 1.0f;            // BLEND: coverage probability; 1 otherwise
    bool unlit = false;                 // KHR_materials_unlit: surface.emission = base colour, nothing scatters
};

PtMaterialHit evaluateMaterial(const PathTraceScene& pts, const PtHitPoint& hit, const glm::vec3& wo);

// Emitted radiance of `hit` toward wo: emissive factor x emissive texture, 0 behind a single-sided emitter.
glm::vec3 emissionAt(const PathTraceScene& pts, const PtHitPoint& hit, const glm::vec3& wo);

}  // namespace idk::pathtrace
