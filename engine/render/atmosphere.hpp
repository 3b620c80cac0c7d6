// atmosphere.hpp: the atmospheric-scattering sky (`--sky atmosphere`): single-scattering Rayleigh + Mie radiance
// baked on the GPU into an equirectangular map (atmosphere/bake.comp.glsl) whenever the sun moves, then used as
// the frame's environment (sky, SH ambient, specular; frame/environment_feature.cpp). atmosphereRadiance is the
// C++ twin of the shader's integral in double precision (the conformance test's oracle at fine steps).
// Ports IDKEngine's AtmosphericScatterer (reference: atmosphere).
#pragma once
#include <glm/glm.hpp>

#include <cstdint>

#include "core/image_file.hpp"
#include "shared/atmosphere_types.h"

namespace idk::vk {
class Context;
class ShaderLibrary;
}  // namespace idk::vk

namespace idk::render {

struct AtmosphereSettings {
    bool enabled = false;        // `--sky atmosphere` (else the HDR environment file)
    float sunElevation = 30.0f;  // degrees above the horizon
    float sunAzimuth = 0.0f;     // degrees, 0 = towards -Z, 90 = towards +X
    float sunIntensity = 20.0f;  // sun irradiance scale of the baked radiance
    uint32_t width = 256;        // equirectangular map size (height = width / 2)
};

// Unit direction towards the sun.
glm::vec3 sunDirection(float elevationDegrees, float azimuthDegrees);

// Earth's atmosphere (Bruneton & Neyret 2008 coefficients; Mie g = 0.8) seen from 200 m, quadrature 32 x 8.
gpu::GpuAtmosphere earthAtmosphere(glm::vec3 toSun, float sunIntensity, uint32_t width, uint32_t height);

// The GPU bake (one immediate submission, waits) read back as an RGBA32F image (row 0 = up).
core::ImageRgba32f bakeAtmosphere(vk::Context& ctx, vk::ShaderLibrary& shaders, const gpu::GpuAtmosphere& params);

// The sky `settings` ask for, baked (bakeAtmosphere of earthAtmosphere at settings.width x width / 2): the map the
// raster's environment and the path tracer's environment (`idk render --pathtrace --sky atmosphere`) share.
core::ImageRgba32f bakeSky(vk::Context& ctx, vk::ShaderLibrary& shaders, const AtmosphereSettings& settings);

// Radiance along unit `direction` with viewSteps x lightSteps midpoint quadrature (the shader's scheme).
glm::dvec3 atmosphereRadiance(const gpu::GpuAtmosphere& params, const glm::dvec3& direction, uint32_t viewSteps,
                              uint32_t lightSteps);

}  // namespace idk::render
