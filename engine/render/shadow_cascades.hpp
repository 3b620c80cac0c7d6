// shadow_cascades.hpp: the projections of directional-light cascades and spot-light maps (pure maths, no Vulkan;
// render/light_shadow_maps.cpp turns them into GpuShadowMap records). Cascades split the view frustum between the
// camera's near plane and the shadow distance (practical split scheme), each slice enclosed in its bounding sphere
// (whose radius depends only on the slice, not on the camera's orientation) and the sphere's centre snapped to the
// light-space texel grid, so the maps do not swim or shimmer while the camera moves or turns. Their depth range
// is the whole scene box along the light, so every caster between the light and the slice is in the map.
// Ports the role of IDKEngine's directional-shadow setup (it has point shadows only; reference 2.12).
#pragma once
#include <glm/glm.hpp>

#include <vector>

#include "scene/camera.hpp"
#include "scene/scene.hpp"

namespace idk::render {

struct ShadowProjection {
    glm::mat4 viewProjection{1.0f};  // world -> Vulkan clip; uv = ndc.xy * 0.5 + 0.5, depth = ndc.z in [0, 1]
    float texelScale = 0.0f;         // world size of one texel (perspective: at clip.w = 1)
    bool perspective = false;
    float splitFar = 0.0f;           // cascades: the view distance where this slice ends
};

// View distance up to which cascades cover the view: the camera's far plane, the farthest scene-box corner along
// the view axis, and maxDistance (0: no limit), whichever is nearest; at least twice the near plane.
float cascadeShadowDistance(const scene::CameraView& camera, const scene::Aabb& sceneBox, float maxDistance);

// `count` cascades (1..4) of a directional light shining along `direction` (unit) for a camera with the given
// viewport aspect, on square maps of `resolution` texels.
std::vector<ShadowProjection> directionalCascades(const scene::CameraView& camera, float aspect,
                                                  const scene::Aabb& sceneBox, glm::vec3 direction, uint32_t count,
                                                  uint32_t resolution, float maxDistance);

// Largest outer cone half-angle a single perspective map covers (with its filter margin); wider spots use a cube.
constexpr float kMaxSpotMapHalfAngle = 1.3f;  // about 74.5 degrees

// The spot's outer cone half-angle from its GpuLight constants (cos outer = -spotOffset / spotScale).
float spotOuterAngle(float spotScale, float spotOffset);

// A spot light's perspective map: looks along `direction` from `position`, its field of view the cone plus the
// filter margin; near/far as the point cubes (render/point_shadow_maps.hpp pointShadowPlanes).
ShadowProjection spotShadowProjection(glm::vec3 position, glm::vec3 direction, float outerAngle, glm::vec2 planes,
                                      uint32_t resolution);

}  // namespace idk::render
