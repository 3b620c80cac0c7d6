// collision.hpp: spheres that collide with a scene's triangle meshes and slide along them (the viewer's camera)
// or bounce off them (the lights the player shoots). Ports the idea of IDKEngine's Intersections.cs +
// Camera/LightManager collision (internals 2.10) with its weakness fixed: the original moves the sphere in a few
// discrete steps and pushes it out of whatever it penetrates, so a fast sphere can pass a thin wall between two
// steps. Here the sphere is swept continuously (exact time of impact against each triangle's face, edges and
// corners), so no speed tunnels. At a contact the sphere steps back out by a small skin width along the contact
// normal, so it rests at radius + skin, and sliding along a surface never catches on the internal edges between its
// triangles. The rest of the motion is clipped against every plane touched so far (one plane: slide; two: slide
// along their crease; three: stop), which keeps it still in corners and at rest. A sphere that starts inside
// geometry is pushed out first (as the original does).
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "bvh/blas.hpp"
#include "scene/scene.hpp"

namespace idk::tools {

// The scene's triangles in world space with a BVH over them. Triangles are double-sided for collision.
class CollisionWorld {
public:
    CollisionWorld() = default;  // empty: nothing collides
    // Every placed instance in its current pose (node world matrices, morph weights, skinned by the current joint
    // matrices): build again after scene::evaluateAnimations when moving geometry must collide where it is drawn.
    static CollisionWorld fromScene(const scene::Scene& scene);
    // Plain triangles (tests, procedural geometry). `instanceOfTriangle` may be empty (all instance 0).
    static CollisionWorld fromTriangles(std::vector<bvh::Triangle> triangles,
                                        std::vector<uint32_t> instanceOfTriangle = {});

    bool empty() const { return triangles_.empty(); }
    const std::vector<bvh::Triangle>& triangles() const { return triangles_; }
    const bvh::Blas& blas() const { return blas_; }
    // Index into Scene::instances of the instance a triangle came from (picking names the object).
    uint32_t instanceOfTriangle(uint32_t triangle) const {
        return triangle < instanceOf_.size() ? instanceOf_[triangle] : 0u;
    }
    // Appends the ids of triangles whose box overlaps `box` (BVH walk).
    void overlapping(const bvh::Box& box, std::vector<uint32_t>& out) const;

private:
    std::vector<bvh::Triangle> triangles_;  // indexed by triangle id (the BLAS's triIds)
    std::vector<uint32_t> instanceOf_;
    bvh::Blas blas_;
};

// The first triangle a ray hits (picking): nullopt when it hits nothing before tMax.
struct RayHit {
    float t = 0.0f;
    uint32_t triangle = 0;
    uint32_t instance = 0;  // CollisionWorld::instanceOfTriangle(triangle)
    glm::vec3 normal{0.0f}; // unit geometric normal facing the ray's origin
};
std::optional<RayHit> castRay(const CollisionWorld& world, glm::vec3 origin, glm::vec3 direction,
                              float tMax = 1e30f);

struct SphereMoveOptions {
    int maxIterations = 8;     // sweeps per move (each one hits at most one more plane)
    float skinWidth = 1e-3f;   // gap kept between the sphere and the surface (metres), > 0
};

struct SphereMoveResult {
    glm::vec3 position{0.0f};
    bool hit = false;                     // touched anything (sweep or push-out)
    std::vector<glm::vec3> normals;       // unit contact normals (away from the surfaces), duplicates merged
    bool pushedOut = false;               // started inside geometry and was pushed out
};

// Moves a sphere by `delta`, colliding with the world and sliding along what it touches.
SphereMoveResult moveSphereDetailed(const CollisionWorld& world, glm::vec3 center, float radius, glm::vec3 delta,
                                    const SphereMoveOptions& options = {});
// The new centre only.
glm::vec3 moveSphere(const CollisionWorld& world, glm::vec3 center, float radius, glm::vec3 delta,
                     const SphereMoveOptions& options = {});

// `v` with every component going into one of the planes removed (the same plane clipping the slide uses): the
// camera's velocity after a contact, so it does not keep pushing into the wall.
glm::vec3 clipToPlanes(glm::vec3 v, const std::vector<glm::vec3>& normals);

// A shot light: moves by velocity * dt and bounces (reflects the motion and the velocity about each contact
// normal, restitution 1 as the original).
struct BouncingSphere {
    glm::vec3 center{0.0f};
    glm::vec3 velocity{0.0f};
    float radius = 0.1f;
};
BouncingSphere stepBouncingSphere(const CollisionWorld& world, const BouncingSphere& sphere, float dt,
                                  const SphereMoveOptions& options = {});

// Two shot lights that overlap (after their steps): pushed apart along the line between the centres (half the
// overlap each) and, when approaching, their velocity components along that line exchanged: the original's 1-D
// elastic collision of equal masses with restitution 1. Not swept: lights are slow next to their size. Returns true
// when they touched.
bool collideSpheres(BouncingSphere& a, BouncingSphere& b);

// The point of the triangle nearest to `p` (degenerate triangles: the nearest point of their edges).
glm::vec3 closestPointOnTriangle(const bvh::Triangle& tri, glm::vec3 p);

}  // namespace idk::tools
