// vxgi_half_res_test.cpp: --gi-resolution half (cone tracing on one pixel per 2x2 block, then the edge-aware
// upsample of passes/vxgi_upsample.cpp) against --gi-resolution full, the oracle: the same frame traced at every
// pixel. 64x64 pixels, 64^3 voxels, 1 + 8 cones. The indirect term is the frame minus the --gi none frame (both HDR).
//  * Closed room lit by an emissive ceiling panel (environment off) and the embedded Cornell box (default camera,
//    environment on): 99% of the pixels' half-resolution indirect term within the range of their 3x3 neighbourhood's
//    full-resolution values (2% slack; every traced sample is its pixel's full trace and the upsample's weights are
//    convex), and the relative L1 over the frame below 0.06 (room, measured 0.038) and 0.09 (Cornell box, measured
//    0.076). Both with the default 4 footprint cones per diffuse cone (--gi-footprint); with one cone they measured
//    0.072 and 0.094: each cone's thin sample tube met or missed the light panel from pixel to pixel, detail the 2x2
//    sampling smooths (0.0635 on the Cornell box while the panel's voxels held 0.53 of its radiance, before the
//    front-most rule of shared/vxgi_depth_key.h; 0.031 while level 0 was isotropic).
//  * Depth edges: a box in front of the back wall of a room whose panel hangs over the back half, so the box's
//    front face sees no emitter (its indirect light is ~0) while the wall behind it is lit. On every pixel next to
//    the box's silhouette (a 3x3 neighbour on the other side, per a CPU ray cast) with a contrast |O - F| of at least
//    half the brighter side (F its full-resolution value, O the other side's mean over the 3x3), the half-resolution
//    value H lies outside the range of its own side's full-resolution values in the 3x3 by less than 0.1 |O - F|
//    (a plain bilinear upsample blends 1/4 .. 3/4 across).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "app/default_scene.hpp"
#include "render/renderer.hpp"
#include "scene/camera.hpp"
#include "shared/pt_common.h"
#include "support/gpu_fixture.hpp"
#include "support/placed_quads.hpp"

