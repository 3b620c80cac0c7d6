// picking.cpp: unprojects the cursor with the renderer's own matrices and casts the ray through the BVH.
#include "viewer/picking.hpp"

namespace idk::viewer {

void cursorRay(const scene::CameraView& camera, glm::vec2 cursor, uint32_t width, uint32_t height,
               glm::vec3& origin, glm::vec3& direction) {
    const float aspect = float(width) / float(height);
    const glm::mat4 inverse = glm::inverse(scene::projectionMatrix(camera, aspect) * scene::viewMatrix(camera));
    // NDC: x right, y DOWN (the projection flips y, see scene/camera.hpp), depth 0 near .. 1 far.
    const glm::vec2 ndc((cursor.x + 0.5f) / float(width) * 2.0f - 1.0f, (cursor.y + 0.5f) / float(height) * 2.0f - 1.0f);
    glm::vec4 nearPoint = inverse * glm::vec4(ndc, 0.0f, 1.0f);
    glm::vec4 farPoint = inverse * glm::vec4(ndc, 0.5f, 1.0f);  // 0.5, not 1: an infinite far plane maps to 1
    nearPoint /= nearPoint.w;
    farPoint /= farPoint.w;
    origin = glm::vec3(nearPoint);
    direction = glm::normalize(glm::vec3(farPoint) - glm::vec3(nearPoint));
}

std::optional<Pick> pickInstance(const scene::Scene& scene, const tools::CollisionWorld& world,
                                 const scene::CameraView& camera, glm::vec2 cursor, uint32_t width, uint32_t height) {
    if (width == 0 || height == 0 || world.empty()) return std::nullopt;
    glm::vec3 origin, direction;
    cursorRay(camera, cursor, width, height, origin, direction);
    std::optional<tools::RayHit> hit = tools::castRay(world, origin, direction);
    if (!hit || hit->instance >= scene.instances.size()) return std::nullopt;
    Pick pick;
    pick.instance = hit->instance;
    pick.node = scene.instances[hit->instance].node;
    pick.point = origin + direction * hit->t;
    pick.distance = glm::length(pick.point - camera.position);  // from the eye (the ray starts at the near plane)
    return pick;
}

}  // namespace idk::viewer
