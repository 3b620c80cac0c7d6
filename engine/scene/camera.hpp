// camera.hpp: camera placement and matrices: view and Vulkan projection matrices, the scene's default camera
// (the file's own camera, else an auto-fit view of the bounds) and the orbit camera of the Khronos
// render-fidelity project (see ../shared/scenes/README.md).
//
// Conventions. View space is right-handed: the camera looks down -Z with +Y up (as glTF cameras). Projections
// map view space to Vulkan clip space with:
//   * y pointing DOWN in NDC: the matrix negates y, so framebuffer row 0 is the top of the image and no negative
//     viewport height is needed. glTF's counter-clockwise front faces then rasterize as front faces with
//     VK_FRONT_FACE_COUNTER_CLOCKWISE.
//   * depth 0 at the near plane and 1 at the far plane (standard, not reversed, as in IDKEngine); with zfar = 0
//     the far plane is at infinity (depth -> 1 as distance -> infinity). Depth test LESS, clear to 1.
#pragma once

#include <glm/glm.hpp>

#include "scene/scene.hpp"

namespace idk::scene {

constexpr float kDefaultYfov = 0.785398163f;  // 45 degrees, the auto-fit and orbit vertical FOV

// Everything a renderer needs to place a camera.
struct CameraView {
    glm::vec3 position{0.0f};
    glm::vec3 forward{0.0f, 0.0f, -1.0f};  // unit
    glm::vec3 up{0.0f, 1.0f, 0.0f};        // unit, orthogonal to forward
    CameraType type = CameraType::Perspective;
    float yfov = kDefaultYfov;  // radians
    float aspectRatio = 0.0f;   // 0: use the viewport's
    float znear = 0.1f;
    float zfar = 0.0f;               // 0: infinite (perspective only)
    float xmag = 1.0f, ymag = 1.0f;  // orthographic half extents
};

// World -> view (right-handed, looking down -Z).
glm::mat4 lookAtView(const glm::vec3& eye, const glm::vec3& target, const glm::vec3& up);
glm::mat4 viewMatrix(const CameraView& camera);

// View -> Vulkan clip space, y down, depth 0 (near) .. 1 (far). zfar = 0: infinite far plane.
glm::mat4 perspectiveVulkan(float yfov, float aspectRatio, float znear, float zfar);
glm::mat4 orthographicVulkan(float xmag, float ymag, float znear, float zfar);
// Uses camera.aspectRatio, or viewportAspect when the camera has none.
glm::mat4 projectionMatrix(const CameraView& camera, float viewportAspect);

// A file camera as a CameraView.
CameraView cameraView(const Camera& camera);

// Distance at which a sphere of `radius` exactly fills the vertical FOV: the view cone's half-angle yfov / 2 is
// tangent to the sphere, so distance = radius / sin(yfov / 2).
float autoFitDistance(float radius, float yfov = kDefaultYfov);

// Looks at the centre of `bounds` from +Z at autoFitDistance(bounding sphere radius, 45 degrees); the bounding
// sphere is centred on the box with radius = half its diagonal. An empty box is treated as a unit sphere at the
// origin. znear/zfar bracket the sphere.
CameraView autoFitCamera(const Aabb& bounds);

// Orbit placement: eye = target + radius * (sin(phi) sin(theta), cos(phi), sin(phi) cos(theta)) in glTF's Y-up
// space, looking at target, vertical FOV 45 degrees. theta = 0, phi = pi/2 puts the eye on +Z.
// znear = 0.01 * radius, zfar = 100 * radius (callers may tighten them).
CameraView orbitCamera(const glm::vec3& target, float radius, float theta = 0.0f, float phi = 1.57079633f);

// The scene's first camera if it has one, else autoFitCamera(scene.bounds).
CameraView defaultCamera(const Scene& scene);

}  // namespace idk::scene
