// picking.hpp: right-click selection in GUI mode: a CPU ray from the camera through the cursor's pixel, traced
// through the collision world's BVH (tools::castRay), mapped back to the scene instance whose triangle it hit.
// Ports IDKEngine's Application.cs picking (it reads an object-id texture; a BVH ray needs no GPU readback).
#pragma once
#include <optional>

#include <glm/glm.hpp>

#include "scene/camera.hpp"
#include "tools/collision.hpp"

namespace idk::viewer {

struct Pick {
    uint32_t instance = 0;  // Scene::instances index
    uint32_t node = 0;      // Scene::nodes index of that instance
    glm::vec3 point{0.0f};  // world-space hit point
    float distance = 0.0f;
};

// World-space ray through the centre of pixel `cursor` (window pixels, y down) of a `width` x `height` view.
void cursorRay(const scene::CameraView& camera, glm::vec2 cursor, uint32_t width, uint32_t height,
               glm::vec3& origin, glm::vec3& direction);

std::optional<Pick> pickInstance(const scene::Scene& scene, const tools::CollisionWorld& world,
                                 const scene::CameraView& camera, glm::vec2 cursor, uint32_t width, uint32_t height);

}  // namespace idk::viewer
