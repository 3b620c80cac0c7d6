// shadow_oracle_test.cpp: point-light cube shadows in the deferred lighting against a CPU ray-cast oracle, on
// scenes of quads built in code (support/placed_quads.hpp), 128x128 HDR frames, constant environment (ambient).
// Per floor pixel: s = (full - ambient) / (unshadowed - ambient) in RGB sums, from three frames of the same scene:
// with shadows, with the light at intensity 0 (ambient only), with shadows off (PointShadowSettings::maxLights = 0).
//  * Occluder test (a light above a floor and a box): where the CPU ray from the floor point to the light hits the
//    box, s <= 0.02 (only ambient); where it does not, s >= 0.98 (no acne). Excluded: pixels next to a box
//    silhouette, and floor points within kBandTexels shadow texels (world size 2 |p - light| / resolution, divided
//    by the cosine of incidence, at least 1/4) of the CPU shadow boundary: the 3x3 PCF kernel plus bilinear
//    footprint (2.5 texels) and the normal offset (up to 4 texels) blur the edge. The contact region behind the
//    box is NOT excluded, so peter-panning there fails the test.
//  * Mask test: the same check under two alpha-MASK panes, one below its cutoff (cut away: casts nothing).
//  * Acne test (a room corner lit at grazing angles, nothing in between): s >= 0.99 on every lit pixel except
//    within kCornerBand of a concave edge, where a PCF tap may see the adjacent wall.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include "render/renderer.hpp"
#include "support/gpu_fixture.hpp"
#include "support/placed_quads.hpp"

