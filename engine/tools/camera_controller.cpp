// camera_controller.cpp: the fly camera (see camera_controller.hpp; ports IDKEngine Camera.cs).
#include "tools/camera_controller.hpp"

#include <algorithm>
#include <cmath>

namespace idk::tools {

namespace {
constexpr float kPi = 3.14159265358979f;
constexpr float kDegrees = kPi / 180.0f;
constexpr float kDefaultMaxPitch = 89.99f * kDegrees;
}  // namespace

glm::vec3 flyForward(float yaw, float pitch) {
    return {std::cos(pitch) * std::sin(yaw), std::sin(pitch), -std::cos(pitch) * std::cos(yaw)};
}

glm::vec3 flyRight(float yaw) { return {std::cos(yaw), 0.0f, std::sin(yaw)}; }

FlyCameraParams flyParamsForBounds(const scene::Aabb& bounds) {
    FlyCameraParams params;
    if (bounds.empty()) return params;
    const float diagonal = glm::length(bounds.max - bounds.min);
    const float scale = std::clamp(diagonal / 25.0f, 0.01f, 100.0f);
    params.acceleration *= scale;
    params.stopSpeedPerSecond *= scale;
    params.radius *= scale;
    params.collision.skinWidth *= scale;
    return params;
}

FlyCameraState stepFlyCamera(const FlyCameraState& state, const FlyInput& input, float dt,
                             const FlyCameraParams& params, const CollisionWorld* world) {
    FlyCameraState next = state;
    if (!(dt > 0.0f) || !std::isfinite(dt)) return next;

    // Mouse look: degrees per pixel, +x turns right, +y (down the window) looks down.
    const float maxPitch = std::clamp(params.maxPitchDegrees, 0.0f, 89.999f) * kDegrees;
    next.yaw = state.yaw + input.mouseDelta.x * params.mouseDegreesPerPixel * kDegrees;
    next.pitch = std::clamp(state.pitch - input.mouseDelta.y * params.mouseDegreesPerPixel * kDegrees, -maxPitch, maxPitch);
    // Keep yaw in (-pi, pi] so float precision does not degrade over long sessions.
    if (next.yaw > kPi || next.yaw <= -kPi) next.yaw = std::remainder(next.yaw, 2.0f * kPi);

    // Forces (per unit mass) from the keys, in the new view's frame.
    const glm::vec3 forward = flyForward(next.yaw, next.pitch);
    const glm::vec3 right = flyRight(next.yaw);
    glm::vec3 acceleration(0.0f);
    if (input.forward) acceleration += forward * params.acceleration;
    if (input.back) acceleration -= forward * params.acceleration;
    if (input.right) acceleration += right * params.acceleration;
    if (input.left) acceleration -= right * params.acceleration;
    if (input.fast) acceleration *= params.boost;
    if (input.slow) acceleration /= params.boost;
    if (input.up) acceleration.y += params.acceleration * params.boost;

    // Integration as the original: constant acceleration over the step, rest snap, then drag.
    const glm::vec3 delta = state.velocity * dt + 0.5f * acceleration * dt * dt;
    glm::vec3 velocity = state.velocity + acceleration * dt;
    if (glm::length(velocity) < params.stopSpeedPerSecond * dt) velocity = glm::vec3(0.0f);
    const float drag = std::log10(params.dragPer144Hz) * 144.0f;
    velocity *= std::exp(drag * dt);

    if (world != nullptr && !world->empty()) {
        const SphereMoveResult moved = moveSphereDetailed(*world, state.position, params.radius, delta, params.collision);
        next.position = moved.position;
        // Like the original's projection onto the contact plane: no velocity left going into what was touched.
        if (!moved.normals.empty()) velocity = clipToPlanes(velocity, moved.normals);
    } else {
        next.position = state.position + delta;
    }
    next.velocity = velocity;
    return next;
}

scene::CameraView toCameraView(const FlyCameraState& state, const scene::CameraView& lens) {
    scene::CameraView view = lens;
    view.position = state.position;
    view.forward = flyForward(state.yaw, state.pitch);
    view.up = glm::normalize(glm::cross(flyRight(state.yaw), view.forward));
    return view;
}

FlyCameraState fromCameraView(const scene::CameraView& view) {
    FlyCameraState state;
    state.position = view.position;
    glm::vec3 f = view.forward;
    const float length = glm::length(f);
    f = length > 0.0f ? f / length : glm::vec3(0.0f, 0.0f, -1.0f);
    const float horizontal = std::sqrt(f.x * f.x + f.z * f.z);
    // Straight up/down: the yaw is where the view's up vector points (the top of the image faces that way).
    state.yaw = horizontal > 1e-6f ? std::atan2(f.x, -f.z)
                                   : std::atan2(view.up.x * -f.y, -view.up.z * -f.y);
    state.pitch = std::clamp(std::asin(std::clamp(f.y, -1.0f, 1.0f)), -kDefaultMaxPitch, kDefaultMaxPitch);
    return state;
}

}  // namespace idk::tools
