// sphere_sweep.hpp: the exact geometric kernels of the collision code, in double precision: the closest point
// on a triangle, and the first time a moving sphere touches a triangle (Fauerby's swept-sphere test: the sphere's
// centre against the triangle grown by the radius = a slab over the face, a cylinder around each edge, a sphere
// at each corner; the earliest entry into any of them). Used by sphere_move.cpp; exposed for the unit tests.
#pragma once

#include <optional>

#include <glm/glm.hpp>

namespace idk::tools {

glm::dvec3 closestPointOnTriangle(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, const glm::dvec3& p);

struct SweepContact {
    double t = 0.0;             // fraction of the motion [0, 1] at first contact
    glm::dvec3 normal{0.0};     // unit, from the surface towards the sphere's centre at contact
};

// A sphere of `radius` centred at `center` moving by `delta` against triangle (a, b, c), double-sided.
// - Already closer than `radius`: contact at t = 0 when the motion goes further in (the distance to a convex set
//   is convex along a line, so a motion that does not go in now never gets closer), else none.
// - Otherwise the earliest t in [0, 1] at which the distance becomes `radius`. Grazing contacts (the motion
//   parallel to the surface there) are not contacts: they would stop a slide along a flat floor at every
//   internal edge between its triangles.
std::optional<SweepContact> sweepSphereTriangle(const glm::dvec3& center, double radius, const glm::dvec3& delta,
                                                const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c);

}  // namespace idk::tools
