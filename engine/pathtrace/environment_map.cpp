// environment_map.cpp: texel radiance and the luminance * solid-angle alias table of the environment.
#include "pathtrace/environment_map.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "pathtrace/alias_table.hpp"
#include "shared/pt_sampling.h"

namespace idk::pathtrace {

namespace {

constexpr double kPi = 3.14159265358979323846;

void buildTables(EnvironmentMap& env) {
    std::vector<double> weights(size_t(env.width) * env.height);
    double total = 0.0, solidAngleSum = 0.0;
    for (uint32_t y = 0; y < env.height; ++y) {
        // Exact solid angle of a texel row: 2 pi / width * (cos t0 - cos t1).
        const double t0 = kPi * y / env.height, t1 = kPi * (y + 1) / env.height;
        const double solidAngle = 2.0 * kPi / env.width * (std::cos(t0) - std::cos(t1));
        for (uint32_t x = 0; x < env.width; ++x) {
            const size_t i = size_t(y) * env.width + x;
            const glm::vec3 c = env.radiance[i];
            const double lum = std::max(0.0, 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z);
            // The sampler spreads each texel uniformly over its (u, v) rectangle, whose density in solid angle is
            // proportional to 1 / sin(theta): weighting by the texel's solid angle makes the pdf follow radiance.
            weights[i] = std::isfinite(lum) ? lum * solidAngle : 0.0;
            total += weights[i];
            solidAngleSum += solidAngle;
        }
    }
    env.meanLuminance = solidAngleSum > 0.0 ? total / solidAngleSum : 0.0;
    env.aliasTable = buildAliasTable(weights);
}

}  // namespace

glm::vec3 EnvironmentMap::lookup(const glm::vec3& direction) const {
    if (width == 0 || height == 0) return glm::vec3(0.0f);
    return radiance[gpu::ptEnvironmentTexel(direction, width, height)];
}

EnvironmentMap buildEnvironmentMap(const core::ImageRgba32f& equirect, float intensity) {
    if (equirect.width == 0 || equirect.height == 0 ||
        equirect.pixels.size() != size_t(equirect.width) * equirect.height * 4)
        throw std::invalid_argument("environment image is empty or its pixel count does not match its size");
    EnvironmentMap env;
    env.width = equirect.width;
    env.height = equirect.height;
    env.radiance.resize(size_t(env.width) * env.height);
    const float scale = std::isfinite(intensity) && intensity > 0.0f ? intensity : 0.0f;
    for (size_t i = 0; i < env.radiance.size(); ++i) {
        glm::vec3 c(equirect.pixels[4 * i], equirect.pixels[4 * i + 1], equirect.pixels[4 * i + 2]);
        for (int k = 0; k < 3; ++k) c[k] = std::isfinite(c[k]) && c[k] > 0.0f ? c[k] * scale : 0.0f;
        env.radiance[i] = c;
    }
    buildTables(env);
    return env;
}

EnvironmentMap constantEnvironment(const glm::vec3& radiance) {
    EnvironmentMap env;
    env.width = kConstantWidth;
    env.height = kConstantHeight;
    glm::vec3 c = radiance;
    for (int k = 0; k < 3; ++k) c[k] = std::isfinite(c[k]) && c[k] > 0.0f ? c[k] : 0.0f;
    env.radiance.assign(size_t(env.width) * env.height, c);
    buildTables(env);
    return env;
}

}  // namespace idk::pathtrace
