// collision_test.cpp: swept-sphere collide-and-slide (tools/collision.hpp) against analytic expectations: the
// sweep kernel against a brute-force oracle (the distance to a triangle is convex along the path, so its first
// crossing of the radius is found by ternary search + bisection), stopping at a wall at radius + skin and sliding
// along it, corners of two and three planes, thin walls at any speed, rest without jitter, internal edges of a
// tessellated floor, degenerate triangles, bouncing and ray picking.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "tools/collision.hpp"
#include "tools/sphere_sweep.hpp"

namespace idk::tools {
namespace {

constexpr float kSkin = 1e-3f;

// Two triangles spanning the quad corner + s * u + t * v, s, t in [0, 1].
void addQuad(std::vector<bvh::Triangle>& out, glm::vec3 corner, glm::vec3 u, glm::vec3 v) {
    out.push_back({corner, corner + u, corner + u + v});
    out.push_back({corner, corner + u + v, corner + v});
}

// A big wall in the plane z = 0.
CollisionWorld wallWorld() {
    std::vector<bvh::Triangle> tris;
    addQuad(tris, {-50, -50, 0}, {100, 0, 0}, {0, 100, 0});
    return CollisionWorld::fromTriangles(tris);
}

double distanceTo(const bvh::Triangle& tri, const glm::dvec3& p) {
    return glm::length(p - closestPointOnTriangle(glm::dvec3(tri.v0), glm::dvec3(tri.v1), glm::dvec3(tri.v2), p));
}

TEST(SweepKernel, MatchesConvexDistanceOracle) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    int hits = 0, misses = 0, startTouching = 0;
    for (int trial = 0; trial < 10000; ++trial) {
        const bvh::Triangle tri{glm::vec3(u(rng), u(rng), u(rng)), glm::vec3(u(rng), u(rng), u(rng)),
                                glm::vec3(u(rng), u(rng), u(rng))};
        const glm::dvec3 c(2 * u(rng), 2 * u(rng), 2 * u(rng)), d(3 * u(rng), 3 * u(rng), 3 * u(rng));
        const double radius = 0.05 + 0.3 * (u(rng) + 1.0);
        auto dist = [&](double t) { return distanceTo(tri, c + t * d); };
        // Oracle: the minimum of the convex distance on [0, 1], then the first crossing before it.
        double lo = 0.0, hi = 1.0;
        for (int i = 0; i < 200; ++i) {
            const double m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
            if (dist(m1) < dist(m2)) {
                hi = m2;
            } else {
                lo = m1;
            }
        }
        const double tMin = 0.5 * (lo + hi);
        const std::optional<SweepContact> got =
            sweepSphereTriangle(c, radius, d, glm::dvec3(tri.v0), glm::dvec3(tri.v1), glm::dvec3(tri.v2));
        if (dist(0.0) < radius) {
            ++startTouching;
            const bool goingIn = dist(1e-6) < dist(0.0);
            EXPECT_EQ(got.has_value(), goingIn) << "trial " << trial;
            if (got) {
                EXPECT_EQ(got->t, 0.0);
            }
            continue;
        }
        if (dist(tMin) > radius + 1e-9) {
            ++misses;
            EXPECT_FALSE(got.has_value()) << "trial " << trial << ": closest approach " << dist(tMin) << " > " << radius;
            continue;
        }
        if (dist(tMin) > radius - 1e-6) continue;  // grazing within rounding: either answer is right
        ++hits;
        double a = 0.0, b = tMin;
        for (int i = 0; i < 200; ++i) {
            const double mid = 0.5 * (a + b);
            if (dist(mid) > radius) {
                a = mid;
            } else {
                b = mid;
            }
        }
        ASSERT_TRUE(got.has_value()) << "trial " << trial << ": oracle contact at t = " << a;
        EXPECT_NEAR(got->t, a, 1e-7) << "trial " << trial;
        EXPECT_NEAR(glm::length(got->normal), 1.0, 1e-9);
        // The normal points from the surface to the centre at contact.
        const glm::dvec3 at = c + got->t * d;
        const glm::dvec3 q = closestPointOnTriangle(glm::dvec3(tri.v0), glm::dvec3(tri.v1), glm::dvec3(tri.v2), at);
        EXPECT_NEAR(glm::dot(got->normal, glm::normalize(at - q)), 1.0, 1e-6) << "trial " << trial;
    }
    EXPECT_GT(hits, 300);
    EXPECT_GT(misses, 300);
    EXPECT_GT(startTouching, 100);
}

TEST(MoveSphere, StopsAtRadiusFromWallAndSlides) {
    const CollisionWorld world = wallWorld();
    const float r = 0.5f;
    // Straight in: stops at radius + skin in front of the wall.
    glm::vec3 p = moveSphere(world, {0, 1, 3}, r, {0, 0, -10});
    EXPECT_NEAR(p.z, r + kSkin, 1e-5);
    EXPECT_NEAR(p.x, 0.0f, 1e-6);
    // At an angle: the motion along the wall survives in full (first contact, then slide).
    SphereMoveResult res = moveSphereDetailed(world, {0, 1, 1}, r, {1, 0, -2});
    EXPECT_NEAR(res.position.x, 1.0f, 1e-5);
    EXPECT_NEAR(res.position.y, 1.0f, 1e-6);
    EXPECT_NEAR(res.position.z, r + kSkin, 1e-5);
    ASSERT_EQ(res.normals.size(), 1u);
    EXPECT_NEAR(res.normals[0].z, 1.0f, 1e-6);
    // From behind (triangles are double-sided).
    p = moveSphere(world, {0, 1, -3}, r, {0, 0, 10});
    EXPECT_NEAR(p.z, -(r + kSkin), 1e-5);
}

TEST(MoveSphere, NoTunnellingThroughAThinWallAtAnySpeed) {
    const CollisionWorld world = wallWorld();
    for (float speed : {1.0f, 50.0f, 1e3f, 1e5f}) {
        for (glm::vec3 dir : {glm::vec3(0, 0, -1), glm::normalize(glm::vec3(3, 1, -0.2f)), glm::normalize(glm::vec3(-1, 2, -1))}) {
            const glm::vec3 p = moveSphere(world, {0.3f, 0.7f, 0.8f}, 0.25f, dir * speed);
            EXPECT_GE(p.z, 0.25f) << "speed " << speed;
        }
    }
    // The fly camera's top speed (Shift: 5 * 30 m/s^2 against the drag, ~47 m/s) at 10 fps, many frames, a
    // sphere much smaller than one frame's travel, zig-zagging through the wall's plane.
    glm::vec3 p(0, 0, 2);
    for (int frame = 0; frame < 200; ++frame) {
        const glm::vec3 v = frame % 2 ? glm::vec3(3, 1, 47) : glm::vec3(-2, -1, -47);
        p = moveSphere(world, p, 0.05f, v * 0.1f);
        ASSERT_GE(p.z, 0.05f) << "frame " << frame;
    }
}

TEST(MoveSphere, AtRestAndPushingIntoAWallDoesNotJitter) {
    const CollisionWorld world = wallWorld();
    glm::vec3 p = moveSphere(world, {0, 0, 2}, 0.5f, {0, 0, -5});
    // Zero motion: exactly where it was.
    EXPECT_EQ(moveSphere(world, p, 0.5f, glm::vec3(0.0f)), p);
    // Pushing straight in every frame: after settling, the position never changes.
    for (int i = 0; i < 3; ++i) p = moveSphere(world, p, 0.5f, {0, 0, -0.3f});
    for (int i = 0; i < 100; ++i) {
        const glm::vec3 next = moveSphere(world, p, 0.5f, {0, 0, -0.3f});
        ASSERT_EQ(next, p) << "frame " << i;
    }
    EXPECT_NEAR(p.z, 0.5f + kSkin, 1e-5);
}

TEST(MoveSphere, CornersOfTwoAndThreePlanesAreStable) {
    // Floor y = 0, walls x = 0 and z = 0: an open box corner at the origin.
    std::vector<bvh::Triangle> tris;
    addQuad(tris, {0, 0, 0}, {10, 0, 0}, {0, 0, 10});
    addQuad(tris, {0, 0, 0}, {0, 10, 0}, {0, 0, 10});
    addQuad(tris, {0, 0, 0}, {10, 0, 0}, {0, 10, 0});
    const CollisionWorld world = CollisionWorld::fromTriangles(tris);
    const float r = 0.4f;
    for (glm::vec3 push : {glm::vec3(-1, 0, -1), glm::vec3(-1, -1, -1), glm::vec3(-0.2f, -1, -3)}) {
        glm::vec3 p(3, 2, 3);
        for (int i = 0; i < 20; ++i) p = moveSphere(world, p, r, push);
        for (int i = 0; i < 50; ++i) {
            const glm::vec3 next = moveSphere(world, p, r, push);
            ASSERT_EQ(next, p) << "push " << push.x << "," << push.y << "," << push.z << " frame " << i;
        }
        EXPECT_NEAR(p.x, r + kSkin, 1e-4);
        EXPECT_NEAR(p.z, r + kSkin, 1e-4);
        if (push.y < 0.0f) {
            EXPECT_NEAR(p.y, r + kSkin, 1e-4);
        } else {
            EXPECT_NEAR(p.y, 2.0f, 1e-5);  // two walls: the crease is vertical, nothing pushes it along
        }
    }
    // An acute V (60 degrees between the walls): pushed into the crease, it wedges and stays, inside both.
    std::vector<bvh::Triangle> vee;
    const glm::vec3 a(std::cos(0.5236f), 0, std::sin(0.5236f)), b(std::cos(0.5236f), 0, -std::sin(0.5236f));
    addQuad(vee, {0, -5, 0}, a * 20.0f, {0, 10, 0});
    addQuad(vee, {0, -5, 0}, b * 20.0f, {0, 10, 0});
    const CollisionWorld wedge = CollisionWorld::fromTriangles(vee);
    glm::vec3 p(8, 0, 0.5f);
    for (int i = 0; i < 30; ++i) p = moveSphere(wedge, p, 0.5f, {-1.0f, 0.0f, 0.3f});
    const glm::vec3 settled = p;
    for (int i = 0; i < 30; ++i) p = moveSphere(wedge, p, 0.5f, {-1.0f, 0.0f, 0.3f});
    EXPECT_EQ(p, settled);
    // Distance to each wall plane (normals of the two half-planes through the y axis).
    const glm::vec3 na = glm::normalize(glm::cross(a, glm::vec3(0, 1, 0))), nb = glm::normalize(glm::cross(glm::vec3(0, 1, 0), b));
    EXPECT_GE(std::abs(glm::dot(p, na)), 0.5f);
    EXPECT_GE(std::abs(glm::dot(p, nb)), 0.5f);
    EXPECT_NEAR(p.x, 1.0f + 2e-3f, 5e-3f);  // the sphere touching both walls: r / sin(30 degrees) from the apex
}

TEST(MoveSphere, SlidesAcrossATessellatedFloorWithoutCatchingOnInternalEdges) {
    std::vector<bvh::Triangle> tris;
    for (int i = 0; i < 20; ++i)
        for (int j = 0; j < 20; ++j) addQuad(tris, {i - 10.0f, 0, j - 10.0f}, {1, 0, 0}, {0, 0, 1});
    const CollisionWorld world = CollisionWorld::fromTriangles(tris);
    glm::vec3 p = moveSphere(world, {-8.7f, 3, -8.3f}, 0.3f, {0, -5, 0});
    EXPECT_NEAR(p.y, 0.3f + kSkin, 1e-5);
    // Diagonally across many triangle edges, pressed slightly down: all of the horizontal motion happens.
    const glm::vec3 q = moveSphere(world, p, 0.3f, {15.1f, -0.2f, 13.7f});
    EXPECT_NEAR(q.x, p.x + 15.1f, 1e-4);
    EXPECT_NEAR(q.z, p.z + 13.7f, 1e-4);
    EXPECT_NEAR(q.y, p.y, 1e-5);
}

TEST(MoveSphere, DegenerateTrianglesCollideAsTheirSegmentsAndPoints) {
    std::vector<bvh::Triangle> tris;
    tris.push_back({{-5, 0, 0}, {0, 0, 0}, {5, 0, 0}});  // collinear: the segment x in [-5, 5] on the x axis
    tris.push_back({{0, 0, 10}, {0, 0, 10}, {0, 0, 10}});  // a point
    const CollisionWorld world = CollisionWorld::fromTriangles(tris);
    const glm::vec3 p = moveSphere(world, {1, 3, 0}, 0.5f, {0, -10, 0});
    EXPECT_NEAR(p.y, 0.5f + kSkin, 1e-5);
    EXPECT_NEAR(p.x, 1.0f, 1e-6);
    const glm::vec3 q = moveSphere(world, {0, 0, 15}, 0.5f, {0, 0, -10});
    EXPECT_NEAR(q.z, 10.5f + kSkin, 1e-5);
    // Past the segment's end: no contact, the full motion.
    const glm::vec3 s = moveSphere(world, {6, 3, 0}, 0.5f, {0, -10, 0});
    EXPECT_EQ(s, glm::vec3(6, -7, 0));
    // Non-finite input and non-finite triangles never produce NaN.
    tris.push_back({{NAN, 0, 0}, {1, 1, 1}, {2, 2, 2}});
    const CollisionWorld withNan = CollisionWorld::fromTriangles(tris);
    const glm::vec3 t = moveSphere(withNan, {1, 3, 0}, 0.5f, {0, -10, 0});
    EXPECT_TRUE(std::isfinite(t.x) && std::isfinite(t.y) && std::isfinite(t.z));
    EXPECT_EQ(moveSphere(withNan, {1, 3, 0}, 0.5f, {NAN, 0, 0}), glm::vec3(1, 3, 0));
}

TEST(MoveSphere, StartingInsideGeometryIsPushedOut) {
    const CollisionWorld world = wallWorld();
    const SphereMoveResult res = moveSphereDetailed(world, {0, 0, 0.2f}, 0.5f, glm::vec3(0.0f));
    EXPECT_TRUE(res.pushedOut);
    EXPECT_NEAR(res.position.z, 0.5f + kSkin, 1e-5);
}

TEST(ClipToPlanes, RemovesOnlyTheComponentsIntoThePlanes) {
    const std::vector<glm::vec3> floor{{0, 1, 0}};
    EXPECT_EQ(clipToPlanes({1, -2, 3}, floor), glm::vec3(1, 0, 3));
    EXPECT_EQ(clipToPlanes({1, 2, 3}, floor), glm::vec3(1, 2, 3));
    const std::vector<glm::vec3> crease{{0, 1, 0}, {1, 0, 0}};
    const glm::vec3 c = clipToPlanes({-1, -2, 3}, crease);
    EXPECT_NEAR(glm::length(c - glm::vec3(0, 0, 3)), 0.0f, 1e-6);
    const std::vector<glm::vec3> corner{{0, 1, 0}, {1, 0, 0}, {0, 0, 1}};
    EXPECT_EQ(clipToPlanes({-1, -2, -3}, corner), glm::vec3(0.0f));
}

TEST(BouncingSphere, ReflectsOffAWallKeepingItsSpeed) {
    const CollisionWorld world = wallWorld();
    BouncingSphere s{{0, 0, 1}, {1, 0, -4}, 0.2f};
    s = stepBouncingSphere(world, s, 1.0f);
    EXPECT_NEAR(s.velocity.x, 1.0f, 1e-6);
    EXPECT_NEAR(s.velocity.z, 4.0f, 1e-6);
    // Contact after 0.8 of the 4 in z (t = 0.2), a skin's step back out, then the remaining 3.2 mirrored.
    EXPECT_NEAR(s.center.z, 0.2f + kSkin + 3.2f, 1e-4);
    EXPECT_NEAR(s.center.x, 1.0f, 1e-5);
}

TEST(BouncingSphere, EqualSpheresExchangeTheirNormalVelocities) {
    BouncingSphere a{{0, 0, 0}, {2, 1, 0}, 0.5f}, b{{0.8f, 0, 0}, {-1, 0, 3}, 0.5f};
    ASSERT_TRUE(collideSpheres(a, b));
    EXPECT_NEAR(glm::length(b.center - a.center), 1.0f, 1e-6f);  // just touching
    EXPECT_NEAR(a.center.x + b.center.x, 0.8f, 1e-6f);             // symmetric push
    EXPECT_EQ(a.velocity, glm::vec3(-1, 1, 0));                    // x components swapped, the rest kept
    EXPECT_EQ(b.velocity, glm::vec3(2, 0, 3));
    // Separating spheres keep their velocities; apart ones do not touch.
    BouncingSphere c{{0, 0, 0}, {-1, 0, 0}, 0.5f}, d{{0.9f, 0, 0}, {1, 0, 0}, 0.5f};
    EXPECT_TRUE(collideSpheres(c, d));
    EXPECT_EQ(c.velocity, glm::vec3(-1, 0, 0));
    BouncingSphere e{{0, 0, 0}, {1, 0, 0}, 0.5f}, f{{2, 0, 0}, {-1, 0, 0}, 0.5f};
    EXPECT_FALSE(collideSpheres(e, f));
    EXPECT_EQ(e.velocity, glm::vec3(1, 0, 0));
}

TEST(CastRay, FindsTheNearestTriangleAndItsInstance) {
    std::vector<bvh::Triangle> tris;
    addQuad(tris, {-1, -1, -5}, {2, 0, 0}, {0, 2, 0});
    addQuad(tris, {-1, -1, -2}, {2, 0, 0}, {0, 2, 0});
    const CollisionWorld world = CollisionWorld::fromTriangles(tris, {7, 7, 9, 9});
    const std::optional<RayHit> hit = castRay(world, {0.1f, 0.2f, 0}, {0, 0, -1});
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 2.0f, 1e-5);
    EXPECT_EQ(hit->instance, 9u);
    EXPECT_NEAR(hit->normal.z, 1.0f, 1e-6);
    EXPECT_FALSE(castRay(world, {0, 0, 0}, {0, 0, 1}));
    EXPECT_FALSE(castRay(CollisionWorld(), {0, 0, 0}, {0, 0, -1}));
}

}  // namespace
}  // namespace idk::tools
