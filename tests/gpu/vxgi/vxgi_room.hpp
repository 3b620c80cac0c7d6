// vxgi_room.hpp: the closed room the VXGI GPU tests share: a 2 m cube of inward-facing walls (floor, left, right,
// back, front) whose ceiling, in the plane y = 1, is an emissive panel (quad 5, 0.6 m square) and four strips
// around it; a camera inside it, looking slightly up at the back wall. Materials are dielectric.
#pragma once

#include <array>
#include <vector>

#include "scene/camera.hpp"
#include "support/placed_quads.hpp"

namespace idk::test {

// One wall: a quad at `centre` facing `normal`, `half` its half sizes, with base colour `colour`.
inline PlacedQuad roomWall(glm::vec3 centre, glm::vec3 normal, glm::vec2 half, glm::vec3 colour = glm::vec3(0.6f)) {
    PlacedQuad q;
    q.centre = centre;
    q.normal = normal;
    q.halfSize = half;
    q.baseColor = colour;
    return q;
}

// The room's quads: `walls` the base colours of floor, left, right, back and front; the panel and the strips are
// grey 0.6.
inline std::vector<PlacedQuad> closedRoomQuads(const std::array<glm::vec3, 5>& walls = {
                                                   glm::vec3(0.6f), glm::vec3(0.6f), glm::vec3(0.6f), glm::vec3(0.6f),
                                                   glm::vec3(0.6f)}) {
    const auto wall = roomWall;
    const glm::vec3 grey(0.6f);
    std::vector<PlacedQuad> q;
    q.push_back(wall({0, -1, 0}, {0, 1, 0}, {1, 1}, walls[0]));  // floor
    q.push_back(wall({-1, 0, 0}, {1, 0, 0}, {1, 1}, walls[1]));  // left
    q.push_back(wall({1, 0, 0}, {-1, 0, 0}, {1, 1}, walls[2]));  // right
    q.push_back(wall({0, 0, -1}, {0, 0, 1}, {1, 1}, walls[3]));  // back
    q.push_back(wall({0, 0, 1}, {0, 0, -1}, {1, 1}, walls[4]));  // front (behind the camera)
    q.push_back(wall({0, 1, 0}, {0, -1, 0}, {0.3f, 0.3f}, grey));  // the panel
    // quadAxes: a horizontal quad's local x is world x, local y world -z or z: the strips' half sizes are (x, z).
    q.push_back(wall({-0.65f, 1, 0}, {0, -1, 0}, {0.35f, 1}, grey));
    q.push_back(wall({0.65f, 1, 0}, {0, -1, 0}, {0.35f, 1}, grey));
    q.push_back(wall({0, 1, -0.65f}, {0, -1, 0}, {0.3f, 0.35f}, grey));
    q.push_back(wall({0, 1, 0.65f}, {0, -1, 0}, {0.3f, 0.35f}, grey));
    return q;
}

// The room with one more quad standing in it (index kStandingQuad, facing the camera, blue-grey), which the
// transparency tests make transparent.
inline constexpr size_t kStandingQuad = 10;  // after the room's ten
inline std::vector<PlacedQuad> closedRoomWithStandingQuad() {
    std::vector<PlacedQuad> q = closedRoomQuads();
    q.push_back(roomWall({0.1f, -0.35f, -0.3f}, {0, 0, 1}, {0.35f, 0.35f}, glm::vec3(0.5f, 0.6f, 0.7f)));
    return q;
}

// The room's scene (closedRoomQuads), dielectric, quad 5 emitting `panelEmission`.
inline scene::Scene closedRoomScene(glm::vec3 panelEmission, const std::vector<PlacedQuad>& quads = closedRoomQuads()) {
    scene::Scene s = makePlacedQuadScene(quads);
    for (scene::Material& m : s.materials) m.metallic = 0.0f;
    s.materials[5].emissive = panelEmission;
    return s;
}

// The camera at `position` (the tests use z = 0.95, near the front wall), looking slightly up at the back wall.
inline scene::CameraView closedRoomCamera(glm::vec3 position = {0.0f, -0.1f, 0.95f}) {
    scene::CameraView c;
    c.position = position;
    c.forward = glm::normalize(glm::vec3(0.0f, 0.25f, -1.0f));
    c.up = glm::normalize(glm::cross(glm::cross(c.forward, glm::vec3(0, 1, 0)), c.forward));
    c.yfov = 1.4f;
    c.znear = 0.01f;
    return c;
}

}  // namespace idk::test
