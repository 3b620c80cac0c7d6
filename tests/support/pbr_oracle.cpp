// pbr_oracle.cpp: the C++ evaluation of the deferred renderer's BRDF, lights and AgX (see pbr_oracle.hpp); the
// formulas are the glTF 2.0 spec's Appendix B and the KHR_lights_punctual README, written independently of the
// GLSL so a transcription error in either shows up as a test failure.
#include "support/pbr_oracle.hpp"

#include <algorithm>
#include <cmath>

#include "support/plastic_weight.hpp"

namespace idk::test {
namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kMinRoughness = 0.045;
}  // namespace

glm::dvec3 brdfCosine(const glm::dvec3& baseColor, double metallic, double perceptualRoughness, const glm::dvec3& n,
                      const glm::dvec3& v, const glm::dvec3& l) {
    double NdotL = glm::dot(n, l);
    if (NdotL <= 0.0) return glm::dvec3(0.0);
    double NdotV = std::max(glm::dot(n, v), 1e-4);
    glm::dvec3 h = glm::normalize(l + v);
    double NdotH = std::max(glm::dot(n, h), 0.0), VdotH = std::max(glm::dot(v, h), 0.0);
    double r = std::clamp(perceptualRoughness, kMinRoughness, 1.0);
    double alpha = r * r, a2 = alpha * alpha;
    // D: Trowbridge-Reitz / GGX
    double d = NdotH * NdotH * (a2 - 1.0) + 1.0;
    double D = a2 / (kPi * d * d);
    // V: Smith joint (height-correlated) GGX, = G / (4 |N.L| |N.V|)
    double V =
        0.5 / (NdotL * std::sqrt(NdotV * NdotV * (1.0 - a2) + a2) + NdotV * std::sqrt(NdotL * NdotL * (1.0 - a2) + a2));
    // F: the dielectric's exact unpolarised Fresnel of IOR 1.5 mixed with the metal's Schlick (f0 = baseColor)
    double sinT2 = (1.0 - VdotH * VdotH) / (1.5 * 1.5), cosT = std::sqrt(1.0 - sinT2);
    double rs = (VdotH - 1.5 * cosT) / (VdotH + 1.5 * cosT), rp = (1.5 * VdotH - cosT) / (1.5 * VdotH + cosT);
    glm::dvec3 F = glm::mix(glm::dvec3(0.5 * (rs * rs + rp * rp)),
                            baseColor + (1.0 - baseColor) * std::pow(1.0 - VdotH, 5.0), metallic);
    // Diffuse: the albedo-scaled weight of the path tracers' plastic (IOR 1.5: f0 0.04), written out by hand in
    // plastic_weight.hpp from the committed albedo tables; none for a full metal (the GLSL skips the lookups).
    double w = metallic < 1.0 ? plasticDiffuseWeight(PlasticSpec{float(r), 1.5}, NdotV, NdotL) : 0.0;
    glm::dvec3 diffuse = w * baseColor * (1.0 - metallic) / kPi;
    return (diffuse + F * D * V) * NdotL;
}

glm::dvec3 lightIncidence(const gpu::GpuLight& light, const glm::dvec3& p, glm::dvec3& l) {
    glm::dvec3 intensity(light.intensity);
    if (light.type == gpu::kLightDirectional) {
        l = -glm::dvec3(light.direction);
        return intensity;
    }
    glm::dvec3 toLight = glm::dvec3(light.position) - p;
    double dist = glm::length(toLight);
    l = toLight / dist;
    double attenuation = 1.0 / (dist * dist);
    if (light.range > 0.0f) attenuation *= std::pow(std::clamp(1.0 - std::pow(dist / light.range, 4.0), 0.0, 1.0), 2.0);
    if (light.type == gpu::kLightSpot) {
        double cd = glm::dot(glm::dvec3(light.direction), -l);
        double a = std::clamp(cd * light.spotScale + light.spotOffset, 0.0, 1.0);
        attenuation *= a * a;
    }
    return intensity * attenuation;
}

glm::dvec3 agx(const glm::dvec3& linear) {
    // Sobotka's inset matrix (rows: output channels) and log2 range; Wrensch's 6th-order contrast fit.
    const glm::dmat3 inset = glm::transpose(glm::dmat3(0.842479062253094, 0.0784335999999992, 0.0792237451477643,
                                                       0.0423282422610123, 0.878468636469772, 0.0791661274605434,
                                                       0.0423756549057051, 0.0784336, 0.879142973793104));
    const double minEv = -12.47393, maxEv = 4.026069;
    glm::dvec3 v = inset * glm::max(linear, glm::dvec3(0.0));
    for (int c = 0; c < 3; ++c) {
        double x = (std::clamp(std::log2(std::max(v[c], 1e-10)), minEv, maxEv) - minEv) / (maxEv - minEv);
        v[c] = 15.5 * std::pow(x, 6) - 40.14 * std::pow(x, 5) + 31.96 * std::pow(x, 4) - 6.868 * std::pow(x, 3) +
               0.4298 * x * x + 0.1191 * x - 0.00232;
    }
    v = glm::inverse(inset) * v;
    for (int c = 0; c < 3; ++c) v[c] = std::pow(std::clamp(v[c], 0.0, 1.0), 2.2);
    return v;
}

double srgbEncode(double c) {
    c = std::clamp(c, 0.0, 1.0);
    return c <= 0.0031308 ? c * 12.92 : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
}

double quantizeSrgb8(double linear) {
    double code = std::round(srgbEncode(linear) * 255.0) / 255.0;
    return code <= 0.04045 ? code / 12.92 : std::pow((code + 0.055) / 1.055, 2.4);
}

double quantizeUnorm8(double value) { return std::round(std::clamp(value, 0.0, 1.0) * 255.0) / 255.0; }

}  // namespace idk::test
