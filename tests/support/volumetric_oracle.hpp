// volumetric_oracle.hpp: the CPU ray march that volumetric lighting (frame/volumetrics_feature.hpp) is checked against,
// shared by tests/gpu/volumetrics and the volumetrics benchmark rows (bench/lights_bench.cpp). Scene: a floor, a box
// and a point light above it (its shadow hides part of the medium), no environment light. Per pixel the march
// predicts frame_off * T + L along the pixel's centre ray: T = exp(-sigma d) to the surface, L = the sum over
// `steps` midpoint steps of T(t) sigma I / r^2 HG(cos) V, V = the CPU ray test (placed_quads castRay) from the step
// to the light through the box. Test support, no IDKEngine counterpart.
#pragma once
#include <glm/glm.hpp>

#include <vector>

#include "core/image_file.hpp"
#include "render/render_settings.hpp"
#include "scene/camera.hpp"
#include "support/placed_quads.hpp"

namespace idk::test {

struct VolumetricCase {
    std::vector<PlacedQuad> quads;  // floor, then the box's faces
    scene::Scene scene;
    glm::dvec3 light{0.0};
    double intensity = 0.0;
    scene::CameraView camera;
    float density = 0.3f, anisotropy = 0.3f;
};
VolumetricCase volumetricCase();

// The case's settings: shadowTestSettings(512) without environment light, the medium on or off at 1/scale.
render::RenderSettings volumetricSettings(const VolumetricCase& c, bool volumetrics, uint32_t scale);

struct VolumetricPrediction {
    std::vector<glm::dvec3> predicted;      // with the medium's shadows
    std::vector<glm::dvec3> unshadowed;     // V = 1 everywhere
    std::vector<glm::dvec3> withoutMedium;  // frame_off itself
};
// `off`: the size x size frame with volumetrics off. Throws std::runtime_error if a pixel misses every quad.
VolumetricPrediction predictVolumetrics(const VolumetricCase& c, const core::ImageRgba32f& off, uint32_t size,
                                        int steps = 512);

struct RelativeErrors {
    double mean = 0.0, p95 = 0.0;  // of |frame - predicted| / max(|predicted|, 1e-3) (RGB lengths) per pixel
};
RelativeErrors relativeErrors(const core::ImageRgba32f& frame, const std::vector<glm::dvec3>& predicted);

}  // namespace idk::test
