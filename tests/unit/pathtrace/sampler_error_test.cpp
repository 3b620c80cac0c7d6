// sampler_error_test.cpp: what the Owen-scrambled Sobol' sampler buys in images, on the CPU reference tracer:
// at equal spp (4, 16, 64) its RMSE against a high-spp reference is lower than the independent sampler's on the
// Cornell box and two shared scenes (BoxTextured and DamagedHelmet under a uniform sky),
// and its error image is white noise: no pixel-to-pixel correlation and a flat power spectrum (per-pixel
// scrambling; a sampler sharing its points between pixels would leave structured patterns).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <filesystem>

#include "pathtrace/cpu_path_tracer.hpp"
#include "pt_test_scenes.hpp"
#include "scene/gltf_loader.hpp"
#include "scene/primitive_ops.hpp"
#include "shared/pt_sampler.h"

namespace idk::test {
namespace {

using pathtrace::PtSampler;
using pathtrace::PtSettings;

struct SamplerCase {
    const char* name;
    std::filesystem::path file;
    glm::vec3 sky;  // uniform environment radiance
    uint32_t size;  // image width and height
};

// RMSE over the pixels away from directly visible emitters (reference above 1 in a channel, and their 8
// neighbours): an emitter's edge pixel is a coin flip between ~0 and ~15 per sample, so there the reference's own
// noise (independent, 4096 spp) is larger than a stratified 64-spp estimate's and would decide the comparison.
double rmseAwayFromEmitters(const core::ImageRgba32f& image, const core::ImageRgba32f& reference) {
    const int w = int(reference.width), h = int(reference.height);
    auto bright = [&](int x, int y) {
        if (x < 0 || y < 0 || x >= w || y >= h) return false;
        const float* p = &reference.pixels[4 * (size_t(y) * w + x)];
        return std::max({p[0], p[1], p[2]}) > 1.0f;
    };
    double sum = 0.0;
    size_t count = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            bool near = false;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) near |= bright(x + dx, y + dy);
            if (near) continue;
            for (int c = 0; c < 3; ++c) {
                const size_t i = 4 * (size_t(y) * w + x) + c;
                sum += (double(image.pixels[i]) - reference.pixels[i]) * (double(image.pixels[i]) - reference.pixels[i]);
            }
            count += 3;
        }
    EXPECT_GT(count, size_t(3 * w * h / 2)) << "most pixels are compared";
    return count ? std::sqrt(sum / double(count)) : 0.0;
}

// RMSE of both samplers at 4, 16, 64 spp against an independent-sampler reference of 2^20 samples in all (4096
// spp at 16x16: its error is 1/8 of the 64-spp independent render's; it favours neither sampler), depth 5.
void compareSamplers(const SamplerCase& c) {
    scene::Scene s = scene::loadGltf(c.file);
    s.lights.clear();  // Cornell's point light under the emitter has heavy-tailed variance (cornell_test.cpp)
    const pathtrace::PathTraceScene pts = pathtrace::buildPathTraceScene(s, nullptr, 1.0f, c.sky);
    const scene::CameraView cam = scene::defaultCamera(s);
    const uint32_t size = c.size;
    PtSettings settings;
    settings.maxDepth = 5;
    settings.spp = (1u << 20) / (size * size);
    settings.seed = 9001;
    settings.sampler = PtSampler::Independent;
    const core::ImageRgba32f reference = pathtrace::renderReference(pts, cam, size, size, settings);
    const glm::dvec3 mean = imageMean(reference);
    ASSERT_GT(mean.x + mean.y + mean.z, 0.03) << c.name << " is lit";
    for (uint32_t spp : {4u, 16u, 64u}) {
        settings.spp = spp;
        settings.seed = spp;
        settings.sampler = PtSampler::Independent;
        const double independent =
            rmseAwayFromEmitters(pathtrace::renderReference(pts, cam, size, size, settings), reference);
        settings.sampler = PtSampler::Sobol;
        const double sobol = rmseAwayFromEmitters(pathtrace::renderReference(pts, cam, size, size, settings), reference);
        std::printf("%s %u spp: RMSE independent %.5f sobol %.5f ratio %.3f\n", c.name, spp, independent, sobol,
                    sobol / independent);
        EXPECT_LT(sobol, 0.95 * independent) << c.name << " at " << spp << " spp";
    }
}

const std::filesystem::path kShared = std::filesystem::path(IDK_SHARED_DIR) / "scenes";

TEST(PtSamplerError, SobolBeatsIndependentOnTheCornellBox) {
    compareSamplers({"cornell", std::filesystem::path(IDK_SOURCE_DIR) / "scenes/cornell_box.gltf", glm::vec3(0.0f), 16});
}
TEST(PtSamplerError, SobolBeatsIndependentOnBoxTextured) {
    compareSamplers({"BoxTextured", kShared / "BoxTextured/glTF-Binary/BoxTextured.glb", glm::vec3(0.6f), 32});
}
TEST(PtSamplerError, SobolBeatsIndependentOnDamagedHelmet) {
    compareSamplers({"DamagedHelmet", kShared / "DamagedHelmet/glTF-Binary/DamagedHelmet.glb", glm::vec3(0.6f), 24});
}

