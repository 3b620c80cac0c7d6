// environment.hpp: the HDR environment of the deferred renderer: an equirectangular radiance map (OpenImageIO)
// with a box-filtered mip chain (the blurred specular lookup, the sky background) and its SH9 diffuse
// irradiance projected on the CPU (Ramamoorthi & Hanrahan 2001, "An Efficient Representation for Irradiance
// Environment Maps"). IDKEngine's rasterizer has a skybox cubemap but no IBL (reference 2.17, 2.19, section 5).
#pragma once
#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/image_file.hpp"
#include "vk/bindless.hpp"
#include "vk/resources.hpp"

namespace idk::vk {
class Context;
}

namespace idk::render {

using ShIrradiance = std::array<glm::vec3, 9>;  // layout of GpuFrame::irradianceSh (shared/deferred_types.h)

// Mapping shared with include/environment.glsl: u = 0.5 looks down -Z, v = 0 is +Y.
glm::vec3 equirectDirection(glm::vec2 uv);
glm::vec2 equirectUv(const glm::vec3& direction);

// Projects radiance onto the 9 real SH basis functions (solid-angle weighted per texel) and folds in the
// clamped-cosine convolution (A0 = pi, A1 = 2pi/3, A2 = pi/4) and the basis constants, so that
// evaluateIrradianceSh(sh, n) = E(n), the irradiance at a surface facing n. A constant radiance L gives
// E = pi L for every n.
ShIrradiance projectIrradianceSh(const core::ImageRgba32f& equirect);
glm::vec3 evaluateIrradianceSh(const ShIrradiance& sh, const glm::vec3& n);  // C++ twin of shIrradiance()

// Mip chain of an equirectangular image: level k+1 averages 2x2 texels of level k (1 in a dimension already 1).
std::vector<core::ImageRgba32f> buildMipChain(core::ImageRgba32f level0);

// The default environment: ../shared/environments/snow_field_puresky_1k.hdr next to the repository (from the
// shader source folder baked in at build time), or $IDK_ENVIRONMENT when set.
std::filesystem::path defaultEnvironmentPath();

// The environment on the GPU: RGBA16F equirectangular texture with all mips, registered as bindless.
struct GpuEnvironment {
    vk::Image image;
    vk::SampledIndex texture;
    vk::SamplerIndex sampler;
    ShIrradiance irradianceSh{};  // for intensity 1
    float maxLod = 0.0f;
    float width = 1.0f, height = 1.0f;
};

// Loads `file` (any format OpenImageIO reads; throws naming the file). An empty path gives a constant
// environment of radiance `constant` (a 1x1 texture; E = pi * constant).
GpuEnvironment createEnvironment(vk::Context& ctx, const std::filesystem::path& file,
                                 glm::vec3 constant = glm::vec3(0.5f));
// The same from an equirectangular image already in memory (the atmosphere's bake, render/atmosphere.hpp).
GpuEnvironment createEnvironment(vk::Context& ctx, core::ImageRgba32f level0, const std::string& name);
void destroyEnvironment(vk::Context& ctx, GpuEnvironment& env);

}  // namespace idk::render
