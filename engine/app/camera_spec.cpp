// camera_spec.cpp: parsing and placement of the command-line cameras (camera_spec.hpp).
#include "app/camera_spec.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

namespace idk::app {

namespace {

std::vector<std::string> split(const std::string& text, char separator) {
    std::vector<std::string> parts;
    size_t start = 0;
    for (size_t i = 0; i <= text.size(); ++i) {
        if (i == text.size() || text[i] == separator) {
            parts.push_back(text.substr(start, i - start));
            start = i + 1;
        }
    }
    return parts;
}

double number(const char* flag, const std::string& spec, const std::string& key, const std::string& text) {
    size_t used = 0;
    double v = 0.0;
    try {
        v = std::stod(text, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (text.empty() || used != text.size() || !std::isfinite(v))
        throw core::CliError(std::string(flag) + " '" + spec + "': " + key + " '" + text + "' is not a finite number");
    return v;
}

glm::vec3 vec3(const char* flag, const std::string& spec, const std::string& key, const std::string& text) {
    const std::vector<std::string> parts = split(text, ',');
    if (parts.size() != 3)
        throw core::CliError(std::string(flag) + " '" + spec + "': " + key + " needs X,Y,Z, got '" + text + "'");
    glm::vec3 v;
    for (int i = 0; i < 3; ++i) v[i] = float(number(flag, spec, key, parts[size_t(i)]));
    return v;
}

// key=value items; `allowed` lists the keys. Values of --orbit may hold commas (target=X,Y,Z): an item without
// '=' continues the previous value.
std::map<std::string, std::string> keyValues(const char* flag, const std::string& spec, char separator,
                                             std::initializer_list<const char*> allowed) {
    std::map<std::string, std::string> out;
    std::string last;
    for (const std::string& item : split(spec, separator)) {
        const size_t eq = item.find('=');
        if (eq == std::string::npos) {
            if (last.empty() || separator != ',')
                throw core::CliError(std::string(flag) + " '" + spec + "': '" + item + "' is not KEY=VALUE");
            out[last] += "," + item;
            continue;
        }
        const std::string key = item.substr(0, eq);
        bool known = false;
        std::string list;
        for (const char* a : allowed) {
            known = known || key == a;
            list += (list.empty() ? "" : ", ") + std::string(a);
        }
        if (!known) throw core::CliError(std::string(flag) + " '" + spec + "': unknown key '" + key + "' (keys: " + list + ")");
        if (out.count(key)) throw core::CliError(std::string(flag) + " '" + spec + "': " + key + " given twice");
        out[key] = item.substr(eq + 1);
        last = key;
    }
    return out;
}

double fov(const char* flag, const std::string& spec, const std::map<std::string, std::string>& kv) {
    auto it = kv.find("yfov");
    if (it == kv.end()) return 45.0;
    const double deg = number(flag, spec, "yfov", it->second);
    if (!(deg > 0.0 && deg < 180.0)) throw core::CliError(std::string(flag) + " '" + spec + "': yfov must be in (0, 180) degrees");
    return deg;
}

struct Sphere {
    glm::vec3 centre{0.0f};
    float radius = 1.0f;
};

// The auto-fit camera's bounding sphere (scene::autoFitCamera).
Sphere boundingSphere(const scene::Aabb& bounds) {
    Sphere s;
    if (bounds.empty()) return s;
    s.centre = bounds.centre();
    s.radius = 0.5f * glm::length(bounds.max - bounds.min);
    if (!(s.radius > 0.0f) || !std::isfinite(s.radius)) s.radius = 1.0f;
    return s;
}

}  // namespace

float radiansFromDegrees(double degrees) { return float(degrees * (std::numbers::pi / 180.0)); }

LookAtSpec parseLookAtSpec(const std::string& text) {
    const char* flag = "--camera";
    const auto kv = keyValues(flag, text, ':', {"eye", "target", "up", "yfov"});
    if (!kv.count("eye") || !kv.count("target"))
        throw core::CliError(std::string(flag) + " '" + text + "': give eye=X,Y,Z:target=X,Y,Z[:up=X,Y,Z][:yfov=DEG]");
    LookAtSpec s;
    s.eye = vec3(flag, text, "eye", kv.at("eye"));
    s.target = vec3(flag, text, "target", kv.at("target"));
    if (kv.count("up")) s.up = vec3(flag, text, "up", kv.at("up"));
    s.yfovDegrees = fov(flag, text, kv);
    const glm::vec3 forward = s.target - s.eye;
    if (!(glm::length(forward) > 0.0f)) throw core::CliError(std::string(flag) + " '" + text + "': eye and target coincide");
    const glm::vec3 side = glm::cross(forward, s.up);
    if (!(glm::length(side) > 1e-6f * glm::length(forward) * glm::length(s.up)))
        throw core::CliError(std::string(flag) + " '" + text + "': up is zero or parallel to the view direction");
    return s;
}

OrbitSpec parseOrbitSpec(const std::string& text) {
    const char* flag = "--orbit";
    const auto kv = keyValues(flag, text, ',', {"theta", "phi", "radius", "target", "yfov"});
    if (!kv.count("theta") || !kv.count("phi"))
        throw core::CliError(std::string(flag) + " '" + text + "': give theta=DEG,phi=DEG[,radius=R][,target=X,Y,Z]");
    OrbitSpec s;
    s.thetaDegrees = number(flag, text, "theta", kv.at("theta"));
    s.phiDegrees = number(flag, text, "phi", kv.at("phi"));
    if (s.phiDegrees < 0.0 || s.phiDegrees > 180.0)
        throw core::CliError(std::string(flag) + " '" + text + "': phi is the polar angle from +Y, in [0, 180] degrees");
    if (kv.count("radius")) {
        const double r = number(flag, text, "radius", kv.at("radius"));
        if (!(r > 0.0)) throw core::CliError(std::string(flag) + " '" + text + "': radius must be > 0");
        s.radius = float(r);
    }
    if (kv.count("target")) s.target = vec3(flag, text, "target", kv.at("target"));
    s.yfovDegrees = fov(flag, text, kv);
    return s;
}

void bracketScene(scene::CameraView& view, const scene::Aabb& bounds) {
    const Sphere s = boundingSphere(bounds);
    const float d = glm::length(view.position - s.centre);
    view.znear = std::max(0.5f * (d - s.radius), 1e-3f * std::max(d, s.radius));
    view.zfar = 2.0f * (d + s.radius);
}

scene::CameraView lookAtCamera(const LookAtSpec& spec, const scene::Aabb& bounds) {
    scene::CameraView view;
    view.position = spec.eye;
    view.forward = glm::normalize(spec.target - spec.eye);
    view.up = glm::normalize(spec.up - glm::dot(spec.up, view.forward) * view.forward);
    view.yfov = radiansFromDegrees(spec.yfovDegrees);
    bracketScene(view, bounds);
    return view;
}

scene::CameraView orbitCamera(const OrbitSpec& spec, const scene::Aabb& bounds, double extraThetaDegrees) {
    const Sphere s = boundingSphere(bounds);
    const glm::vec3 target = spec.target.value_or(s.centre);
    const float yfov = radiansFromDegrees(spec.yfovDegrees);
    // Auto-fit: the whole bounding sphere fills the vertical FOV seen from any direction around the target.
    const float radius = spec.radius.value_or(scene::autoFitDistance(glm::length(target - s.centre) + s.radius, yfov));
    scene::CameraView view = scene::orbitCamera(target, radius, radiansFromDegrees(spec.thetaDegrees + extraThetaDegrees),
                                                radiansFromDegrees(spec.phiDegrees));
    view.yfov = yfov;
    bracketScene(view, bounds);
    return view;
}

std::vector<scene::CameraView> camerasFromCli(const core::CliArgs& args, const scene::Scene& scene) {
    const std::optional<std::string> lookAt = args.get("--camera"), orbit = args.get("--orbit"),
                                     index = args.get("--camera-index"), frames = args.get("--orbit-frames");
    if (int(lookAt.has_value()) + int(orbit.has_value()) + int(index.has_value()) > 1)
        throw core::CliError("give at most one of --camera, --orbit and --camera-index");
    if (frames) {
        if (lookAt || index) throw core::CliError("--orbit-frames turns an --orbit camera; it cannot be combined with " +
                                                  std::string(lookAt ? "--camera" : "--camera-index"));
        const double n = core::parseNumber("--orbit-frames", *frames);
        if (!(n >= 1 && n <= 10000 && n == std::floor(n)))
            throw core::CliError("--orbit-frames '" + *frames + "': give a whole number of frames in 1..10000");
        const OrbitSpec spec = orbit ? parseOrbitSpec(*orbit) : OrbitSpec{};
        std::vector<scene::CameraView> views;
        for (uint32_t k = 0; k < uint32_t(n); ++k) views.push_back(orbitCamera(spec, scene.bounds, 360.0 * k / n));
        return views;
    }
    if (lookAt) return {lookAtCamera(parseLookAtSpec(*lookAt), scene.bounds)};
    if (orbit) return {orbitCamera(parseOrbitSpec(*orbit), scene.bounds)};
    if (index) {
        const double n = core::parseNumber("--camera-index", *index);
        if (!(n >= 0 && n == std::floor(n) && n < double(scene.cameras.size())))
            throw core::CliError("--camera-index '" + *index + "': the scene has " + std::to_string(scene.cameras.size()) +
                                 " camera(s), numbered from 0");
        return {scene::cameraView(scene.cameras[size_t(n)])};
    }
    return {scene::defaultCamera(scene)};
}

std::filesystem::path turntablePath(const std::filesystem::path& out, size_t index, size_t count) {
    const size_t digits = std::max<size_t>(3, std::to_string(count - 1).size());
    std::string number = std::to_string(index);
    number.insert(0, digits - number.size(), '0');
    return out.parent_path() / (out.stem().string() + "_" + number + out.extension().string());
}

nlohmann::json cameraJson(const scene::CameraView& v) {
    auto vec = [](const glm::vec3& a) { return nlohmann::json::array({a.x, a.y, a.z}); };
    return {{"position", vec(v.position)}, {"forward", vec(v.forward)}, {"up", vec(v.up)},
            {"yfovDegrees", double(v.yfov) * 180.0 / std::numbers::pi}, {"znear", v.znear}, {"zfar", v.zfar},
            {"orthographic", v.type == scene::CameraType::Orthographic}};
}

}  // namespace idk::app