// Normalised autocorrelation of a w x h field at lag (dx, dy).
double autocorrelation(const std::vector<double>& e, int w, int h, int dx, int dy) {
    double mean = 0;
    for (double v : e) mean += v;
    mean /= double(e.size());
    double num = 0, den = 0;
    for (double v : e) den += (v - mean) * (v - mean);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const int x2 = x + dx, y2 = y + dy;
            if (x2 < 0 || y2 < 0 || x2 >= w || y2 >= h) continue;
            num += (e[size_t(y) * w + x] - mean) * (e[size_t(y2) * w + x2] - mean);
        }
    return den > 0 ? num / den * double(w * h) / double((w - std::abs(dx)) * (h - std::abs(dy))) : 1.0;
}

// Mean power of the field's DFT in the low (radius < n/4) over the high (radius >= n/4) frequency band; 1 for
// white noise. n x n, n small (a direct DFT).
double lowOverHighPower(const std::vector<double>& e, int n) {
    const double pi = 3.14159265358979;
    double mean = 0;
    for (double v : e) mean += v;
    mean /= double(e.size());
    double low = 0, high = 0;
    int lowCount = 0, highCount = 0;
    for (int v = 0; v < n; ++v)
        for (int u = 0; u < n; ++u) {
            if (u == 0 && v == 0) continue;
            std::complex<double> f = 0;
            for (int y = 0; y < n; ++y)
                for (int x = 0; x < n; ++x)
                    f += (e[size_t(y) * n + x] - mean) * std::polar(1.0, -2.0 * pi * double(u * x + v * y) / n);
            const int fu = std::min(u, n - u), fv = std::min(v, n - v);
            const bool isLow = fu * fu + fv * fv < n * n / 16;
            (isLow ? low : high) += std::norm(f);
            ++(isLow ? lowCount : highCount);
        }
    return (low / lowCount) / (high / highCount);
}

// The error field check, tried on a field with structure first so that it is known to fail: every pixel
// estimating the same step function with the SAME points (no per-pixel scrambling) gives errors that follow the
// step's position, i.e. smooth in x.
void expectWhite(const std::vector<double>& e, int n, const char* what, double rhoLimit, bool expectPass) {
    const double rx = autocorrelation(e, n, n, 1, 0), ry = autocorrelation(e, n, n, 0, 1);
    const double rd = autocorrelation(e, n, n, 1, 1), r2 = autocorrelation(e, n, n, 2, 0);
    const double ratio = lowOverHighPower(e, n);
    std::printf("%s: autocorrelation (1,0) %.3f (0,1) %.3f (1,1) %.3f (2,0) %.3f, low/high band power %.3f\n", what,
                rx, ry, rd, r2, ratio);
    const bool white = std::abs(rx) < rhoLimit && std::abs(ry) < rhoLimit && std::abs(rd) < rhoLimit &&
                       std::abs(r2) < rhoLimit && ratio > 0.75 && ratio < 1.33;
    EXPECT_EQ(white, expectPass) << what;
}

TEST(PtSamplerError, SobolErrorImageIsWhite) {
    const int n = 32;
    // Negative control: one shared scramble for all pixels, integrand step(u < x / n) per pixel.
    std::vector<double> shared(size_t(n) * n);
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            double sum = 0;
            for (uint32_t i = 0; i < 3; ++i) {
                const float u = gpu::ptUnitFloat(gpu::ptSobolBits(12345u, i, 0));
                sum += u < (float(x) + 0.5f) / float(n) ? 1.0 : 0.0;
            }
            shared[size_t(y) * n + x] = sum / 3.0 - (double(x) + 0.5) / n + 1e-3 * double(y % 2);
        }
    expectWhite(shared, n, "shared points (control)", 0.15, false);

    // The tracer: a Lambert sphere (albedo 0.8, IOR 1) filling the view in a uniform sky of radiance 1 reflects
    // exactly 0.8 everywhere, so the error of a 4-spp NEE+MIS render is known per pixel without a reference.
    scene::Scene s;
    scene::Material grey = diffuse(glm::vec3(0.8f));
    grey.ior = 1.0f;
    scene::Primitive sphere = uvSphere(glm::vec3(0.0f), 1.0f, 24, 48);
    scene::makeFlatNormals(sphere);
    addObject(s, sphere, grey);
    const pathtrace::PathTraceScene pts = pathtrace::buildPathTraceScene(s, nullptr, 1.0f, glm::vec3(1.0f));
    const scene::CameraView cam = lookAt(glm::vec3(0.0f, 0.3f, 3.0f), glm::vec3(0.0f), 0.25f);
    PtSettings settings;
    settings.spp = 4;
    settings.maxDepth = 6;
    settings.sampler = PtSampler::Sobol;
    const core::ImageRgba32f img = pathtrace::renderReference(pts, cam, n, n, settings);
    std::vector<double> error(size_t(n) * n);
    for (size_t i = 0; i < error.size(); ++i) error[i] = double(img.pixels[4 * i]) - 0.8;
    double rms = 0;
    for (double v : error) rms += v * v;
    ASSERT_GT(std::sqrt(rms / double(error.size())), 1e-3) << "the render is noisy (the check has something to see)";
    // 1024 pixels: an autocorrelation of white noise has a standard deviation of 1/32; the bound is 4 of them.
    expectWhite(error, n, "sobol 4 spp error", 0.125, true);
}

}  // namespace
}  // namespace idk::test
