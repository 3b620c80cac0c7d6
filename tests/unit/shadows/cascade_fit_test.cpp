// cascade_fit_test.cpp: the directional-cascade fit (render/shadow_cascades.hpp) without a GPU:
//  * coverage: every point of the view frustum up to the shadow distance lies in some cascade's map, inside the
//    lookup's filter margin and the depth range, for perspective and orthographic cameras in many orientations;
//  * stability: moving or turning the camera keeps each cascade's texel size and moves a fixed world point by a
//    whole number of texels in the map (texel snapping), so the maps do not shimmer;
//  * spot maps hold their whole cone inside the margin.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "render/shadow_cascades.hpp"
#include "shared/shadow_types.h"

namespace idk::render {
namespace {

constexpr uint32_t kResolution = 1024;

scene::Aabb box(glm::vec3 lo, glm::vec3 hi) {
    scene::Aabb b;
    b.extend(lo);
    b.extend(hi);
    return b;
}

scene::CameraView randomCamera(std::mt19937& rng, bool ortho) {
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    scene::CameraView c;
    c.position = glm::vec3(u(rng), u(rng), u(rng)) * 20.0f;
    glm::vec3 f;
    do f = glm::vec3(u(rng), u(rng), u(rng));
    while (glm::length(f) < 0.2f || std::abs(glm::normalize(f).y) > 0.95f);
    c.forward = glm::normalize(f);
    c.up = glm::normalize(glm::cross(glm::cross(c.forward, glm::vec3(0, 1, 0)), c.forward));
    c.type = ortho ? scene::CameraType::Orthographic : scene::CameraType::Perspective;
    c.yfov = 0.4f + 1.2f * (u(rng) * 0.5f + 0.5f);
    c.znear = 0.05f;
    c.zfar = 500.0f;
    c.xmag = 8.0f;
    c.ymag = 4.5f;
    return c;
}

// Whether world point p lies inside cascade c's map with the lookup margin, and (where depth) inside its depth
// range. Points outside the scene box need no depth: nothing is there to receive a shadow.
bool inside(const ShadowProjection& c, glm::vec3 p, bool depth = true) {
    glm::dvec4 clip = glm::dmat4(c.viewProjection) * glm::dvec4(glm::dvec3(p), 1.0);
    glm::dvec3 ndc = glm::dvec3(clip) / clip.w;
    double m = gpu::kShadowMapMargin / kResolution - 1e-5;  // a spot's rim lies exactly on the margin
    glm::dvec2 uv = glm::dvec2(ndc) * 0.5 + 0.5;
    return uv.x >= m && uv.y >= m && uv.x <= 1.0 - m && uv.y <= 1.0 - m && (!depth || (ndc.z >= 0.0 && ndc.z <= 1.0));
}

TEST(CascadeFit, CascadesCoverTheWholeViewFrustumUpToTheShadowDistance) {
    std::mt19937 rng(7);
    const scene::Aabb scene = box(glm::vec3(-60.0f), glm::vec3(60.0f));
    uint32_t tested = 0;
    for (int trial = 0; trial < 40; ++trial) {
        const bool ortho = trial % 4 == 3;
        scene::CameraView cam = randomCamera(rng, ortho);
        std::uniform_real_distribution<float> u(-1.0f, 1.0f);
        glm::vec3 dir = glm::normalize(glm::vec3(u(rng), -1.0f, u(rng)));
        const float aspect = 16.0f / 9.0f;
        for (uint32_t count = 1; count <= 4; ++count) {
            const float maxDistance = trial % 2 ? 0.0f : 40.0f;
            auto cascades = directionalCascades(cam, aspect, scene, dir, count, kResolution, maxDistance);
            ASSERT_EQ(cascades.size(), count);
            const float far = cascadeShadowDistance(cam, scene, maxDistance);
            EXPECT_FLOAT_EQ(cascades.back().splitFar, far);
            const glm::vec3 right = glm::cross(cam.forward, cam.up);
            for (int k = 0; k <= 10; ++k) {
                float z = cam.znear + (far - cam.znear) * float(k) / 10.0f;  // slice boundaries and between
                for (int a = 0; a <= 4; ++a) {
                    for (int b = 0; b <= 4; ++b) {
                        float sx = a / 2.0f - 1.0f, sy = b / 2.0f - 1.0f;  // corners, edges and centre
                        float hx = ortho ? cam.xmag : std::tan(0.5f * cam.yfov) * aspect * z;
                        float hy = ortho ? cam.ymag : std::tan(0.5f * cam.yfov) * z;
                        glm::vec3 p = cam.position + cam.forward * z + right * (sx * hx) + cam.up * (sy * hy);
                        bool covered = false;
                        const bool inBox = glm::all(glm::greaterThanEqual(p, scene.min)) &&
                                           glm::all(glm::lessThanEqual(p, scene.max));
                        for (const ShadowProjection& c : cascades) covered = covered || inside(c, p, inBox);
                        ++tested;
                        ASSERT_TRUE(covered) << "trial " << trial << " count " << count << " depth " << z;
                    }
                }
            }
        }
    }
    EXPECT_GT(tested, 40000u);
}

TEST(CascadeFit, CameraMotionMovesTheMapsByWholeTexelsOnly) {
    const scene::Aabb scene = box(glm::vec3(-30.0f), glm::vec3(30.0f));
    const glm::vec3 dir = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
    scene::CameraView cam;
    cam.position = {1.0f, 2.0f, 3.0f};
    cam.forward = glm::normalize(glm::vec3(1.0f, -0.2f, -1.0f));
    cam.up = glm::normalize(glm::cross(glm::cross(cam.forward, glm::vec3(0, 1, 0)), cam.forward));
    cam.zfar = 40.0f;  // the far plane, not the scene, sets the distance: it stays fixed while the camera moves
    auto before = directionalCascades(cam, 1.5f, scene, dir, 4, kResolution, 0.0f);
    const glm::vec3 probe(0.37f, 0.11f, -0.52f);
    for (int step = 1; step <= 8; ++step) {
        scene::CameraView moved = cam;
        moved.position += glm::vec3(0.0137f, -0.0071f, 0.0093f) * float(step);
        float a = 0.01f * float(step);  // and turned about y
        moved.forward = glm::normalize(glm::vec3(std::cos(a) * cam.forward.x - std::sin(a) * cam.forward.z,
                                                 cam.forward.y,
                                                 std::sin(a) * cam.forward.x + std::cos(a) * cam.forward.z));
        moved.up = glm::normalize(glm::cross(glm::cross(moved.forward, glm::vec3(0, 1, 0)), moved.forward));
        auto after = directionalCascades(moved, 1.5f, scene, dir, 4, kResolution, 0.0f);
        for (size_t c = 0; c < 4; ++c) {
            ASSERT_FLOAT_EQ(after[c].texelScale, before[c].texelScale) << "the radius depends on the slice only";
            glm::dvec4 p0 = glm::dmat4(before[c].viewProjection) * glm::dvec4(glm::dvec3(probe), 1.0);
            glm::dvec4 p1 = glm::dmat4(after[c].viewProjection) * glm::dvec4(glm::dvec3(probe), 1.0);
            for (int axis = 0; axis < 2; ++axis) {
                double texels = (p1[axis] - p0[axis]) * 0.5 * kResolution;
                EXPECT_NEAR(texels, std::round(texels), 2e-3) << "cascade " << c << " step " << step;
            }
            EXPECT_NEAR(p1.z, p0.z, 1e-6) << "the depth range comes from the scene box";
        }
    }
}

TEST(CascadeFit, SpotMapHoldsItsWholeConeInsideTheMargin) {
    const glm::vec3 pos(1.0f, 4.0f, -2.0f), dir = glm::normalize(glm::vec3(0.2f, -1.0f, 0.4f));
    for (float outer : {0.2f, 0.7f, 1.0f, kMaxSpotMapHalfAngle}) {
        ShadowProjection p = spotShadowProjection(pos, dir, outer, {0.01f, 20.0f}, kResolution);
        EXPECT_TRUE(p.perspective);
        // Rays on the cone's rim, at several distances.
        glm::vec3 a = glm::normalize(glm::cross(dir, glm::vec3(1, 0, 0))), b = glm::cross(dir, a);
        for (int k = 0; k < 16; ++k) {
            float phi = 6.2831853f * float(k) / 16.0f;
            glm::vec3 rim = std::cos(outer) * dir + std::sin(outer) * (std::cos(phi) * a + std::sin(phi) * b);
            for (float t : {0.5f, 5.0f, 15.0f}) {
                glm::vec4 clip = p.viewProjection * glm::vec4(pos + rim * t, 1.0f);
                EXPECT_TRUE(inside(p, pos + rim * t)) << outer << " " << phi << " " << t << " ndc " << clip.x / clip.w
                                                      << " " << clip.y / clip.w << " " << clip.z / clip.w;
            }
        }
    }
    EXPECT_NEAR(spotOuterAngle(1.0f / (std::cos(0.3f) - std::cos(0.6f)),
                               -std::cos(0.6f) / (std::cos(0.3f) - std::cos(0.6f))),
                0.6f, 1e-5f);
}

}  // namespace
}  // namespace idk::render
