// shadow_oracle.cpp: frames and CPU visibility oracle of the shadow tests. See shadow_oracle.hpp.
#include "support/shadow_oracle.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "render/renderer.hpp"

namespace idk::test {
namespace {

core::ImageRgba32f renderOne(vk::Context& ctx, vk::ShaderLibrary& shaders, const scene::Scene& scene,
                             const scene::CameraView& camera, render::RenderSettings settings, uint32_t maxLights) {
    settings.pointShadows.maxLights = maxLights;
    render::Renderer renderer(ctx, shaders, settings);
    renderer.setScene(scene);
    render::FrameResult frame = renderer.renderOffscreen(camera, kShadowFrameSize, kShadowFrameSize);
    const bool casts = maxLights > 0 && scene.lights[0].intensity > 0.0f && !settings.lightShadows.rayTraced;
    EXPECT_EQ(renderer.pointShadowMaps() != nullptr || renderer.lightShadowMaps() != nullptr, casts)
        << "maps exist exactly while a light casts a shadow through them";
    return frame.image;
}

}  // namespace

render::RenderSettings shadowTestSettings(uint32_t resolution) {
    render::RenderSettings settings;
    settings.output = render::OutputKind::Hdr;
    settings.environment = std::filesystem::path();  // constant radiance 0.5
    settings.environmentIntensity = 0.3f;
    settings.pointShadows.resolution = resolution;
    settings.lightShadows.resolution = resolution;
    return settings;
}

ShadowFrames renderShadowFrames(vk::Context& ctx, vk::ShaderLibrary& shaders, scene::Scene scene,
                                const scene::CameraView& c, const std::string& name,
                                const render::RenderSettings& settings) {
    ShadowFrames f;
    f.full = renderOne(ctx, shaders, scene, c, settings, 8);
    f.unshadowed = renderOne(ctx, shaders, scene, c, settings, 0);
    scene.lights[0].intensity = 0.0f;
    f.ambient = renderOne(ctx, shaders, scene, c, settings, 8);
    std::filesystem::path dir = std::filesystem::path(IDK_BINARY_DIR) / "shadow_oracle_test";
    std::filesystem::create_directories(dir);
    core::writeImage((dir / (name + "_full.exr")).string(), f.full);
    core::writeImage((dir / (name + "_unshadowed.exr")).string(), f.unshadowed);
    core::writeImage((dir / (name + "_ambient.exr")).string(), f.ambient);
    return f;
}

scene::CameraView shadowTestCamera(glm::vec3 eye, glm::vec3 target) {
    scene::CameraView c;
    c.position = eye;
    c.forward = glm::normalize(target - eye);
    c.up = glm::normalize(glm::cross(glm::cross(c.forward, glm::vec3(0, 1, 0)), c.forward));
    c.znear = 0.1f;
    c.zfar = 100.0f;
    return c;
}

double rgbSum(const core::ImageRgba32f& img, size_t pixel) {
    const float* p = &img.pixels[pixel * 4];
    return double(p[0]) + p[1] + p[2];
}

PrimaryHits primaryHits(const std::vector<PlacedQuad>& quads, const scene::CameraView& camera) {
    constexpr uint32_t n = kShadowFrameSize;
    glm::dmat4 inv = glm::inverse(glm::dmat4(scene::projectionMatrix(camera, 1.0f) * scene::viewMatrix(camera)));
    PrimaryHits h{std::vector<int>(n * n, -1), std::vector<glm::dvec3>(n * n)};
    for (uint32_t py = 0; py < n; ++py) {
        for (uint32_t px = 0; px < n; ++px) {
            glm::dvec2 ndc((px + 0.5) / n * 2.0 - 1.0, (py + 0.5) / n * 2.0 - 1.0);
            glm::dvec4 a = inv * glm::dvec4(ndc, 0.0, 1.0), b = inv * glm::dvec4(ndc, 0.5, 1.0);
            glm::dvec3 o = glm::dvec3(a) / a.w, d = glm::normalize(glm::dvec3(b) / b.w - o);
            if (auto hit = castRay(quads, o, d, 0.0, 1e9)) {
                h.quad[py * n + px] = int(hit->quad);
                h.point[py * n + px] = o + hit->t * d;
            }
        }
    }
    return h;
}

bool interiorPixel(const PrimaryHits& h, uint32_t px, uint32_t py) {
    constexpr uint32_t n = kShadowFrameSize;
    if (px == 0 || py == 0 || px + 1 >= n || py + 1 >= n) return false;
    int q = h.quad[py * n + px];
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
            if (h.quad[(py + dy) * n + px + dx] != q) return false;
    return true;
}

bool occludedFrom(const std::vector<PlacedQuad>& quads, const glm::dvec3& p, const glm::dvec3& target) {
    glm::dvec3 d = target - p;
    double len = glm::length(d);
    return castRay(quads, p, d / len, 1e-6, len - 1e-6).has_value();
}

double sphereVisibility(const std::vector<PlacedQuad>& occluders, const glm::dvec3& p, const glm::dvec3& c, double r,
                        int n) {
    const glm::dvec3 toCentre = c - p;
    const double d = glm::length(toCentre);
    const glm::dvec3 w = toCentre / d;
    const glm::dvec3 u = glm::normalize(std::abs(w.x) > 0.9 ? glm::cross(w, glm::dvec3(0, 1, 0))
                                                            : glm::cross(w, glm::dvec3(1, 0, 0)));
    const glm::dvec3 v = glm::cross(w, u);
    const double cosMax = std::sqrt(1.0 - (r / d) * (r / d));
    int visible = 0;
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
            const double cosT = 1.0 - (i + 0.5) / n * (1.0 - cosMax), sinT = std::sqrt(1.0 - cosT * cosT);
            const double phi = 2.0 * M_PI * (j + 0.5) / n;
            const glm::dvec3 dir = u * (std::cos(phi) * sinT) + v * (std::sin(phi) * sinT) + w * cosT;
            const double t = d * cosT - std::sqrt(std::max(r * r - d * d * sinT * sinT, 0.0));
            visible += !occludedFrom(occluders, p, p + dir * t);
        }
    }
    return double(visible) / double(n * n);
}

