// lambert_oracle.cpp: CPU reference for the Lambert raster pass, and image comparison helpers.
#include "support/lambert_oracle.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace idk::test {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Moller-Trumbore in double precision; returns t and barycentrics (u, v) of the hit, or t < 0.
bool intersect(const glm::dvec3& origin, const glm::dvec3& dir, const glm::dvec3& a, const glm::dvec3& b,
               const glm::dvec3& c, double& t, double& u, double& v) {
    glm::dvec3 e1 = b - a, e2 = c - a;
    glm::dvec3 p = glm::cross(dir, e2);
    double det = glm::dot(e1, p);
    if (std::abs(det) < 1e-14) return false;
    double inv = 1.0 / det;
    glm::dvec3 s = origin - a;
    u = glm::dot(s, p) * inv;
    if (u < 0.0 || u > 1.0) return false;
    glm::dvec3 q = glm::cross(s, e1);
    v = glm::dot(dir, q) * inv;
    if (v < 0.0 || u + v > 1.0) return false;
    t = glm::dot(e2, q) * inv;
    return t > 0.0;
}

}  // namespace

core::ImageRgba32f renderLambertReference(const render::LambertSceneData& scene, const glm::mat4& viewProjection,
                                          glm::vec3 ambient, uint32_t width, uint32_t height) {
    core::ImageRgba32f img{width, height, std::vector<float>(size_t(width) * height * 4, 0.0f)};
    glm::dmat4 inv = glm::inverse(glm::dmat4(viewProjection));
    for (uint32_t py = 0; py < height; ++py) {
        for (uint32_t px = 0; px < width; ++px) {
            // Pixel centre in Vulkan NDC (row 0 is y = -1, the top).
            double x = (px + 0.5) / width * 2.0 - 1.0, y = (py + 0.5) / height * 2.0 - 1.0;
            glm::dvec4 nearH = inv * glm::dvec4(x, y, 0.0, 1.0), farH = inv * glm::dvec4(x, y, 0.5, 1.0);
            glm::dvec3 origin = glm::dvec3(nearH) / nearH.w;
            glm::dvec3 dir = glm::normalize(glm::dvec3(farH) / farH.w - origin);
            double bestT = std::numeric_limits<double>::max(), bu = 0, bv = 0;
            size_t best = SIZE_MAX;
            for (size_t tri = 0; tri + 2 < scene.vertices.size(); tri += 3) {
                double t, u, v;
                if (intersect(origin, dir, glm::dvec3(scene.vertices[tri].position),
                              glm::dvec3(scene.vertices[tri + 1].position), glm::dvec3(scene.vertices[tri + 2].position),
                              t, u, v) &&
                    t < bestT) {
                    bestT = t;
                    bu = u;
                    bv = v;
                    best = tri;
                }
            }
            float* out = &img.pixels[(size_t(py) * width + px) * 4];
            out[3] = 1.0f;
            if (best == SIZE_MAX) continue;
            const auto& va = scene.vertices[best];
            const auto& vb = scene.vertices[best + 1];
            const auto& vc = scene.vertices[best + 2];
            glm::dvec3 n = glm::normalize((1 - bu - bv) * glm::dvec3(va.normal) + bu * glm::dvec3(vb.normal) +
                                          bv * glm::dvec3(vc.normal));
            if (glm::dot(n, dir) > 0.0) n = -n;  // lit from the side the camera sees
            glm::dvec3 p = origin + bestT * dir;
            const auto& m = scene.materials[va.material];
            glm::dvec3 albedo(m.albedo);
            glm::dvec3 radiance = glm::dvec3(m.emissive) + albedo * glm::dvec3(ambient);
            for (const auto& light : scene.lights) {
                glm::dvec3 toLight = glm::dvec3(light.position) - p;
                double d2 = std::max(glm::dot(toLight, toLight), 1e-8);
                double cosTheta = std::max(glm::dot(n, toLight / std::sqrt(d2)), 0.0);
                radiance += albedo / kPi * glm::dvec3(light.intensity) * cosTheta / d2;
            }
            out[0] = float(radiance.x);
            out[1] = float(radiance.y);
            out[2] = float(radiance.z);
        }
    }
    return img;
}

ImageComparison compareImages(const core::ImageRgba32f& actual, const core::ImageRgba32f& expected, float tolerance) {
    ImageComparison c;
    size_t pixels = size_t(expected.width) * expected.height;
    if (actual.width != expected.width || actual.height != expected.height) {
        c.badPixelFraction = 1.0;
        c.maxError = std::numeric_limits<double>::infinity();
        return c;
    }
    size_t bad = 0;
    double sum = 0.0;
    for (size_t p = 0; p < pixels; ++p) {
        double worst = 0.0;
        for (int ch = 0; ch < 4; ++ch) {
            double e = actual.pixels[p * 4 + ch], a = expected.pixels[p * 4 + ch];
            double err = std::abs(e - a) / std::max(1.0, std::abs(a));
            if (!std::isfinite(e)) err = std::numeric_limits<double>::infinity();
            sum += err;
            worst = std::max(worst, err);
        }
        c.maxError = std::max(c.maxError, worst);
        if (worst > tolerance) ++bad;
    }
    c.meanAbsError = sum / double(pixels * 4);
    c.badPixelFraction = double(bad) / double(pixels);
    return c;
}

void writeDiffImage(const std::string& path, const core::ImageRgba32f& actual, const core::ImageRgba32f& expected) {
    uint32_t w = expected.width, h = expected.height;
    core::ImageRgba32f out{w * 3, h, std::vector<float>(size_t(w) * 3 * h * 4, 1.0f)};
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) {
                size_t src = (size_t(y) * w + x) * 4 + c;
                float a = src < actual.pixels.size() ? actual.pixels[src] : 0.0f;
                float e = expected.pixels[src];
                out.pixels[(size_t(y) * w * 3 + x) * 4 + c] = a;
                out.pixels[(size_t(y) * w * 3 + x + w) * 4 + c] = e;
                out.pixels[(size_t(y) * w * 3 + x + 2 * w) * 4 + c] = 10.0f * std::abs(a - e);
            }
    core::writeImage(path, out);
}

}  // namespace idk::test
