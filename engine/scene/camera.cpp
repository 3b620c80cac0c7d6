// camera.cpp: view/projection matrices in the Vulkan convention documented in camera.hpp (y down, depth 0..1,
// optional infinite far plane), the default camera (file camera or auto-fit to the bounds) and the orbit camera.
#include "scene/camera.hpp"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace idk::scene {

glm::mat4 lookAtView(const glm::vec3& eye, const glm::vec3& target, const glm::vec3& up) {
    return glm::lookAtRH(eye, target, up);
}

glm::mat4 viewMatrix(const CameraView& camera) {
    return lookAtView(camera.position, camera.position + camera.forward, camera.up);
}

glm::mat4 perspectiveVulkan(float yfov, float aspectRatio, float znear, float zfar) {
    // clip = M * view; w_clip = -z_view; depth = z_clip / w_clip.
    // Finite: depth(z = -n) = 0, depth(z = -f) = 1  =>  m22 = f / (n - f), m32 = n f / (n - f).
    // Infinite (f -> inf): m22 = -1, m32 = -n.
    const float focal = 1.0f / std::tan(0.5f * yfov);
    glm::mat4 m(0.0f);
    m[0][0] = focal / aspectRatio;
    m[1][1] = -focal;  // Vulkan NDC y points down
    m[2][3] = -1.0f;
    if (zfar > 0.0f) {
        m[2][2] = zfar / (znear - zfar);
        m[3][2] = znear * zfar / (znear - zfar);
    } else {
        m[2][2] = -1.0f;
        m[3][2] = -znear;
    }
    return m;
}

glm::mat4 orthographicVulkan(float xmag, float ymag, float znear, float zfar) {
    // depth = (-z - n) / (f - n): 0 at the near plane, 1 at the far plane.
    glm::mat4 m(1.0f);
    m[0][0] = 1.0f / xmag;
    m[1][1] = -1.0f / ymag;
    m[2][2] = -1.0f / (zfar - znear);
    m[3][2] = -znear / (zfar - znear);
    return m;
}

glm::mat4 projectionMatrix(const CameraView& camera, float viewportAspect) {
    if (camera.type == CameraType::Orthographic) {
        return orthographicVulkan(camera.xmag, camera.ymag, camera.znear, camera.zfar);
    }
    const float aspect = camera.aspectRatio > 0.0f ? camera.aspectRatio : viewportAspect;
    return perspectiveVulkan(camera.yfov, aspect, camera.znear, camera.zfar);
}

CameraView cameraView(const Camera& camera) {
    CameraView view;
    view.position = glm::vec3(camera.world[3]);
    view.forward = glm::normalize(-glm::vec3(camera.world[2]));
    view.up = glm::normalize(glm::vec3(camera.world[1]));
    view.type = camera.type;
    view.yfov = camera.yfov;
    view.aspectRatio = camera.aspectRatio;
    view.znear = camera.znear;
    view.zfar = camera.zfar;
    view.xmag = camera.xmag;
    view.ymag = camera.ymag;
    return view;
}

float autoFitDistance(float radius, float yfov) {
    return radius / std::sin(0.5f * yfov);
}

namespace {

// Near/far planes that enclose a sphere of `radius` seen from `distance` (> radius) with some slack.
void bracketSphere(CameraView& view, float distance, float radius) {
    view.znear = std::max(0.5f * (distance - radius), 1e-3f * distance);
    view.zfar = 2.0f * (distance + radius);
}

}  // namespace

CameraView autoFitCamera(const Aabb& bounds) {
    glm::vec3 centre(0.0f);
    float radius = 1.0f;
    if (!bounds.empty()) {
        centre = bounds.centre();
        radius = 0.5f * glm::length(bounds.max - bounds.min);
        if (!(radius > 0.0f) || !std::isfinite(radius)) radius = 1.0f;  // a single point, or garbage
    }
    CameraView view;
    const float distance = autoFitDistance(radius, kDefaultYfov);
    view.position = centre + glm::vec3(0.0f, 0.0f, distance);
    view.forward = glm::vec3(0.0f, 0.0f, -1.0f);
    view.up = glm::vec3(0.0f, 1.0f, 0.0f);
    view.yfov = kDefaultYfov;
    bracketSphere(view, distance, radius);
    return view;
}

CameraView orbitCamera(const glm::vec3& target, float radius, float theta, float phi) {
    const glm::vec3 offset(std::sin(phi) * std::sin(theta), std::cos(phi), std::sin(phi) * std::cos(theta));
    CameraView view;
    view.position = target + radius * offset;
    view.forward = -offset;
    // Up is +Y projected orthogonal to forward; straight above/below (phi = 0 or pi), use the orbit's
    // "towards -theta" direction so the image keeps a stable orientation.
    glm::vec3 up(0.0f, 1.0f, 0.0f);
    if (std::abs(offset.y) > 0.9999f) {
        up = glm::vec3(-std::sin(theta), 0.0f, -std::cos(theta)) * (offset.y > 0.0f ? 1.0f : -1.0f);
    }
    view.up = glm::normalize(up - glm::dot(up, view.forward) * view.forward);
    view.yfov = kDefaultYfov;
    view.znear = std::max(0.01f * radius, 1e-4f);  // the subject's size is unknown: a generous range
    view.zfar = std::max(100.0f * radius, 1.0f);
    return view;
}

CameraView defaultCamera(const Scene& scene) {
    if (!scene.cameras.empty()) return cameraView(scene.cameras.front());
    return autoFitCamera(scene.bounds);
}

}  // namespace idk::scene
