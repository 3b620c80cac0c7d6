// camera_controller.hpp: the viewer's fly camera as a pure function of (state, input, dt): the same inputs and
// time steps give the same path, bit for bit. Ports IDKEngine's Camera.cs dynamics: key forces accelerate a
// point mass (W/S along the view direction, A/D sideways, Space straight up at the boosted rate, Shift x5,
// Ctrl /5), position += v dt + a dt^2 / 2, velocity snapped to zero below 9 dt, exponential drag
// exp(144 log10(0.95) dt); mouse look in degrees per pixel with the pitch clamped short of straight up/down.
// Deviation: the camera is a sphere moved with tools::moveSphereDetailed (swept, slides along walls) and its
// velocity is clipped against the contact planes, as the original projects it onto the contact plane.
#pragma once

#include <glm/glm.hpp>

#include "scene/camera.hpp"
#include "tools/collision.hpp"

namespace idk::tools {

// Angles in radians. yaw 0 looks down -Z; positive yaw turns right (towards +X). pitch > 0 looks up.
struct FlyCameraState {
    glm::vec3 position{0.0f};
    float yaw = 0.0f;
    float pitch = 0.0f;
    glm::vec3 velocity{0.0f};
};

struct FlyInput {
    bool forward = false, back = false, left = false, right = false, up = false, fast = false;
    glm::vec2 mouseDelta{0.0f};  // pixels since the last step, window coordinates (+x right, +y down)
    bool slow = false;           // the original's Ctrl (force / 5)
};

struct FlyCameraParams {
    float acceleration = 30.0f;      // m/s^2 per key (the original's KeyboardAccelerationSpeed / MASS)
    float boost = 5.0f;              // Shift multiplies, Ctrl divides; Space always accelerates at this rate
    float dragPer144Hz = 0.95f;      // velocity *= exp(144 log10(dragPer144Hz) dt)
    float stopSpeedPerSecond = 9.0f; // |v| < this * dt snaps to 0 (the original's rest threshold)
    float mouseDegreesPerPixel = 0.09f;
    float maxPitchDegrees = 89.99f;  // the original clamps its polar angle to [0.01, 179.99] degrees
    float radius = 0.5f;             // collision sphere (the original camera's)
    SphereMoveOptions collision;
};

// The original's values suit scenes tens of metres across (Sponza). Smaller or larger scenes get acceleration,
// stop speed and radius scaled by diagonal / 25 m (clamped to [0.01, 100]), so crossing the scene takes as long.
FlyCameraParams flyParamsForBounds(const scene::Aabb& bounds);

// Unit view direction and right vector of a state (right = forward x world up).
glm::vec3 flyForward(float yaw, float pitch);
glm::vec3 flyRight(float yaw);

// One step: mouse look, forces, integration, drag, then the move through `world` (nullptr: no collision).
FlyCameraState stepFlyCamera(const FlyCameraState& state, const FlyInput& input, float dt,
                             const FlyCameraParams& params, const CollisionWorld* world);

// The camera to render: `lens` gives projection (yfov, near/far, type...), the state gives placement.
scene::CameraView toCameraView(const FlyCameraState& state, const scene::CameraView& lens);
// Placement of a view as a state at rest (pitch clamped to the controller's default limit).
FlyCameraState fromCameraView(const scene::CameraView& view);

}  // namespace idk::tools
