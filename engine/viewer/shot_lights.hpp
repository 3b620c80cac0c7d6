// shot_lights.hpp: the lights the player shoots in FPS mode (right-click): shadow-casting point lights that fly
// from the camera along the view direction and bounce off the scene (tools::stepBouncingSphere, restitution 1).
// Ports IDKEngine's LightManager "shoot light" (internals 2.10, 2.19). At most kMaxShotLights; the oldest goes.
#pragma once
#include <vector>

#include <glm/glm.hpp>

#include "shared/scene_types.h"
#include "tools/collision.hpp"

namespace idk::viewer {

inline constexpr size_t kMaxShotLights = 8;

struct ShotLight {
    tools::BouncingSphere body;
    glm::vec3 color{1.0f};
    float intensity = 1.0f;  // candela
};

class ShotLights {
public:
    // speed and radius in scene units (scaled to the scene by the caller); colour cycles through a palette.
    void shoot(glm::vec3 origin, glm::vec3 direction, float speed, float radius, float intensity);
    void step(const tools::CollisionWorld& world, float dt);
    void clear() { lights_.clear(); }
    const std::vector<ShotLight>& lights() const noexcept { return lights_; }
    std::vector<gpu::GpuLight> gpuLights() const;  // point lights for Renderer::setExtraLights

private:
    std::vector<ShotLight> lights_;
    uint32_t shots_ = 0;
};

}  // namespace idk::viewer