namespace idk::test {
namespace {

constexpr uint32_t kSize = 128;
constexpr double kBandTexels = 5.0;
constexpr uint32_t kResolution = 512;

struct Frames {
    core::ImageRgba32f full, ambient, unshadowed;
};

core::ImageRgba32f render(vk::Context& ctx, vk::ShaderLibrary& shaders, const scene::Scene& scene,
                          const scene::CameraView& camera, uint32_t maxShadowLights) {
    render::RenderSettings settings;
    settings.output = render::OutputKind::Hdr;
    settings.environment = std::filesystem::path();  // constant radiance 0.5
    settings.environmentIntensity = 0.3f;
    settings.pointShadows.maxLights = maxShadowLights;
    settings.pointShadows.resolution = kResolution;
    render::Renderer renderer(ctx, shaders, settings);
    renderer.setScene(scene);
    render::FrameResult frame = renderer.renderOffscreen(camera, kSize, kSize);
    EXPECT_EQ(renderer.pointShadowMaps() != nullptr, maxShadowLights > 0 && scene.lights[0].intensity > 0.0f);
    return frame.image;
}

// The three frames are also written to <build>/shadow_oracle_test/<name>_{full,unshadowed,ambient}.exr.
Frames renderFrames(vk::Context& ctx, vk::ShaderLibrary& shaders, scene::Scene scene, const scene::CameraView& c,
                    const std::string& name) {
    Frames f;
    f.full = render(ctx, shaders, scene, c, 8);
    f.unshadowed = render(ctx, shaders, scene, c, 0);
    scene.lights[0].intensity = 0.0f;
    f.ambient = render(ctx, shaders, scene, c, 8);
    std::filesystem::path dir = std::filesystem::path(IDK_BINARY_DIR) / "shadow_oracle_test";
    std::filesystem::create_directories(dir);
    core::writeImage((dir / (name + "_full.exr")).string(), f.full);
    core::writeImage((dir / (name + "_unshadowed.exr")).string(), f.unshadowed);
    core::writeImage((dir / (name + "_ambient.exr")).string(), f.ambient);
    return f;
}

scene::CameraView lookAt(glm::vec3 eye, glm::vec3 target) {
    scene::CameraView c;
    c.position = eye;
    c.forward = glm::normalize(target - eye);
    c.up = glm::normalize(glm::cross(glm::cross(c.forward, glm::vec3(0, 1, 0)), c.forward));
    c.znear = 0.1f;
    c.zfar = 100.0f;
    return c;
}

double sum3(const core::ImageRgba32f& img, size_t pixel) {
    const float* p = &img.pixels[pixel * 4];
    return double(p[0]) + p[1] + p[2];
}

// Primary CPU hits through every pixel centre (the same ray construction as the deferred lighting).
struct PrimaryHits {
    std::vector<int> quad;  // -1: none
    std::vector<glm::dvec3> point;
};
PrimaryHits primaryHits(const std::vector<PlacedQuad>& quads, const scene::CameraView& camera) {
    glm::dmat4 inv = glm::inverse(glm::dmat4(scene::projectionMatrix(camera, 1.0f) * scene::viewMatrix(camera)));
    PrimaryHits h{std::vector<int>(kSize * kSize, -1), std::vector<glm::dvec3>(kSize * kSize)};
    for (uint32_t py = 0; py < kSize; ++py) {
        for (uint32_t px = 0; px < kSize; ++px) {
            glm::dvec2 ndc((px + 0.5) / kSize * 2.0 - 1.0, (py + 0.5) / kSize * 2.0 - 1.0);
            glm::dvec4 a = inv * glm::dvec4(ndc, 0.0, 1.0), b = inv * glm::dvec4(ndc, 0.5, 1.0);
            glm::dvec3 o = glm::dvec3(a) / a.w, d = glm::normalize(glm::dvec3(b) / b.w - o);
            if (auto hit = castRay(quads, o, d, 0.0, 1e9)) {
                h.quad[py * kSize + px] = int(hit->quad);
                h.point[py * kSize + px] = o + hit->t * d;
            }
        }
    }
    return h;
}

bool interior(const PrimaryHits& h, uint32_t px, uint32_t py) {  // the 3x3 neighbourhood hits the same quad
    if (px == 0 || py == 0 || px + 1 >= kSize || py + 1 >= kSize) return false;
    int q = h.quad[py * kSize + px];
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
            if (h.quad[(py + dy) * kSize + px + dx] != q) return false;
    return true;
}

bool occluded(const std::vector<PlacedQuad>& quads, const glm::dvec3& p, const glm::dvec3& light) {
    glm::dvec3 d = light - p;
    double len = glm::length(d);
    return castRay(quads, p, d / len, 1e-6, len - 1e-6).has_value();
}

struct FloorCounts {
    uint32_t dark = 0, lit = 0, band = 0, failures = 0;
    std::string first;
};

// Classifies the floor pixels (quad 0 of `visible`) against the CPU ray test towards the light through `occluders`
// and checks s per class (see the top of the file).
FloorCounts checkFloor(const Frames& f, const std::vector<PlacedQuad>& visible,
                       const std::vector<PlacedQuad>& occluders, const scene::CameraView& camera, glm::vec3 light) {
    PrimaryHits hits = primaryHits(visible, camera);
    FloorCounts c;
    const glm::dvec3 L(light);
    for (uint32_t py = 0; py < kSize; ++py) {
        for (uint32_t px = 0; px < kSize; ++px) {
            const size_t i = size_t(py) * kSize + px;
            if (hits.quad[i] != 0 || !interior(hits, px, py)) continue;
            const glm::dvec3 p = hits.point[i];
            const bool shadow = occluded(occluders, p, L);
            double cosInc = std::max(0.25, (L.y - p.y) / glm::length(L - p));
            double w = kBandTexels * 2.0 * glm::length(L - p) / kResolution / cosInc;
            bool edge = false;
            for (int k = 0; k < 8 && !edge; ++k) {
                double a = k * 3.14159265358979 / 4.0;
                edge = occluded(occluders, p + w * glm::dvec3(std::cos(a), 0.0, std::sin(a)), L) != shadow;
            }
            if (edge) {
                ++c.band;
                continue;
            }
            double direct = sum3(f.unshadowed, i) - sum3(f.ambient, i);
            EXPECT_GT(direct, 0.05) << px << "," << py << ": the floor should be lit without shadows";
            double s = (sum3(f.full, i) - sum3(f.ambient, i)) / direct;
            bool ok = shadow ? s <= 0.02 : s >= 0.98;
            (shadow ? c.dark : c.lit)++;
            if (!ok && c.failures++ == 0)
                c.first = "pixel " + std::to_string(px) + "," + std::to_string(py) + (shadow ? " occluded" : " lit") +
                          " s=" + std::to_string(s);
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

class ShadowOracleTest : public GpuTest {};

TEST_F(ShadowOracleTest, FloorIsDarkExactlyWhereTheCpuRayToTheLightHitsTheBox) {
    std::vector<PlacedQuad> quads{floorQuad(3.0f)};
    for (const PlacedQuad& f : boxFaces({0.0f, 0.0f, 0.0f}, {0.5f, 0.5f, 0.5f}, glm::vec3(0.6f))) quads.push_back(f);
    const glm::vec3 lightPos(-1.2f, 2.2f, -0.8f);
    scene::Scene scene = makePlacedQuadScene(quads);
    scene.lights.push_back(pointLight(lightPos, 20.0f));
    scene::CameraView camera = lookAt({0.8f, 4.0f, 4.2f}, {0.6f, 0.0f, 0.4f});
    Frames f = renderFrames(ctx(), shaders(), scene, camera, "occluder");
    FloorCounts c = checkFloor(f, quads, quads, camera, lightPos);
    EXPECT_EQ(c.failures, 0u) << "first: " << c.first;
    EXPECT_GT(c.dark, 1000u) << "occluded floor pixels tested";
    EXPECT_GT(c.lit, 3000u) << "lit floor pixels tested";
    EXPECT_LT(c.band, c.dark) << "the excluded edge band stays thinner than the umbra";
    std::printf("shadow oracle: %u occluded, %u lit floor pixels, %u in the edge band\n", c.dark, c.lit, c.band);
}

// Alpha MASK in the shadow pass: a pane whose alpha (0.3) is below its cutoff (0.5) is cut away entirely and
// casts nothing; one above it (0.9) casts a full shadow.
TEST_F(ShadowOracleTest, MaskedPaneBelowItsCutoffCastsNoShadow) {
    std::vector<PlacedQuad> quads{floorQuad(3.0f), {}, {}};
    for (int k : {1, 2}) {
        quads[k].centre = {k == 1 ? -0.9f : 0.9f, 0.8f, 0.0f};
        quads[k].normal = {0.0f, 1.0f, 0.0f};
        quads[k].halfSize = {0.6f, 0.6f};
        quads[k].alphaMode = scene::AlphaMode::Mask;
        quads[k].alpha = k == 1 ? 0.3f : 0.9f;
        quads[k].doubleSided = true;
    }
    const glm::vec3 lightPos(0.0f, 2.5f, 0.0f);
    scene::Scene scene = makePlacedQuadScene(quads);
    scene.lights.push_back(pointLight(lightPos, 20.0f));
    scene::CameraView camera = lookAt({0.0f, 4.5f, 4.0f}, {0.0f, 0.0f, 0.2f});
    Frames f = renderFrames(ctx(), shaders(), scene, camera, "mask");
    std::vector<PlacedQuad> seen{quads[0], quads[2]};  // the cut pane is invisible and casts nothing
    FloorCounts c = checkFloor(f, seen, {quads[2]}, camera, lightPos);
    EXPECT_EQ(c.failures, 0u) << "first: " << c.first;
    EXPECT_GT(c.dark, 500u);
    EXPECT_GT(c.lit, 3000u);
    std::printf("mask oracle: %u occluded, %u lit floor pixels, %u in the edge band\n", c.dark, c.lit, c.band);
}

TEST_F(ShadowOracleTest, GrazingLightOnARoomCornerCastsNoAcne) {
    std::vector<PlacedQuad> quads{floorQuad(2.0f), {}, {}};
    quads[1].centre = {0.0f, 1.0f, -2.0f};  // back wall
    quads[1].halfSize = {2.0f, 1.0f};
    quads[2].centre = {-2.0f, 1.0f, 0.0f};  // left wall
    quads[2].normal = {1.0f, 0.0f, 0.0f};
    quads[2].halfSize = {2.0f, 1.0f};
    const glm::vec3 lightPos(-1.7f, 0.2f, -1.7f);  // 0.2-0.3 from every surface: incidence up to ~86 degrees
    scene::Scene scene = makePlacedQuadScene(quads);
    scene.lights.push_back(pointLight(lightPos, 3.0f));
    scene::CameraView camera = lookAt({2.6f, 2.4f, 2.6f}, {-0.8f, 0.4f, -0.8f});
    Frames f = renderFrames(ctx(), shaders(), scene, camera, "corner");
    PrimaryHits hits = primaryHits(quads, camera);

    constexpr double kCornerBand = 0.03;  // world units from the wall/floor junctions
    uint32_t tested = 0, failures = 0;
    double worst = 1.0;
    std::string first;
    for (uint32_t py = 0; py < kSize; ++py) {
        for (uint32_t px = 0; px < kSize; ++px) {
            const size_t i = size_t(py) * kSize + px;
            if (hits.quad[i] < 0 || !interior(hits, px, py)) continue;
            const glm::dvec3 p = hits.point[i];
            double planes[3] = {p.y, p.x + 2.0, p.z + 2.0};  // one is 0: the point's own surface
            std::sort(planes, planes + 3);
            if (planes[1] < kCornerBand) continue;  // near a junction with another surface
            double direct = sum3(f.unshadowed, i) - sum3(f.ambient, i);
            if (direct < 1e-3) continue;
            double s = (sum3(f.full, i) - sum3(f.ambient, i)) / direct;
            ++tested;
            worst = std::min(worst, s);
            if (s < 0.99 && failures++ == 0)
                first = "pixel " + std::to_string(px) + "," + std::to_string(py) + " quad " +
                        std::to_string(hits.quad[i]) + " s=" + std::to_string(s);
        }
    }
    EXPECT_EQ(failures, 0u) << "first: " << first;
    EXPECT_GT(tested, 6000u);
    std::printf("acne test: %u pixels, lowest visibility %.4f\n", tested, worst);
}

}  // namespace
}  // namespace idk::test