namespace idk::test {
namespace {

constexpr uint32_t kSize = 64;

struct Frame {
    core::ImageRgba32f image;
    std::vector<std::string> passes;
};

Frame render(vk::Context& ctx, vk::ShaderLibrary& shaders, const scene::Scene& s, const scene::CameraView& c,
             frame::GiMode gi, frame::GiResolution resolution, bool environment) {
    render::RenderSettings settings;
    settings.output = render::OutputKind::Hdr;
    if (!environment) settings.environmentIntensity = 0.0f;
    settings.vxgi.mode = gi;
    settings.vxgi.voxels = 64;
    settings.vxgi.ringCones = 8;
    settings.vxgi.resolution = resolution;
    render::Renderer renderer(ctx, shaders, settings);
    renderer.setScene(s);
    render::FrameResult f = renderer.renderOffscreen(c, kSize, kSize);
    return {std::move(f.image), std::move(f.passesRun)};
}

double luminance(const core::ImageRgba32f& img, size_t i) {
    const float* p = &img.pixels[i * 4];
    return (double(p[0]) + p[1] + p[2]) / 3.0;
}

// The indirect term's luminance per pixel: the frame minus the --gi none frame.
std::vector<double> indirect(const core::ImageRgba32f& vxgi, const core::ImageRgba32f& none) {
    std::vector<double> out(size_t(kSize) * kSize);
    for (size_t i = 0; i < out.size(); ++i) out[i] = luminance(vxgi, i) - luminance(none, i);
    return out;
}

PlacedQuad wall(glm::vec3 centre, glm::vec3 normal, glm::vec2 half, float albedo = 0.6f) {
    PlacedQuad q;
    q.centre = centre;
    q.normal = normal;
    q.halfSize = half;
    q.baseColor = glm::vec3(albedo);
    return q;
}

// The 2 m room of grey walls with a full ceiling and an emissive panel hung 1 cm below it at (x, z).
std::vector<PlacedQuad> room(glm::vec2 panelCentre, glm::vec2 panelHalf) {
    return {wall({0, -1, 0}, {0, 1, 0}, {1, 1}),  wall({-1, 0, 0}, {1, 0, 0}, {1, 1}),
            wall({1, 0, 0}, {-1, 0, 0}, {1, 1}),  wall({0, 0, -1}, {0, 0, 1}, {1, 1}),
            wall({0, 0, 1}, {0, 0, -1}, {1, 1}),  wall({0, 1, 0}, {0, -1, 0}, {1, 1}),
            wall({panelCentre.x, 0.99f, panelCentre.y}, {0, -1, 0}, panelHalf)};
}

scene::Scene roomScene(const std::vector<PlacedQuad>& quads) {
    scene::Scene s = makePlacedQuadScene(quads);
    for (scene::Material& m : s.materials) m.metallic = 0.0f;
    s.materials[6].emissive = glm::vec3(8.0f);
    return s;
}

scene::CameraView lookAt(glm::vec3 eye, glm::vec3 forward, float yfov) {
    scene::CameraView c;
    c.position = eye;
    c.forward = glm::normalize(forward);
    c.up = glm::normalize(glm::cross(glm::cross(c.forward, glm::vec3(0, 1, 0)), c.forward));
    c.yfov = yfov;
    c.znear = 0.01f;
    return c;
}

class VxgiHalfResTest : public GpuTest {};

void expectHalfNearFull(vk::Context& ctx, vk::ShaderLibrary& shaders, const char* name, const scene::Scene& s,
                        const scene::CameraView& c, bool environment, double maxL1) {
    const Frame none = render(ctx, shaders, s, c, frame::GiMode::None, frame::GiResolution::Full, environment);
    const Frame full = render(ctx, shaders, s, c, frame::GiMode::Vxgi, frame::GiResolution::Full, environment);
    const Frame half = render(ctx, shaders, s, c, frame::GiMode::Vxgi, frame::GiResolution::Half, environment);
    const auto count = [](const Frame& f, const char* pass) {
        return std::count(f.passes.begin(), f.passes.end(), pass);
    };
    EXPECT_EQ(count(full, "vxgi_upsample"), 0);
    EXPECT_EQ(count(half, "vxgi_upsample"), 1);
    EXPECT_EQ(count(half, "vxgi_cone_trace"), 1);
    EXPECT_EQ(count(half, "vxgi_cone_trace_fixup"), 1);
    const std::vector<double> f = indirect(full.image, none.image), h = indirect(half.image, none.image);
    double diff = 0.0, sum = 0.0;
    for (size_t i = 0; i < f.size(); ++i) {
        diff += std::abs(h[i] - f[i]);
        sum += std::abs(f[i]);
    }
    ASSERT_GT(sum, 0.0) << name << ": no indirect light";
    const double mean = sum / double(f.size());
    // Every traced sample is the full-resolution trace of its pixel, and the upsample's weights are convex over
    // samples within one pixel: each pixel lies within the range of its 3x3 neighbourhood's full-resolution values.
    size_t within = 0;
    for (int y = 0; y < int(kSize); ++y) {
        for (int x = 0; x < int(kSize); ++x) {
            double lo = 1e30, hi = -1e30;
            for (int dy = -1; dy <= 1; ++dy) {
                for (int dx = -1; dx <= 1; ++dx) {
                    const int qx = x + dx, qy = y + dy;
                    if (qx < 0 || qy < 0 || qx >= int(kSize) || qy >= int(kSize)) continue;
                    lo = std::min(lo, f[size_t(qy) * kSize + size_t(qx)]);
                    hi = std::max(hi, f[size_t(qy) * kSize + size_t(qx)]);
                }
            }
            const double v = h[size_t(y) * kSize + size_t(x)], slack = 0.02 * std::abs(hi) + 1e-3 * mean;
            within += v >= lo - slack && v <= hi + slack;
        }
    }
    const double fraction = double(within) / double(f.size());
    std::printf("%s: half vs full resolution indirect term: relative L1 %.4f, %.2f%% of pixels within their 3x3 "
                "neighbourhood's full-resolution range\n",
                name, diff / sum, 100.0 * fraction);
    EXPECT_LT(diff / sum, maxL1) << name;
    EXPECT_GE(fraction, 0.99) << name;
}

TEST_F(VxgiHalfResTest, ClosedRoomHalfResolutionMatchesFull) {
    const scene::Scene s = roomScene(room({0.0f, 0.0f}, {0.3f, 0.3f}));
    expectHalfNearFull(ctx(), shaders(), "closed room", s,
                       lookAt({0.0f, -0.1f, 0.95f}, {0.0f, 0.25f, -1.0f}, 1.4f), false, 0.06);
}

TEST_F(VxgiHalfResTest, CornellBoxHalfResolutionMatchesFull) {
    const scene::Scene s = app::loadDefaultScene();
    expectHalfNearFull(ctx(), shaders(), "Cornell box", s, scene::defaultCamera(s), true, 0.09);
}

TEST_F(VxgiHalfResTest, NoIndirectLightCrossesADepthEdge) {
    std::vector<PlacedQuad> quads = room({0.0f, -0.6f}, {0.4f, 0.3f});
    const size_t firstBoxQuad = quads.size();
    for (const PlacedQuad& q : boxFaces({0.0f, -1.0f, 0.25f}, {0.3f, 0.45f, 0.15f}, glm::vec3(0.6f)))
        quads.push_back(q);
    const scene::Scene s = roomScene(quads);
    const scene::CameraView c = lookAt({0.0f, 0.0f, 0.95f}, {0.0f, -0.2f, -1.0f}, 1.2f);
    const Frame none = render(ctx(), shaders(), s, c, frame::GiMode::None, frame::GiResolution::Full, false);
    const Frame full = render(ctx(), shaders(), s, c, frame::GiMode::Vxgi, frame::GiResolution::Full, false);
    const Frame half = render(ctx(), shaders(), s, c, frame::GiMode::Vxgi, frame::GiResolution::Half, false);
    const std::vector<double> f = indirect(full.image, none.image), h = indirect(half.image, none.image);

    // Which side of the silhouette each pixel sees: the box (1), the room (0), nothing (-1).
    const glm::mat4 inverseViewProjection =
        glm::inverse(scene::projectionMatrix(c, 1.0f) * scene::viewMatrix(c));
    std::vector<int> side(size_t(kSize) * kSize, -1);
    for (uint32_t y = 0; y < kSize; ++y) {
        for (uint32_t x = 0; x < kSize; ++x) {
            glm::vec3 o, d;
            gpu::ptCameraRay(inverseViewProjection, glm::vec2(float(x) + 0.5f, float(y) + 0.5f),
                             glm::vec2(float(kSize)), o, d);
            if (auto hit = castRay(quads, glm::dvec3(o), glm::dvec3(d), 0.0, 1e9))
                side[size_t(y) * kSize + x] = hit->quad >= firstBoxQuad ? 1 : 0;
        }
    }
    size_t edge = 0, box = 0;
    double worst = 0.0, leakSum = 0.0;
    for (int y = 1; y + 1 < int(kSize); ++y) {
        for (int x = 1; x + 1 < int(kSize); ++x) {
            const size_t i = size_t(y) * kSize + size_t(x);
            if (side[i] < 0) continue;
            box += side[i] == 1;
            double other = 0.0, lo = f[i], hi = f[i];
            int n = 0;
            bool mixed = false;
            for (int dy = -1; dy <= 1; ++dy) {
                for (int dx = -1; dx <= 1; ++dx) {
                    const size_t j = size_t(y + dy) * kSize + size_t(x + dx);
                    if (side[j] < 0) mixed = true;  // the pixel may be a silhouette against nothing: skip it
                    if (side[j] == side[i]) {
                        lo = std::min(lo, f[j]);
                        hi = std::max(hi, f[j]);
                    } else if (side[j] >= 0) {
                        other += f[j];
                        ++n;
                    }
                }
            }
            if (n == 0 || mixed) continue;
            other /= double(n);
            const double contrast = std::abs(other - f[i]);
            if (contrast == 0.0 || contrast < 0.5 * std::max(std::abs(other), std::abs(f[i]))) continue;
            // How far the half-resolution value lies outside its own side's full-resolution range, in units of the
            // contrast: 0 when it blends only its own side's light, 1 when it took the other side's.
            const double leak = std::max({0.0, h[i] - hi, lo - h[i]}) / contrast;
            worst = std::max(worst, leak);
            leakSum += leak;
            ++edge;
        }
    }
    std::printf("depth edges: %zu silhouette pixels with contrast, leak beyond the own side's range / contrast: mean %.4f, worst %.4f\n",
                edge, edge ? leakSum / double(edge) : 0.0, worst);
    ASSERT_GT(box, size_t(kSize) * kSize / 10) << "the camera should see the box";
    ASSERT_GT(edge, 40u) << "the silhouette should separate dark from lit";
    EXPECT_LT(worst, 0.1);
}

}  // namespace
}  // namespace idk::test
