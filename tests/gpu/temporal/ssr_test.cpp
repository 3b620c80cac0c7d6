// ssr_test.cpp: screen-space reflections (frame/ssr_feature.hpp) against the path tracer's mirror reflection. The
// scene: a mirror floor (metallic 1, roughness 0, white: it reflects everything, f0 = 1) under a constant sky of
// radiance 0.5, an emissive panel (black base colour, emission 4) standing above it in view, no lights, 96x96. The
// panel's radiance is its emission in both renderers, so the reflection's error is SSR's alone. Pixels are
// classified on the CPU by casting the camera ray and its mirror ray against the quads (castRay):
//  * reflected region (floor pixels whose mirror ray hits the panel, 3x3-eroded so no pixel straddles an edge): the
//    mean absolute error against the path tracer (64 spp) relative to its mean, with --ssr well below 10% and below
//    a tenth of the error without SSR (which shows the sky there: about 88%).
//  * miss region (floor pixels whose mirror ray leaves through the sky clear of the panel's box thickened by the
//    SSR thickness and padded by 0.1, eroded): SSR returns no hit, so the pixels equal the frame without SSR exactly
//    and the environment term (0.5 * albedo 1). (Rays passing within the thickness behind the panel may count as
//    hits: the thickness test's approximation, excluded here.)
//  * nothing SSR runs without --ssr; its three passes run with it.
// The images are written to <build>/ssr_test/mirror_{ssr,no_ssr,pt}.exr.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "render/path_tracer.hpp"
#include "render/renderer.hpp"
#include "scene/camera.hpp"
#include "support/gpu_fixture.hpp"
#include "support/placed_quads.hpp"

