// bunny_flight_test.cpp: the fly camera against a real, finely tessellated mesh (the Stanford bunny of the BVH
// tests, ../shared/scenes/bunny/bunny.bin, 69630 triangles): flight at top speed steered into it never
// brings the sphere nearer than its radius to any triangle (checked by brute force over every triangle). The
// DISABLED_ case measures the cost of a collision world build and of one camera step (no timing assertions):
//   build-*/bin/idk_unit_tools_tests --gtest_also_run_disabled_tests --gtest_filter='*BunnyFlight*'
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>

#include "bvh/raw_mesh.hpp"
#include "tools/camera_controller.hpp"

namespace idk::tools {
namespace {

struct Flight {
    CollisionWorld world;
    FlyCameraParams params;
    FlyCameraState start;
    glm::vec3 centre{0.0f};
    float size = 0.0f;  // bounds diagonal
    double buildMs = 0.0;
};

Flight bunnyFlight() {
    Flight f;
    std::vector<bvh::Triangle> tris = bvh::loadRawTriangles(std::string(IDK_SHARED_DIR) + "/scenes/bunny/bunny.bin");
    scene::Aabb bounds;
    for (const bvh::Triangle& t : tris) {
        bounds.extend(t.v0);
        bounds.extend(t.v1);
        bounds.extend(t.v2);
    }
    const auto t0 = std::chrono::steady_clock::now();
    f.world = CollisionWorld::fromTriangles(std::move(tris));
    f.buildMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    f.params = flyParamsForBounds(bounds);
    f.centre = bounds.centre();
    f.size = glm::length(bounds.max - bounds.min);
    f.params.radius = 0.02f * glm::length(bounds.max - bounds.min);
    // Start in front of the bunny, looking at it.
    f.start.position = bounds.centre() + glm::vec3(0.0f, 0.0f, 0.8f * glm::length(bounds.max - bounds.min));
    return f;
}

// Steers at the bunny (a random point near its centre) with W and Shift held, plus random strafing: the camera
// keeps slamming into the mesh at top speed and sliding over it.
FlyInput steerAtBunny(std::mt19937& rng, FlyCameraState& s, const Flight& f) {
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    const glm::vec3 target = f.centre + 0.3f * f.size * glm::vec3(u(rng), u(rng), u(rng));
    const glm::vec3 to = glm::normalize(target - s.position);
    s.yaw = std::atan2(to.x, -to.z);
    s.pitch = std::asin(std::clamp(to.y, -0.99f, 0.99f));
    FlyInput in;
    const unsigned bits = rng();
    in.forward = true;
    in.fast = true;
    in.left = (bits & 3) == 3;
    in.right = (bits & 12) == 12;
    in.up = (bits & 48) == 48;
    return in;
}

TEST(BunnyFlight, NeverCloserThanTheRadiusToAnyTriangle) {
    const Flight f = bunnyFlight();
    std::mt19937 rng(5);
    FlyCameraState s = f.start;
    int contacts = 0;
    for (int i = 0; i < 400; ++i) {
        const FlyInput in = steerAtBunny(rng, s, f);
        const glm::vec3 free = stepFlyCamera(s, in, 1.0f / 30.0f, f.params, nullptr).position;
        s = stepFlyCamera(s, in, 1.0f / 30.0f, f.params, &f.world);
        if (glm::length(s.position - free) > 1e-3f * f.params.radius) ++contacts;
        float nearest = 1e30f;
        for (const bvh::Triangle& t : f.world.triangles())
            nearest = std::min(nearest, glm::length(s.position - closestPointOnTriangle(t, s.position)));
        ASSERT_GE(nearest, f.params.radius * (1.0f - 1e-5f)) << "step " << i;
    }
    EXPECT_GT(contacts, 30);  // the flight really collided (45 of the 400 steps touch the bunny)
}

TEST(BunnyFlight, DISABLED_MeasureCost) {
    const Flight f = bunnyFlight();
    std::mt19937 rng(5);
    FlyCameraState s = f.start;
    const int steps = 20000;
    int contacts = 0;
    const auto t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < steps; ++i) {
        const FlyInput in = steerAtBunny(rng, s, f);
        const FlyCameraState before = s;
        s = stepFlyCamera(s, in, 1.0f / 30.0f, f.params, &f.world);
        // One extra collision-free step per step (cheap next to the collision) counts the contacts.
        contacts += glm::length(s.position - stepFlyCamera(before, in, 1.0f / 30.0f, f.params, nullptr).position) >
                    1e-3f * f.params.radius;
    }
    const double us = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count() / steps;
    std::printf("bunny (%zu triangles): collision world build %.1f ms, %.2f us per camera step (%d steps, %d with "
                "contact)\n", f.world.triangles().size(), f.buildMs, us, steps, contacts);
}

}  // namespace
}  // namespace idk::tools
