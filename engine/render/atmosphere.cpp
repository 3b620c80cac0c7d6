// atmosphere.cpp: Earth parameters, the GPU bake of the single-scattering sky, and its C++ twin. See atmosphere.hpp.
#include "render/atmosphere.hpp"

#include <algorithm>
#include <cmath>

#include "vk/context.hpp"
#include "vk/shader_library.hpp"
#include "vk/transfer.hpp"

namespace idk::render {
namespace {

constexpr double kPi = 3.14159265358979323846;

glm::dvec2 sphereHit(const glm::dvec3& o, const glm::dvec3& d, double r) {
    double lo = glm::length(o);
    double b = glm::dot(o, d), c = (lo - r) * (lo + r);  // as the shader computes it
    double disc = b * b - c;
    if (disc < 0.0) return glm::dvec2(-1.0);
    double s = std::sqrt(disc);
    return {-b - s, -b + s};
}

}  // namespace

glm::vec3 sunDirection(float elevationDegrees, float azimuthDegrees) {
    double e = glm::radians(double(elevationDegrees)), a = glm::radians(double(azimuthDegrees));
    return glm::vec3(float(std::cos(e) * std::sin(a)), float(std::sin(e)), float(-std::cos(e) * std::cos(a)));
}

gpu::GpuAtmosphere earthAtmosphere(glm::vec3 toSun, float sunIntensity, uint32_t width, uint32_t height) {
    gpu::GpuAtmosphere a{};
    a.toSun = glm::normalize(toSun);
    a.sunIntensity = sunIntensity;
    a.rayleighScattering = glm::vec3(5.802e-6f, 13.558e-6f, 33.1e-6f);
    a.rayleighHeight = 8000.0f;
    a.mieScattering = 3.996e-6f;
    a.mieExtinction = 4.44e-6f;
    a.mieHeight = 1200.0f;
    a.mieG = 0.8f;
    a.planetRadius = 6360e3f;
    a.atmosphereRadius = 6460e3f;
    a.viewHeight = 200.0f;
    a.viewSamples = 32;
    a.lightSamples = 8;
    a.width = width;
    a.height = height;
    return a;
}

core::ImageRgba32f bakeAtmosphere(vk::Context& ctx, vk::ShaderLibrary& shaders, const gpu::GpuAtmosphere& params) {
    vk::BufferDesc desc;
    desc.size = size_t(params.width) * params.height * sizeof(glm::vec4);
    desc.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    desc.name = "atmosphere bake";
    desc.category = "environment";
    vk::Buffer out = ctx.createBuffer(desc);
    gpu::GpuAtmosphere push = params;
    push.target = out.address;
    vk::ComputePipelineDesc pipeline;
    pipeline.shader = vk::ShaderId::atmosphere_bake_comp;
    pipeline.pushBytes = sizeof(gpu::GpuAtmosphere);
    pipeline.localSize = {gpu::kAtmosphereGroupSize, gpu::kAtmosphereGroupSize, 1};
    const vk::Pipeline& p = shaders.compute(pipeline);
    ctx.runImmediate([&](VkCommandBuffer cmd) {
        vk::bindPipeline(cmd, p);
        vk::pushConstants(cmd, ctx, push);
        vkCmdDispatch(cmd, vk::groupCount(params.width, gpu::kAtmosphereGroupSize),
                      vk::groupCount(params.height, gpu::kAtmosphereGroupSize), 1);
    });
    core::ImageRgba32f image;
    image.width = params.width;
    image.height = params.height;
    image.pixels.resize(size_t(params.width) * params.height * 4);
    vk::downloadBuffer(ctx, out, image.pixels.data(), desc.size);
    ctx.destroyDeferred(out);
    return image;
}

core::ImageRgba32f bakeSky(vk::Context& ctx, vk::ShaderLibrary& shaders, const AtmosphereSettings& a) {
    const uint32_t width = std::max(a.width, 2u);
    return bakeAtmosphere(ctx, shaders,
                          earthAtmosphere(sunDirection(a.sunElevation, a.sunAzimuth), a.sunIntensity, width, width / 2));
}

glm::dvec3 atmosphereRadiance(const gpu::GpuAtmosphere& a, const glm::dvec3& d, uint32_t viewSteps,
                              uint32_t lightSteps) {
    const glm::dvec3 toSun(a.toSun), betaR(a.rayleighScattering);
    auto density = [&](const glm::dvec3& p) {
        double h = std::max(glm::length(p) - double(a.planetRadius), 0.0);
        return glm::dvec2(std::exp(-h / a.rayleighHeight), std::exp(-h / a.mieHeight));
    };
    const glm::dvec3 o(0.0, double(a.planetRadius) + a.viewHeight, 0.0);
    double tEnd = sphereHit(o, d, a.atmosphereRadius).y;
    glm::dvec2 ground = sphereHit(o, d, a.planetRadius);
    if (ground.x > 0.0) tEnd = ground.x;
    glm::dvec3 rayleigh(0.0), mie(0.0);
    glm::dvec2 depthView(0.0);
    const double len = std::max(tEnd, 0.0);  // midpoint rule in s = sqrt(t / len), as the shader
    for (uint32_t i = 0; i < viewSteps; ++i) {
        double s = (i + 0.5) / viewSteps;
        glm::dvec3 p = o + d * (len * s * s);
        glm::dvec2 rho = density(p) * (len * 2.0 * s / viewSteps);
        depthView += rho * 0.5;
        if (sphereHit(p, toSun, a.planetRadius).x <= 0.0) {
            double ls = sphereHit(p, toSun, a.atmosphereRadius).y;
            glm::dvec2 depthSun(0.0);
            for (uint32_t j = 0; j < lightSteps; ++j) {
                double u = (j + 0.5) / lightSteps;
                depthSun += density(p + toSun * (ls * u * u)) * (ls * 2.0 * u / lightSteps);
            }
            glm::dvec2 total = depthView + depthSun;
            glm::dvec3 t = glm::exp(-(betaR * total.x + glm::dvec3(double(a.mieExtinction) * total.y)));
            rayleigh += t * rho.x;
            mie += t * rho.y;
        }
        depthView += rho * 0.5;
    }
    double mu = glm::dot(d, toSun), g = a.mieG;
    double phaseR = 3.0 / (16.0 * kPi) * (1.0 + mu * mu);
    double phaseM = (1.0 - g * g) / (4.0 * kPi * std::pow(1.0 + g * g - 2.0 * g * mu, 1.5));
    return double(a.sunIntensity) * (rayleigh * betaR * phaseR + mie * double(a.mieScattering) * phaseM);
}

}  // namespace idk::render