FloorCounts checkShadowFloor(const ShadowFrames& f, const std::vector<PlacedQuad>& visible,
                             const std::vector<PlacedQuad>& occluders, const scene::CameraView& camera,
                             const OracleLight& light, double bandTexels, bool skipUnlit) {
    constexpr uint32_t n = kShadowFrameSize;
    PrimaryHits hits = primaryHits(visible, camera);
    FloorCounts c;
    for (uint32_t py = 0; py < n; ++py) {
        for (uint32_t px = 0; px < n; ++px) {
            const size_t i = size_t(py) * n + px;
            if (hits.quad[i] != 0 || !interiorPixel(hits, px, py)) continue;
            const glm::dvec3 p = hits.point[i];
            const glm::dvec3 L = light.target(p);
            const bool shadow = occludedFrom(occluders, p, L);
            double cosInc = std::max(0.25, (L.y - p.y) / glm::length(L - p));
            double w = bandTexels * light.texel(p) / cosInc;
            bool edge = false;
            for (int k = 0; k < 8 && !edge; ++k) {
                double a = k * 3.14159265358979 / 4.0;
                glm::dvec3 q = p + w * glm::dvec3(std::cos(a), 0.0, std::sin(a));
                edge = occludedFrom(occluders, q, light.target(q)) != shadow;
            }
            if (edge) {
                ++c.band;
                continue;
            }
            double direct = rgbSum(f.unshadowed, i) - rgbSum(f.ambient, i);
            if (skipUnlit && direct <= 0.05) {
                ++c.unlit;
                continue;
            }
            EXPECT_GT(direct, 0.05) << px << "," << py << ": the floor should be lit without shadows";
            double s = (rgbSum(f.full, i) - rgbSum(f.ambient, i)) / direct;
            bool ok = shadow ? s <= 0.02 : s >= 0.98;
            (shadow ? c.dark : c.lit)++;
            if (!ok && c.failures++ == 0)
                c.first = "pixel " + std::to_string(px) + "," + std::to_string(py) + (shadow ? " occluded" : " lit") +
                          " s=" + std::to_string(s) + " at (" + std::to_string(p.x) + ", " + std::to_string(p.y) +
                          ", " + std::to_string(p.z) + ")";
        }
    }
    return c;
}

PlacedQuad floorQuad(float halfSize) {
    PlacedQuad q;
    q.normal = {0.0f, 1.0f, 0.0f};
    q.halfSize = {halfSize, halfSize};
    return q;
}

AcneCounts checkNoAcne(const ShadowFrames& f, const PrimaryHits& hits,
                       const std::function<double(const glm::dvec3&)>& band) {
    constexpr uint32_t n = kShadowFrameSize;
    AcneCounts c;
    for (uint32_t py = 0; py < n; ++py) {
        for (uint32_t px = 0; px < n; ++px) {
            const size_t i = size_t(py) * n + px;
            if (hits.quad[i] < 0 || !interiorPixel(hits, px, py)) continue;
            const glm::dvec3 p = hits.point[i];
            double planes[3] = {p.y, p.x + 2.0, p.z + 2.0};  // one is 0: the point's own surface
            std::sort(planes, planes + 3);
            if (planes[1] < band(p)) continue;  // near a junction with another surface
            const double direct = rgbSum(f.unshadowed, i) - rgbSum(f.ambient, i);
            if (direct < 1e-3) continue;
            const double s = (rgbSum(f.full, i) - rgbSum(f.ambient, i)) / direct;
            ++c.tested;
            c.worst = std::min(c.worst, s);
            if (s < 0.99 && c.failures++ == 0)
                c.first = "pixel " + std::to_string(px) + "," + std::to_string(py) + " quad " +
                          std::to_string(hits.quad[i]) + " s=" + std::to_string(s);
        }
    }
    return c;
}

}  // namespace idk::test
