// shot_lights.cpp: spawning, moving and packing the shot lights.
#include "viewer/shot_lights.hpp"

#include <array>

namespace idk::viewer {

void ShotLights::shoot(glm::vec3 origin, glm::vec3 direction, float speed, float radius, float intensity) {
    static constexpr std::array<glm::vec3, 4> kPalette = {glm::vec3(1.0f, 0.8f, 0.6f), glm::vec3(0.6f, 0.8f, 1.0f),
                                                          glm::vec3(1.0f, 0.5f, 0.5f), glm::vec3(0.6f, 1.0f, 0.6f)};
    ShotLight light;
    light.body.center = origin;
    light.body.velocity = direction * speed;
    light.body.radius = radius;
    light.color = kPalette[shots_++ % kPalette.size()];
    light.intensity = intensity;
    if (lights_.size() >= kMaxShotLights) lights_.erase(lights_.begin());
    lights_.push_back(light);
}

void ShotLights::step(const tools::CollisionWorld& world, float dt) {
    for (ShotLight& l : lights_) l.body = tools::stepBouncingSphere(world, l.body, dt);
}

std::vector<gpu::GpuLight> ShotLights::gpuLights() const {
    std::vector<gpu::GpuLight> out;
    for (const ShotLight& l : lights_) {
        gpu::GpuLight g{};
        g.position = l.body.center;
        g.type = gpu::kLightPoint;
        g.direction = glm::vec3(0.0f, 0.0f, -1.0f);
        g.range = 0.0f;
        g.intensity = l.color * l.intensity;
        out.push_back(g);
    }
    return out;
}

}  // namespace idk::viewer
