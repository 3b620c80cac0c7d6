// lambert_oracle.hpp: a CPU ray caster that computes what the Lambert raster pass must produce: for each pixel
// centre, the nearest triangle along the camera ray (watertight enough for a reference: Moller-Trumbore in
// double precision), shaded with the same Lambert + emission + ambient model as lambert.frag.glsl.
#pragma once
#include <glm/glm.hpp>

#include "core/image_file.hpp"
#include "render/lambert_scene.hpp"

namespace idk::test {

core::ImageRgba32f renderLambertReference(const render::LambertSceneData& scene, const glm::mat4& viewProjection,
                                          glm::vec3 ambient, uint32_t width, uint32_t height);

struct ImageComparison {
    double meanAbsError = 0.0;         // over all channels of all pixels
    double badPixelFraction = 0.0;     // pixels whose largest channel error exceeds the tolerance
    double maxError = 0.0;
};

// Per-channel error |a - b| / max(1, |b|) (relative above 1, absolute below).
ImageComparison compareImages(const core::ImageRgba32f& actual, const core::ImageRgba32f& expected, float tolerance);

// Writes actual, expected and a 10x amplified difference next to each other (EXR) for failure analysis.
void writeDiffImage(const std::string& path, const core::ImageRgba32f& actual, const core::ImageRgba32f& expected);

}  // namespace idk::test
