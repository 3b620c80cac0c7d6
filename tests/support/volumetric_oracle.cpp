// volumetric_oracle.cpp: the CPU ray march of volumetric lighting (see volumetric_oracle.hpp).
#include "support/volumetric_oracle.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "support/shadow_oracle.hpp"

namespace idk::test {
namespace {

double hg(double c, double g) { return (1 - g * g) / (4 * 3.14159265358979 * std::pow(1 + g * g - 2 * g * c, 1.5)); }

}  // namespace

VolumetricCase volumetricCase() {
    VolumetricCase c;
    c.quads = {floorQuad(8.0f)};
    for (const PlacedQuad& f : boxFaces({0.3f, 0.0f, 0.0f}, {0.5f, 0.5f, 0.5f}, glm::vec3(0.6f))) c.quads.push_back(f);
    c.scene = makePlacedQuadScene(c.quads);
    c.light = glm::dvec3(-0.6, 1.6, -0.2);
    c.intensity = 10.0;
    c.scene.lights.push_back(pointLight(glm::vec3(c.light), float(c.intensity)));
    c.camera = shadowTestCamera({1.5f, 3.2f, 3.6f}, {0.0f, 0.0f, 0.0f});
    return c;
}

render::RenderSettings volumetricSettings(const VolumetricCase& c, bool volumetrics, uint32_t scale) {
    render::RenderSettings settings = shadowTestSettings(512);
    settings.environmentIntensity = 0.0f;
    settings.volumetrics.enabled = volumetrics;
    settings.volumetrics.density = c.density;
    settings.volumetrics.anisotropy = c.anisotropy;
    settings.volumetrics.scale = scale;
    return settings;
}

VolumetricPrediction predictVolumetrics(const VolumetricCase& c, const core::ImageRgba32f& off, uint32_t size,
                                        int steps) {
    const double density = c.density, g = c.anisotropy;
    const glm::dmat4 inv =
        glm::inverse(glm::dmat4(scene::projectionMatrix(c.camera, 1.0f) * scene::viewMatrix(c.camera)));
    const size_t pixels = size_t(size) * size;
    VolumetricPrediction p{std::vector<glm::dvec3>(pixels), std::vector<glm::dvec3>(pixels),
                           std::vector<glm::dvec3>(pixels)};
    const glm::dvec3 eye(c.camera.position);
    for (uint32_t py = 0; py < size; ++py) {
        for (uint32_t px = 0; px < size; ++px) {
            glm::dvec2 ndc((px + 0.5) / size * 2.0 - 1.0, (py + 0.5) / size * 2.0 - 1.0);
            glm::dvec4 a = inv * glm::dvec4(ndc, 0.0, 1.0), b = inv * glm::dvec4(ndc, 0.5, 1.0);
            glm::dvec3 o = glm::dvec3(a) / a.w, d = glm::normalize(glm::dvec3(b) / b.w - o);
            const auto hit = castRay(c.quads, o, d, 0.0, 1e9);
            if (!hit) throw std::runtime_error("volumetric oracle: a pixel sees neither the floor nor the box");
            const double len = glm::length(o + hit->t * d - eye);
            glm::dvec3 lit(0.0), all(0.0);
            for (int k = 0; k < steps; ++k) {
                const double t = (k + 0.5) * len / steps;
                const glm::dvec3 x = eye + d * t, toLight = c.light - x;
                const double r2 = glm::dot(toLight, toLight);
                const glm::dvec3 l = toLight / std::sqrt(r2);
                const double add =
                    density * std::exp(-density * t) * (len / steps) * c.intensity / r2 * hg(glm::dot(l, d), g);
                all += glm::dvec3(add);
                if (!occludedFrom(c.quads, x, c.light)) lit += glm::dvec3(add);
            }
            const size_t i = size_t(py) * size + px;
            const glm::dvec3 surface(off.pixels[4 * i], off.pixels[4 * i + 1], off.pixels[4 * i + 2]);
            p.predicted[i] = surface * std::exp(-density * len) + lit;
            p.withoutMedium[i] = surface;
            p.unshadowed[i] = surface * std::exp(-density * len) + all;
        }
    }
    return p;
}

RelativeErrors relativeErrors(const core::ImageRgba32f& frame, const std::vector<glm::dvec3>& predicted) {
    std::vector<double> rel;
    for (size_t i = 0; i < predicted.size(); ++i) {
        glm::dvec3 v(frame.pixels[4 * i], frame.pixels[4 * i + 1], frame.pixels[4 * i + 2]);
        rel.push_back(glm::length(v - predicted[i]) / std::max(glm::length(predicted[i]), 1e-3));
    }
    RelativeErrors e;
    for (double r : rel) e.mean += r / double(rel.size());
    std::sort(rel.begin(), rel.end());
    e.p95 = rel[rel.size() * 95 / 100];
    return e;
}

}  // namespace idk::test
