// dispersion_prism.hpp: the dispersion tests' scene (pt_dispersion_test.cpp, screen_transmission_test.cpp): a
// smooth dispersive glass interface through the origin, tilted 40 degrees about +y, in front of a small white
// emitter on the plane z = kPrismEmitterZ, seen by a camera on the +z axis. Each channel sees the emitter where
// Snell's law at its IOR puts it, so the channels' image centroids separate in the order of their IORs.
#pragma once

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstdint>

#include "conformance/quad_scene.hpp"
#include "core/image_file.hpp"

namespace idk::test {

constexpr float kPrismTilt = 0.6981317f;  // 40 degrees about +y
constexpr float kPrismEmitterZ = -1.0f, kPrismEmitterHalf = 0.05f, kPrismCameraZ = 3.0f, kPrismFov = 0.15f;
constexpr float kPrismIor = 1.5f;

inline glm::mat3 prismTilt() {
    return glm::mat3(glm::rotate(glm::mat4(1.0f), kPrismTilt, glm::vec3(0.0f, 1.0f, 0.0f)));
}

// Where a camera ray of direction d meets the emitter's plane after refracting at the tilted interface with IOR n,
// and its refracted direction: double precision, Snell's law in vector form.
inline glm::dvec3 prismRefracted(glm::dvec3 d, double n) {
    const glm::dvec3 normal = glm::dmat3(prismTilt()) * glm::dvec3(0.0, 0.0, 1.0);
    const double cosI = -glm::dot(d, normal);
    const double eta = 1.0 / n;
    return d * eta + normal * (eta * cosI - std::sqrt(1.0 - eta * eta * (1.0 - cosI * cosI)));
}

inline glm::dvec3 prismLanding(glm::dvec3 d, double n) {
    const glm::dvec3 o(0.0, 0.0, kPrismCameraZ);
    const glm::dvec3 normal = glm::dmat3(prismTilt()) * glm::dvec3(0.0, 0.0, 1.0);
    const glm::dvec3 p = o + d * (-glm::dot(o, normal) / glm::dot(d, normal));
    const glm::dvec3 r = prismRefracted(d, n);
    return p + r * ((kPrismEmitterZ - p.z) / r.z);
}

// The glass (quad 0: transmission 1, kPrismIor, `dispersion`, double-sided) and the emitter (quad 1, at the origin:
// the caller sets the glass's thickness and places the emitter).
inline scene::Scene prismQuads(float dispersion) {
    conformance::QuadSpec glass;
    glass.halfSize = 2.0f;
    glass.basis = prismTilt();
    glass.roughness = 0.0f;
    conformance::QuadSpec emitter;
    emitter.halfSize = kPrismEmitterHalf;
    emitter.baseColor = glm::vec3(0.0f);
    emitter.emissive = glm::vec3(1.0f);
    scene::Scene s = conformance::makeQuadScene({glass, emitter});
    scene::Material& g = s.materials[0];
    g.transmission = 1.0f;
    g.ior = kPrismIor;
    g.dispersion = dispersion;
    g.doubleSided = true;
    return s;
}

// The x centroid (pixels) of channel c over a size x size image, weighted by its radiance; -1 for a black channel.
inline double channelCentroidX(const core::ImageRgba32f& img, uint32_t size, int c) {
    double sum = 0.0, weighted = 0.0;
    for (uint32_t y = 0; y < size; ++y)
        for (uint32_t x = 0; x < size; ++x) {
            const double v = img.pixels[4 * (size_t(y) * size + x) + c];
            sum += v;
            weighted += v * (x + 0.5);
        }
    return sum > 0.0 ? weighted / sum : -1.0;
}

}  // namespace idk::test