namespace idk::test {
namespace {

constexpr uint32_t kSize = 96;
constexpr double kThickness = 0.1;  // SsrSettings::thickness's default, which the test renders with
constexpr double kMargin = 0.1;     // world units around the panel that a miss ray keeps clear of

std::vector<PlacedQuad> quads() {
    PlacedQuad floor;
    floor.centre = {0.0f, 0.0f, 0.0f};
    floor.normal = {0.0f, 1.0f, 0.0f};
    floor.halfSize = {3.0f, 3.0f};
    floor.baseColor = glm::vec3(1.0f);
    floor.roughness = 0.0f;
    PlacedQuad panel;
    panel.centre = {0.0f, 0.5f, -1.0f};
    panel.normal = {0.0f, 0.0f, 1.0f};
    panel.halfSize = {0.5f, 0.3f};
    panel.baseColor = glm::vec3(0.0f);
    return {floor, panel};
}

scene::Scene mirrorScene() {
    scene::Scene s = makePlacedQuadScene(quads());
    s.materials[0].metallic = 1.0f;
    s.materials[1].metallic = 0.0f;
    s.materials[1].emissive = glm::vec3(4.0f);
    return s;
}

scene::CameraView camera() {
    scene::CameraView c;
    c.position = {0.0f, 0.6f, 1.5f};
    c.forward = glm::normalize(glm::vec3(0.0f, -0.6f, -2.5f));
    c.up = glm::normalize(glm::cross(glm::cross(c.forward, glm::vec3(0, 1, 0)), c.forward));
    c.yfov = 1.0f;
    c.znear = 0.01f;
    return c;
}

enum class Kind { Other, Reflected, Missed };

// The ray o + t d (t > 0) meets the box [lo, hi] (slab test).
bool hitsBox(glm::dvec3 o, glm::dvec3 d, glm::dvec3 lo, glm::dvec3 hi) {
    double t0 = 0.0, t1 = 1e30;
    for (int a = 0; a < 3; ++a) {
        if (std::abs(d[a]) < 1e-12) {
            if (o[a] < lo[a] || o[a] > hi[a]) return false;
            continue;
        }
        double ta = (lo[a] - o[a]) / d[a], tb = (hi[a] - o[a]) / d[a];
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
    }
    return t0 <= t1;
}

// Per pixel: what the camera ray's mirror bounce off the floor reaches.
std::vector<Kind> classify() {
    const std::vector<PlacedQuad> q = quads();
    const scene::CameraView c = camera();
    const glm::dmat4 inv = glm::inverse(glm::dmat4(scene::projectionMatrix(c, 1.0f) * scene::viewMatrix(c)));
    std::vector<Kind> kinds(size_t(kSize) * kSize, Kind::Other);
    for (uint32_t y = 0; y < kSize; ++y)
        for (uint32_t x = 0; x < kSize; ++x) {
            const glm::dvec2 ndc = (glm::dvec2(x, y) + 0.5) / double(kSize) * 2.0 - 1.0;
            const glm::dvec4 a = inv * glm::dvec4(ndc, 0.0, 1.0), b = inv * glm::dvec4(ndc, 0.5, 1.0);
            const glm::dvec3 o = glm::dvec3(a) / a.w, d = glm::normalize(glm::dvec3(b) / b.w - o);
            const auto hit = castRay(q, o, d, 0.0, 1e9);
            if (!hit || hit->quad != 0) continue;
            const glm::dvec3 p = o + d * hit->t;
            const glm::dvec3 r = glm::reflect(d, glm::dvec3(0, 1, 0));
            const auto bounce = castRay(q, p, r, 1e-6, 1e9);
            if (bounce && bounce->quad == 1) {
                kinds[size_t(y) * kSize + x] = Kind::Reflected;
            } else if (!hitsBox(p, r, glm::dvec3(-0.5 - kMargin, 0.2 - kMargin, -1.0 - kThickness - kMargin),
                                glm::dvec3(0.5 + kMargin, 0.8 + kMargin, -1.0 + kMargin))) {
                // A ray passing just behind the panel (within the thickness) may count as a hit: SSR's
                // approximation. Misses are the rays that stay clear of the panel's thickened, padded box.
                kinds[size_t(y) * kSize + x] = Kind::Missed;
            }
        }
    // Erode: keep a pixel only when its 3x3 neighbourhood has its kind (no pixel straddles an edge).
    std::vector<Kind> eroded(kinds.size(), Kind::Other);
    for (uint32_t y = 1; y + 1 < kSize; ++y)
        for (uint32_t x = 1; x + 1 < kSize; ++x) {
            const Kind k = kinds[size_t(y) * kSize + x];
            bool same = true;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) same = same && kinds[size_t(y + dy) * kSize + (x + dx)] == k;
            if (same) eroded[size_t(y) * kSize + x] = k;
        }
    return eroded;
}

render::FrameResult raster(vk::Context& ctx, vk::ShaderLibrary& shaders, bool ssr) {
    render::RenderSettings settings;
    settings.output = render::OutputKind::Hdr;
    settings.environment = std::filesystem::path();  // constant radiance 0.5
    settings.ssr.enabled = ssr;
    render::Renderer renderer(ctx, shaders, settings);
    renderer.setScene(mirrorScene());
    return renderer.renderStill(camera(), kSize, kSize);
}

double luminance(const core::ImageRgba32f& img, size_t i) {
    const float* p = &img.pixels[i * 4];
    return (double(p[0]) + p[1] + p[2]) / 3.0;
}

class SsrTest : public GpuTest {};

TEST_F(SsrTest, MirrorFloorMatchesPathTracedReflection) {
    const std::vector<Kind> kinds = classify();
    const size_t reflected = size_t(std::count(kinds.begin(), kinds.end(), Kind::Reflected));
    const size_t missed = size_t(std::count(kinds.begin(), kinds.end(), Kind::Missed));
    ASSERT_GT(reflected, 150u) << "the panel's reflection should cover part of the floor";
    ASSERT_GT(missed, 500u) << "and the sky's the rest";

    const render::FrameResult on = raster(ctx(), shaders(), true);
    const render::FrameResult off = raster(ctx(), shaders(), false);
    size_t ssrPasses[2] = {0, 0};
    for (const std::string& pass : on.passesRun) ssrPasses[0] += pass.rfind("ssr_", 0) == 0;
    for (const std::string& pass : off.passesRun) ssrPasses[1] += pass.rfind("ssr_", 0) == 0;
    EXPECT_EQ(ssrPasses[0], 3u) << "ssr_hiz, ssr_trace, ssr_keep";
    EXPECT_EQ(ssrPasses[1], 0u) << "nothing SSR runs with --ssr off";

    render::PathTracerOptions options;
    options.environment = std::filesystem::path();
    render::PathTracer tracer(ctx(), shaders(), mirrorScene(), options);
    render::PathTraceSettings pts;
    pts.spp = 64;
    const core::ImageRgba32f pt = tracer.render(camera(), kSize, kSize, pts).image;

    const std::filesystem::path dir = std::filesystem::path(IDK_BINARY_DIR) / "ssr_test";
    std::filesystem::create_directories(dir);
    core::writeImage((dir / "mirror_ssr.exr").string(), on.image);
    core::writeImage((dir / "mirror_no_ssr.exr").string(), off.image);
    core::writeImage((dir / "mirror_pt.exr").string(), pt);

    double errOn = 0.0, errOff = 0.0, reference = 0.0, missDiff = 0.0, envDiff = 0.0;
    for (size_t i = 0; i < kinds.size(); ++i) {
        if (kinds[i] == Kind::Reflected) {
            errOn += std::abs(luminance(on.image, i) - luminance(pt, i));
            errOff += std::abs(luminance(off.image, i) - luminance(pt, i));
            reference += luminance(pt, i);
        } else if (kinds[i] == Kind::Missed) {
            for (int c = 0; c < 3; ++c) {
                const float a = on.image.pixels[i * 4 + c], b = off.image.pixels[i * 4 + c];
                missDiff = std::max(missDiff, double(std::abs(a - b)));
                envDiff = std::max(envDiff, std::abs(double(on.image.pixels[i * 4 + c]) - 0.5));
            }
        }
    }
    errOn /= reference;
    errOff /= reference;
    reference /= double(reflected);
    std::printf("mirror floor, %zu reflected pixels (path tracer mean %.4f): relative mean abs error with SSR %.4f, "
                "without %.4f; %zu miss pixels: max |ssr - no ssr| %.2e, max |ssr - environment 0.5| %.2e\n",
                reflected, reference, errOn, errOff, missed, missDiff, envDiff);
    EXPECT_LT(errOn, 0.10);
    EXPECT_LT(errOn, 0.1 * errOff);
    EXPECT_EQ(missDiff, 0.0) << "a miss keeps the environment term unchanged";
    EXPECT_LT(envDiff, 1e-3) << "the mirror shows the sky's 0.5 where the reflection leaves the screen";
}

}  // namespace
}  // namespace idk::test
