// estimator_test.cpp: the CPU reference path tracer's estimators: NEE+MIS and BSDF-only sampling converge to the
// same image (emissive quad, HDR sky), NEE+MIS has the lower error at equal samples, degenerate geometry and
// materials give finite images, renders are deterministic whatever the thread count and report progress.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "pathtrace/cpu_path_tracer.hpp"
#include "pt_test_scenes.hpp"
#include "scene/gltf_loader.hpp"
#include "scene/primitive_ops.hpp"

namespace idk::test {
namespace {

using pathtrace::PtSettings;

// A grey floor and a glossy sphere lit by a textured-free emissive quad and a dim sky, no punctual light (which
// BSDF sampling alone could never hit).
scene::Scene litScene() {
    scene::Scene s;
    addObject(s, quad({-2, 0, 2}, {2, 0, 2}, {2, 0, -2}, {-2, 0, -2}), diffuse(glm::vec3(0.6f)));
    scene::Material glossy = diffuse(glm::vec3(0.9f, 0.6f, 0.3f));
    glossy.metallic = 1.0f;
    glossy.roughness = 0.4f;
    addObject(s, uvSphere(glm::vec3(0.0f, 0.6f, 0.0f), 0.6f, 8, 16), glossy);
    scene::Material lamp = diffuse(glm::vec3(0.0f));
    lamp.emissive = glm::vec3(4.0f, 3.5f, 3.0f);
    addObject(s, quad({-0.6f, 2.0f, -0.6f}, {0.6f, 2.0f, -0.6f}, {0.6f, 2.0f, 0.6f}, {-0.6f, 2.0f, 0.6f}), lamp);
    return s;
}

TEST(PtReference, NeeMisAndBsdfOnlyAgree) {
    const pathtrace::PathTraceScene pts = pathtrace::buildPathTraceScene(litScene(), nullptr, 1.0f, glm::vec3(0.1f));
    ASSERT_EQ(pts.lights.size(), 2u);
    // Looking down enough that the lamp itself is out of view (its edge pixels would add the same anti-aliasing
    // noise to both estimators).
    const scene::CameraView cam = lookAt(glm::vec3(0.0f, 1.5f, 4.0f), glm::vec3(0.0f), 0.8f);
    PtSettings settings;
    settings.maxDepth = 4;
    settings.spp = 256;
    const core::ImageRgba32f nee = pathtrace::renderReference(pts, cam, 16, 16, settings);
    settings.nee = false;
    settings.spp = 1024;
    const core::ImageRgba32f bsdf = pathtrace::renderReference(pts, cam, 16, 16, settings);
    const glm::dvec3 a = imageMean(nee), b = imageMean(bsdf);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(a[c], b[c], 0.03 * b[c]) << c;
    // Per pixel the two estimators also agree (noise of the BSDF-only image dominates the difference).
    EXPECT_LT(imageRmse(nee, bsdf), 0.15 * (b.x + b.y + b.z) / 3.0);
    // NEE+MIS is the better estimator at equal samples (the original's BSDF-only approach finds the lamp only
    // by chance; here the lamp is large, so the gain is moderate: measured 0.033 against 0.051).
    settings.spp = 32;
    settings.seed = 5;
    const core::ImageRgba32f bsdf32 = pathtrace::renderReference(pts, cam, 16, 16, settings);
    settings.nee = true;
    const core::ImageRgba32f nee32 = pathtrace::renderReference(pts, cam, 16, 16, settings);
    const double rmseNee = imageRmse(nee32, nee), rmseBsdf = imageRmse(bsdf32, nee);
    std::printf("lamp, 32 spp: RMSE NEE+MIS %.5f, BSDF only %.5f\n", rmseNee, rmseBsdf);
    EXPECT_LT(1.3 * rmseNee, rmseBsdf);
}

// The same under the default HDR sky alone (importance-sampled texels + MIS against BSDF sampling).
TEST(PtReference, HdrEnvironmentNeeMisAndBsdfOnlyAgree) {
    const std::filesystem::path file =
        std::filesystem::path(IDK_SHARED_DIR) / "environments" / "snow_field_puresky_1k.hdr";
    if (!std::filesystem::exists(file)) GTEST_SKIP() << file << " is missing";
    const core::ImageRgba32f hdr = core::readImage(file);
    scene::Scene s = litScene();
    s.instances.pop_back();  // no lamp: the sky alone
    const pathtrace::PathTraceScene pts = pathtrace::buildPathTraceScene(s, &hdr, 1.0f);
    ASSERT_EQ(pts.environmentDesc.selectProbability, 1.0f);
    const scene::CameraView cam = lookAt(glm::vec3(0.0f, 1.5f, 4.0f), glm::vec3(0.0f, 0.5f, 0.0f), 0.8f);
    PtSettings settings;
    settings.maxDepth = 4;
    settings.spp = 512;
    settings.seed = 99;
    const core::ImageRgba32f reference = pathtrace::renderReference(pts, cam, 16, 16, settings);
    settings.spp = 32;
    settings.seed = 1;
    const core::ImageRgba32f nee = pathtrace::renderReference(pts, cam, 16, 16, settings);
    settings.nee = false;
    const core::ImageRgba32f bsdf = pathtrace::renderReference(pts, cam, 16, 16, settings);
    settings.spp = 512;
    const core::ImageRgba32f bsdfHigh = pathtrace::renderReference(pts, cam, 16, 16, settings);
    const glm::dvec3 a = imageMean(reference), b = imageMean(bsdfHigh);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(a[c], b[c], 0.02 * b[c]) << c;
    // Both estimators at 32 spp against the NEE reference: comparable errors (on a smooth sky neither wins
    // by much: half the sky samples fall below the floor's horizon, cosine-weighted BSDF samples do not).
    const double rmseNee = imageRmse(nee, reference), rmseBsdf = imageRmse(bsdf, reference);
    std::printf("hdr sky, 32 spp: RMSE NEE+MIS %.5f, BSDF only %.5f\n", rmseNee, rmseBsdf);
    EXPECT_LT(rmseNee, 2.0 * rmseBsdf);
    EXPECT_LT(rmseBsdf, 2.0 * rmseNee);
}

TEST(PtReference, DegenerateSceneGivesFiniteImage) {
    scene::Scene s;
    // Zero-area emitters, a triangle with NaN normals, roughness 0 and 1, IOR 1, glass.
    scene::Material lamp = diffuse(glm::vec3(0.5f));
    lamp.emissive = glm::vec3(5.0f);
    addObject(s, quad({0, 1, 0}, {0, 1, 0}, {0, 1, 0}, {0, 1, 0}), lamp);
    addObject(s, quad({0, 1, 0}, {1, 1, 0}, {2, 1, 0}, {3, 1, 0}), lamp);
    scene::Primitive bad = quad({-2, 0, 2}, {2, 0, 2}, {2, 0, -2}, {-2, 0, -2});
    bad.normals.assign(4, glm::vec3(std::nanf("")));
    scene::Material mirror = diffuse(glm::vec3(1.0f));
    mirror.metallic = 1.0f;
    mirror.roughness = 0.0f;
    addObject(s, bad, mirror);
    scene::Material glass = diffuse(glm::vec3(1.0f));
    glass.transmission = 1.0f;
    glass.roughness = 0.0f;
    glass.thickness = 1.0f;
    glass.attenuationDistance = 0.5f;
    glass.attenuationColor = glm::vec3(0.5f, 0.8f, 0.9f);
    addObject(s, uvSphere(glm::vec3(0.0f, 0.5f, 0.0f), 0.5f, 8, 16), glass);
    scene::Material iorOne = diffuse(glm::vec3(0.8f));
    iorOne.ior = 1.0f;
    iorOne.transmission = 1.0f;
    iorOne.roughness = 1.0f;
    addObject(s, uvSphere(glm::vec3(1.2f, 0.5f, 0.0f), 0.4f, 8, 16), iorOne);
    scene::Light point;
    point.position = glm::vec3(0.0f, 0.5f, 0.0f);  // inside the glass sphere
    point.intensity = 10.0f;
    s.lights.push_back(point);
    const pathtrace::PathTraceScene pts = pathtrace::buildPathTraceScene(s, nullptr, 1.0f, glm::vec3(0.5f));
    const scene::CameraView cam = lookAt(glm::vec3(0.0f, 1.5f, 3.0f), glm::vec3(0.0f, 0.5f, 0.0f), 1.0f);
    PtSettings settings;
    settings.spp = 8;
    for (bool nee : {true, false}) {
        settings.nee = nee;
        const core::ImageRgba32f img = pathtrace::renderReference(pts, cam, 16, 16, settings);
        EXPECT_TRUE(imageFinite(img));
        EXPECT_GT(imageMean(img).x, 0.0);
    }
}

// Image orientation as the raster's (engine/scene/camera.hpp): row 0 is the top, column 0 the left. An emitter up
// and to the right of the view centre lands in the top-right quadrant.
TEST(PtReference, ImageOrientationMatchesTheCamera) {
    scene::Scene s;
    scene::Material lamp = diffuse(glm::vec3(0.0f));
    lamp.emissive = glm::vec3(1.0f);
    lamp.doubleSided = true;
    addObject(s, quad({0.5f, 0.5f, 0.0f}, {0.9f, 0.5f, 0.0f}, {0.9f, 0.9f, 0.0f}, {0.5f, 0.9f, 0.0f}), lamp);
    const pathtrace::PathTraceScene pts = pathtrace::buildPathTraceScene(s, nullptr, 1.0f);
    const scene::CameraView cam = lookAt(glm::vec3(0.0f, 0.0f, 3.0f), glm::vec3(0.0f), 0.8f);
    PtSettings settings;
    settings.spp = 1;
    const core::ImageRgba32f img = pathtrace::renderReference(pts, cam, 16, 16, settings);
    double quadrant[2][2] = {{0, 0}, {0, 0}};  // [top/bottom][left/right]
    for (uint32_t y = 0; y < 16; ++y)
        for (uint32_t x = 0; x < 16; ++x) quadrant[y / 8][x / 8] += img.pixels[(y * 16 + x) * 4];
    EXPECT_GT(quadrant[0][1], 1.0);
    EXPECT_EQ(quadrant[0][0] + quadrant[1][0] + quadrant[1][1], 0.0);
}

TEST(PtReference, DeterministicAcrossThreadCounts) {
    const pathtrace::PathTraceScene pts = pathtrace::buildPathTraceScene(litScene(), nullptr, 1.0f, glm::vec3(0.1f));
    const scene::CameraView cam = lookAt(glm::vec3(0.0f, 1.5f, 4.0f), glm::vec3(0.0f, 0.5f, 0.0f), 0.8f);
    PtSettings settings;
    settings.spp = 4;
    uint32_t calls = 0;
    const core::ImageRgba32f one = pathtrace::renderReference(pts, cam, 12, 10, settings, {}, 1);
    const core::ImageRgba32f two =
        pathtrace::renderReference(pts, cam, 12, 10, settings, [&](uint32_t, uint32_t total) {
            ++calls;
            EXPECT_EQ(total, 10u);
        }, 2);
    EXPECT_EQ(one.pixels, two.pixels);
    EXPECT_EQ(calls, 10u);
}

}  // namespace
}  // namespace idk::test
