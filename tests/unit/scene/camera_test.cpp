// camera_test.cpp: camera math: Vulkan projections (depth 0 at near, 1 at far, y down), view matrices, the
// auto-fit distance (bounding sphere fills a 45 degree vertical FOV), the orbit formula and the default camera.
#include <cmath>

#include <gtest/gtest.h>

#include "scene/camera.hpp"
#include "scene/gltf_loader.hpp"
#include "test_files.hpp"

namespace idk::scene {
namespace {

glm::vec3 toNdc(const glm::mat4& m, const glm::vec3& p) {
    const glm::vec4 c = m * glm::vec4(p, 1.0f);
    return glm::vec3(c) / c.w;
}

TEST(Projection, PerspectiveMapsNearToZeroAndFarToOne) {
    const glm::mat4 p = perspectiveVulkan(glm::radians(60.0f), 1.5f, 0.1f, 100.0f);
    EXPECT_NEAR(toNdc(p, {0, 0, -0.1f}).z, 0.0f, 1e-6f);
    EXPECT_NEAR(toNdc(p, {0, 0, -100.0f}).z, 1.0f, 1e-6f);
    const float mid = toNdc(p, {0, 0, -1.0f}).z;
    EXPECT_GT(mid, 0.0f);
    EXPECT_LT(mid, 1.0f);
}

TEST(Projection, PerspectiveYPointsDownAndEdgesMapToOne) {
    const float yfov = glm::radians(60.0f), aspect = 1.5f;
    const glm::mat4 p = perspectiveVulkan(yfov, aspect, 0.1f, 100.0f);
    const float h = std::tan(0.5f * yfov);  // half height at distance 1
    const glm::vec3 top = toNdc(p, {0, h, -1.0f});
    const glm::vec3 right = toNdc(p, {h * aspect, 0, -1.0f});
    EXPECT_NEAR(top.y, -1.0f, 1e-6f);   // view-space up is NDC -1: the top row of the framebuffer
    EXPECT_NEAR(right.x, 1.0f, 1e-6f);  // view-space right stays right
}

TEST(Projection, InfinitePerspective) {
    const glm::mat4 p = perspectiveVulkan(glm::radians(45.0f), 1.0f, 0.5f, 0.0f);
    EXPECT_NEAR(toNdc(p, {0, 0, -0.5f}).z, 0.0f, 1e-6f);
    const float far = toNdc(p, {0, 0, -1.0e6f}).z;
    EXPECT_LE(far, 1.0f);
    EXPECT_GT(far, 0.99999f);
}

TEST(Projection, OrthographicMapsNearToZeroAndFarToOne) {
    const glm::mat4 p = orthographicVulkan(2.0f, 3.0f, 1.0f, 11.0f);
    EXPECT_NEAR(toNdc(p, {0, 0, -1.0f}).z, 0.0f, 1e-6f);
    EXPECT_NEAR(toNdc(p, {0, 0, -11.0f}).z, 1.0f, 1e-6f);
    EXPECT_NEAR(toNdc(p, {2.0f, 3.0f, -5.0f}).x, 1.0f, 1e-6f);
    EXPECT_NEAR(toNdc(p, {2.0f, 3.0f, -5.0f}).y, -1.0f, 1e-6f);
}

TEST(Projection, CameraAspectOverridesTheViewport) {
    CameraView c;
    c.aspectRatio = 2.0f;
    EXPECT_EQ(projectionMatrix(c, 1.0f)[0][0], perspectiveVulkan(c.yfov, 2.0f, c.znear, c.zfar)[0][0]);
    c.aspectRatio = 0.0f;
    EXPECT_EQ(projectionMatrix(c, 1.25f)[0][0], perspectiveVulkan(c.yfov, 1.25f, c.znear, c.zfar)[0][0]);
}

TEST(View, LooksDownMinusZ) {
    CameraView c;
    c.position = {1, 2, 5};
    const glm::mat4 v = viewMatrix(c);
    const glm::vec3 p = glm::vec3(v * glm::vec4(1, 2, 0, 1));
    EXPECT_NEAR(p.x, 0.0f, 1e-6f);
    EXPECT_NEAR(p.y, 0.0f, 1e-6f);
    EXPECT_NEAR(p.z, -5.0f, 1e-6f);
}

TEST(AutoFit, DistanceIsRadiusOverSinHalfFov) {
    EXPECT_NEAR(autoFitDistance(1.0f), 1.0f / std::sin(glm::radians(22.5f)), 1e-5f);
    EXPECT_NEAR(autoFitDistance(1.0f), 2.6131259f, 1e-5f);
    EXPECT_NEAR(autoFitDistance(3.0f, glm::radians(90.0f)), 3.0f * std::sqrt(2.0f), 1e-5f);
}

TEST(AutoFit, BoundingSphereTouchesTheTopOfTheImage) {
    Aabb box;
    box.extend({-1, -2, -3});
    box.extend({3, 2, 1});
    const CameraView c = autoFitCamera(box);
    const float r = 0.5f * glm::length(box.max - box.min);
    const float d = r / std::sin(glm::radians(22.5f));
    EXPECT_NEAR(glm::distance(c.position, box.centre() + glm::vec3(0, 0, d)), 0.0f, 1e-5f);
    EXPECT_EQ(c.forward, glm::vec3(0, 0, -1));
    EXPECT_NEAR(c.yfov, glm::radians(45.0f), 1e-6f);
    // The tangent point of the view cone's top plane on the sphere projects to the top edge (NDC y = -1).
    const float half = 0.5f * c.yfov;
    const glm::vec3 tangent = c.position + std::sqrt(d * d - r * r) * glm::vec3(0, std::sin(half), -std::cos(half));
    EXPECT_NEAR(glm::distance(tangent, box.centre()), r, 1e-4f);
    const glm::mat4 vp = projectionMatrix(c, 1.0f) * viewMatrix(c);
    const glm::vec3 ndc = toNdc(vp, tangent);
    EXPECT_NEAR(ndc.y, -1.0f, 1e-4f);
    EXPECT_GT(ndc.z, 0.0f);  // inside the depth range
    EXPECT_LT(ndc.z, 1.0f);
    // The far side of the sphere is in front of the far plane and the near side behind the near plane.
    EXPECT_LT(c.znear, d - r);
    EXPECT_GT(c.zfar, d + r);
}

TEST(AutoFit, EmptyBoundsUseAUnitSphere) {
    const CameraView c = autoFitCamera(Aabb{});
    EXPECT_NEAR(c.position.z, autoFitDistance(1.0f), 1e-5f);
    EXPECT_GT(c.znear, 0.0f);
}

TEST(Orbit, FormulaFromTheScenesReadme) {
    const glm::vec3 target(1, 2, 3);
    CameraView c = orbitCamera(target, 4.0f);  // defaults theta 0, phi 90 degrees: on +Z
    EXPECT_NEAR(glm::distance(c.position, target + glm::vec3(0, 0, 4)), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::distance(c.forward, glm::vec3(0, 0, -1)), 0.0f, 1e-6f);
    EXPECT_NEAR(c.yfov, glm::radians(45.0f), 1e-6f);

    const float theta = glm::radians(30.0f), phi = glm::radians(60.0f);
    c = orbitCamera(target, 2.0f, theta, phi);
    const glm::vec3 expected =
        target + 2.0f * glm::vec3(std::sin(phi) * std::sin(theta), std::cos(phi), std::sin(phi) * std::cos(theta));
    EXPECT_NEAR(glm::distance(c.position, expected), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::distance(c.position + 2.0f * c.forward, target), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(c.up, c.forward), 0.0f, 1e-6f);
    EXPECT_GT(c.up.y, 0.0f);

    c = orbitCamera(target, 2.0f, glm::radians(90.0f), glm::radians(90.0f));  // on +X
    EXPECT_NEAR(glm::distance(c.position, target + glm::vec3(2, 0, 0)), 0.0f, 1e-5f);
}

TEST(Orbit, StraightAboveStaysFinite) {
    const CameraView c = orbitCamera(glm::vec3(0), 1.0f, 0.0f, 0.0f);
    EXPECT_NEAR(glm::distance(c.position, glm::vec3(0, 1, 0)), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::length(c.up), 1.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(c.up, c.forward), 0.0f, 1e-5f);
    const glm::mat4 v = viewMatrix(c);
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) EXPECT_TRUE(std::isfinite(v[i][j]));
}

TEST(DefaultCamera, CornellBoxUsesItsPublishedCameraAndSeesTheOpening) {
    const Scene s = loadGltf(test::sourceDir() / "scenes/cornell_box.gltf");
    const CameraView c = defaultCamera(s);
    EXPECT_NEAR(glm::distance(c.position, glm::vec3(-0.278f, 0.273f, 0.8f)), 0.0f, 1e-6f);
    EXPECT_NEAR(c.yfov, 2.0f * std::atan(12.5f / 35.0f), 1e-6f);
    const glm::mat4 vp = projectionMatrix(c, 1.0f) * viewMatrix(c);
    // The four corners of the open front (z = 0) are inside the image and the depth range.
    for (const glm::vec3 corner :
         {glm::vec3(0, 0, 0), glm::vec3(-0.556f, 0, 0), glm::vec3(0, 0.5488f, 0), glm::vec3(-0.556f, 0.5488f, 0)}) {
        const glm::vec3 ndc = toNdc(vp, corner);
        EXPECT_LT(std::abs(ndc.x), 1.0f);
        EXPECT_LT(std::abs(ndc.y), 1.0f);
        EXPECT_GT(ndc.z, 0.0f);
        EXPECT_LT(ndc.z, 1.0f);
    }
    // Green wall (x = 0) on the right of the image, floor at the bottom (NDC y > 0 is down).
    EXPECT_GT(toNdc(vp, {0.0f, 0.27f, -0.3f}).x, 0.5f);
    EXPECT_GT(toNdc(vp, {-0.278f, 0.0f, -0.3f}).y, 0.5f);
}

TEST(DefaultCamera, AutoFitWithoutAFileCamera) {
    const Scene s = loadGltf(test::sharedScene("Box/glTF-Binary/Box.glb"));
    const CameraView c = defaultCamera(s);
    EXPECT_NEAR(c.position.z, autoFitDistance(std::sqrt(3.0f) * 0.5f), 1e-4f);
    EXPECT_NEAR(c.position.x, 0.0f, 1e-5f);
}

}  // namespace
}  // namespace idk::scene
