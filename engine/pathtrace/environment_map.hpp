// environment_map.hpp: the path tracer's environment: the equirectangular HDR the raster shows (loaded by the
// caller with core::readImage, as render/environment.cpp does) scaled by its intensity, read per texel
// (piecewise constant, so radiance and sampling pdf agree exactly), and the alias table that picks texels in
// proportion to luminance * solid angle (shared/pt_lights.h samples within the texel). One alias table over all
// texels replaces the marginal + conditional CDF pair: the same distribution, sampled in O(1) without a binary
// search. IDKEngine's path tracer reads the sky cubemap only when a ray escapes (reference 2.1).
#pragma once
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "core/image_file.hpp"
#include "shared/pt_types.h"

namespace idk::pathtrace {

struct EnvironmentMap {
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<glm::vec3> radiance;               // width * height, row 0 = up, intensity applied
    std::vector<gpu::GpuPtAliasEntry> aliasTable;  // empty when the environment is black
    double meanLuminance = 0.0;                    // solid-angle weighted mean (for light-selection power)

    bool black() const { return aliasTable.empty(); }
    glm::vec3 lookup(const glm::vec3& direction) const;  // radiance of ptEnvironmentTexel(direction)
};

// Constant environments use a small kConstantWidth x kConstantHeight map.
constexpr uint32_t kConstantWidth = 32, kConstantHeight = 16;

EnvironmentMap buildEnvironmentMap(const core::ImageRgba32f& equirect, float intensity);
EnvironmentMap constantEnvironment(const glm::vec3& radiance);

}  // namespace idk::pathtrace
