// camera_spec.hpp: the cameras of `idk render` on the command line: --camera eye=X,Y,Z:target=X,Y,Z[:up=X,Y,Z]
// [:yfov=DEG], --orbit theta=DEG,phi=DEG[,radius=R][,target=X,Y,Z][,yfov=DEG] (the Khronos glTF render-fidelity /
// model-viewer convention: theta = azimuth around +Y from +Z, phi = polar angle from +Y; radius and target
// auto-fitted to the scene bounds when omitted, as the auto-fit camera), --camera-index N (the file's own
// cameras) and --orbit-frames N (a turntable: N views, theta stepping 360/N degrees). Malformed specs throw
// core::CliError naming the flag (exit 2). No IDKEngine counterpart (its renders come from the fly camera).
#pragma once
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/cli.hpp"
#include "scene/camera.hpp"

namespace idk::app {

struct LookAtSpec {
    glm::vec3 eye{0.0f};
    glm::vec3 target{0.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    double yfovDegrees = 45.0;
};

struct OrbitSpec {
    double thetaDegrees = 0.0;
    double phiDegrees = 90.0;
    std::optional<float> radius;        // omitted: auto-fit (scene::autoFitDistance of the bounding sphere)
    std::optional<glm::vec3> target;    // omitted: the centre of the scene bounds
    double yfovDegrees = 45.0;
};

LookAtSpec parseLookAtSpec(const std::string& text);  // --camera
OrbitSpec parseOrbitSpec(const std::string& text);    // --orbit

// Degrees to the radians a CameraView stores (in double, then rounded once to float).
float radiansFromDegrees(double degrees);

// Near/far planes for a camera at `position`: they enclose the scene's bounding sphere (as the auto-fit camera's;
// an empty box counts as a unit sphere at the origin), so every command-line camera gets the same depth range
// whatever the file's own camera says.
void bracketScene(scene::CameraView& view, const scene::Aabb& bounds);

scene::CameraView lookAtCamera(const LookAtSpec& spec, const scene::Aabb& bounds);
// extraThetaDegrees turns the orbit (turntable frames).
scene::CameraView orbitCamera(const OrbitSpec& spec, const scene::Aabb& bounds, double extraThetaDegrees = 0.0);

// The views `idk render` draws per its options: one (--camera, --orbit, --camera-index, else the scene's default
// camera) or --orbit-frames N. Throws core::CliError on conflicting or malformed options.
std::vector<scene::CameraView> camerasFromCli(const core::CliArgs& args, const scene::Scene& scene);

// --orbit-frames: F.png -> F_000.png (at least 3 digits, more when `count` needs them).
std::filesystem::path turntablePath(const std::filesystem::path& out, size_t index, size_t count);

// position, forward, up, yfov (degrees), znear, zfar: `idk render --json`'s "camera".
nlohmann::json cameraJson(const scene::CameraView& view);

}  // namespace idk::app
