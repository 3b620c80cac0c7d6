// sphere_move.cpp: collide-and-slide and bounce for spheres in a CollisionWorld (see collision.hpp for the
// method and how it differs from IDKEngine's stepped position correction). All the arithmetic is in double so
// that a sphere resting against a wall at the skin distance stays exactly where it is.
#include <algorithm>
#include <cmath>

#include "tools/collision.hpp"
#include "tools/sphere_sweep.hpp"

namespace idk::tools {

namespace {

using glm::dvec3;

bool finite(const dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// Projection of v onto the cone {x : dot(x, n) >= 0 for every plane}: v itself, its projection onto one plane or
// onto the crease of two, or zero, whichever is allowed by every plane and nearest to v. In 3D the projection
// onto a polyhedral cone is always one of these.
dvec3 clipAgainst(const dvec3& v, const std::vector<dvec3>& planes) {
    const double tolerance = -1e-9 * glm::length(v);
    auto allowed = [&](const dvec3& x) {
        for (const dvec3& n : planes) {
            if (glm::dot(x, n) < tolerance) return false;
        }
        return true;
    };
    if (allowed(v)) return v;
    dvec3 best(0.0);
    double bestDistance = glm::dot(v, v);
    auto consider = [&](const dvec3& x) {
        const double d = glm::dot(v - x, v - x);
        if (d < bestDistance && allowed(x)) {
            best = x;
            bestDistance = d;
        }
    };
    for (const dvec3& n : planes) {
        const double into = glm::dot(v, n);
        if (into < 0.0) consider(v - into * n);
    }
    for (size_t i = 0; i < planes.size(); ++i) {
        for (size_t j = i + 1; j < planes.size(); ++j) {
            dvec3 crease = glm::cross(planes[i], planes[j]);
            const double length = glm::length(crease);
            if (length < 1e-9) continue;  // parallel planes have no crease
            crease /= length;
            consider(crease * glm::dot(v, crease));
        }
    }
    return best;
}

void addPlane(std::vector<dvec3>& planes, const dvec3& n) {
    for (const dvec3& p : planes) {
        if (glm::dot(p, n) > 1.0 - 1e-9) return;
    }
    planes.push_back(n);
}

class Mover {
public:
    Mover(const CollisionWorld& world, double radius, double skin)
        : world_(world), radius_(radius), skin_(skin) {}

    // Earliest contact of the sphere (true radius) moving from c by d. The caller stops there and steps back by
    // the skin along the contact normal: the sphere then rests at radius + skin, where sliding along the surface
    // (and over the internal edges between its triangles, at radius + skin > radius) touches nothing.
    std::optional<SweepContact> sweep(const dvec3& c, const dvec3& d) {
        bvh::Box box;
        box.grow(glm::vec3(glm::min(c, c + d)));
        box.grow(glm::vec3(glm::max(c, c + d)));
        query(box, radius_);
        std::optional<SweepContact> best;
        for (uint32_t id : ids_) {
            const bvh::Triangle& tri = world_.triangles()[id];
            std::optional<SweepContact> hit =
                sweepSphereTriangle(c, radius_, d, dvec3(tri.v0), dvec3(tri.v1), dvec3(tri.v2));
            if (hit && (!best || hit->t < best->t)) best = hit;
        }
        return best;
    }

    // Moves to the contact and steps back out by the skin.
    dvec3 stopAt(const dvec3& c, const dvec3& d, const SweepContact& hit) const {
        return c + d * hit.t + hit.normal * skin_;
    }

    // The original's correction, kept for spheres that start in geometry (spawned there, or the geometry moved):
    // while a triangle is nearer than radius + skin / 2, push the centre out from the nearest one to the full
    // radius + skin. Half a skin of slack means a sphere resting at the skin distance is never touched here.
    bool pushOut(dvec3& c, std::vector<dvec3>& planes) {
        const double limit = radius_ + 0.5 * skin_;
        bool moved = false;
        for (int round = 0; round < 4; ++round) {
            bvh::Box box;
            box.grow(glm::vec3(c));
            query(box, limit);
            double nearest = limit * limit;
            dvec3 nearestPoint(0.0);
            const bvh::Triangle* nearestTri = nullptr;
            for (uint32_t id : ids_) {
                const bvh::Triangle& tri = world_.triangles()[id];
                const dvec3 q = closestPointOnTriangle(dvec3(tri.v0), dvec3(tri.v1), dvec3(tri.v2), c);
                const double d2 = glm::dot(c - q, c - q);
                if (d2 < nearest) {
                    nearest = d2;
                    nearestPoint = q;
                    nearestTri = &tri;
                }
            }
            if (nearestTri == nullptr) break;
            dvec3 n = c - nearestPoint;
            const double length = glm::length(n);
            if (length > 1e-12) {
                n /= length;
            } else {  // centre on the triangle: out along its face normal
                n = glm::cross(dvec3(nearestTri->v1 - nearestTri->v0), dvec3(nearestTri->v2 - nearestTri->v0));
                if (!(glm::length(n) > 0.0)) break;
                n = glm::normalize(n);
            }
            c = nearestPoint + n * (radius_ + skin_);
            addPlane(planes, n);
            moved = true;
        }
        return moved;
    }

private:
    void query(bvh::Box box, double pad) {
        // Pad by the radius plus a little for the float rounding of the box itself.
        const float p = float(pad) * 1.0001f + 1e-5f * (1.0f + glm::length(box.max));
        box.min -= glm::vec3(p);
        box.max += glm::vec3(p);
        ids_.clear();
        world_.overlapping(box, ids_);
        std::sort(ids_.begin(), ids_.end());  // the same order whatever the tree: ties resolve deterministically
    }

    const CollisionWorld& world_;
    double radius_, skin_;
    std::vector<uint32_t> ids_;
};

std::vector<glm::vec3> toFloat(const std::vector<dvec3>& planes) {
    std::vector<glm::vec3> out;
    out.reserve(planes.size());
    for (const dvec3& n : planes) out.emplace_back(n);
    return out;
}

}  // namespace

glm::vec3 clipToPlanes(glm::vec3 v, const std::vector<glm::vec3>& normals) {
    std::vector<dvec3> planes;
    for (const glm::vec3& n : normals) addPlane(planes, glm::normalize(dvec3(n)));
    return glm::vec3(clipAgainst(dvec3(v), planes));
}

SphereMoveResult moveSphereDetailed(const CollisionWorld& world, glm::vec3 center, float radius, glm::vec3 delta,
                                    const SphereMoveOptions& options) {
    SphereMoveResult result;
    result.position = center;
    dvec3 c(center), remaining(delta);
    if (!finite(c) || !finite(remaining) || !(radius > 0.0f)) return result;  // nothing sensible to do: stay
    if (world.empty()) {
        result.position = center + delta;
        return result;
    }
    Mover mover(world, radius, std::max(options.skinWidth, 1e-6f));
    std::vector<dvec3> planes;
    result.pushedOut = mover.pushOut(c, planes);
    remaining = clipAgainst(remaining, planes);
    for (int i = 0; i < options.maxIterations && glm::dot(remaining, remaining) > 0.0; ++i) {
        const std::optional<SweepContact> hit = mover.sweep(c, remaining);
        if (!hit) {
            c += remaining;
            remaining = dvec3(0.0);
            break;
        }
        c = mover.stopAt(c, remaining, *hit);
        addPlane(planes, hit->normal);
        remaining = clipAgainst(remaining * (1.0 - hit->t), planes);
    }
    // Motion left after the last iteration is dropped (the sphere stays where the last sweep left it).
    if (mover.pushOut(c, planes)) result.pushedOut = true;
    result.position = glm::vec3(c);
    result.hit = !planes.empty();
    result.normals = toFloat(planes);
    return result;
}

glm::vec3 moveSphere(const CollisionWorld& world, glm::vec3 center, float radius, glm::vec3 delta,
                     const SphereMoveOptions& options) {
    return moveSphereDetailed(world, center, radius, delta, options).position;
}

BouncingSphere stepBouncingSphere(const CollisionWorld& world, const BouncingSphere& sphere, float dt,
                                  const SphereMoveOptions& options) {
    BouncingSphere out = sphere;
    dvec3 c(sphere.center), velocity(sphere.velocity), remaining = velocity * double(dt);
    if (!finite(c) || !finite(remaining) || !(sphere.radius > 0.0f)) return out;
    if (world.empty()) {
        out.center = glm::vec3(c + remaining);
        return out;
    }
    Mover mover(world, sphere.radius, std::max(options.skinWidth, 1e-6f));
    auto reflect = [](const dvec3& v, const dvec3& n) {
        const double into = glm::dot(v, n);
        return into < 0.0 ? v - 2.0 * into * n : v;
    };
    std::vector<dvec3> planes;
    if (mover.pushOut(c, planes)) {
        for (const dvec3& n : planes) {
            velocity = reflect(velocity, n);
            remaining = reflect(remaining, n);
        }
    }
    for (int i = 0; i < options.maxIterations && glm::dot(remaining, remaining) > 0.0; ++i) {
        const std::optional<SweepContact> hit = mover.sweep(c, remaining);
        if (!hit) {
            c += remaining;
            remaining = dvec3(0.0);
            break;
        }
        c = mover.stopAt(c, remaining, *hit);
        remaining = reflect(remaining * (1.0 - hit->t), hit->normal);
        velocity = reflect(velocity, hit->normal);
    }
    std::vector<dvec3> after;
    mover.pushOut(c, after);
    out.center = glm::vec3(c);
    out.velocity = glm::vec3(velocity);
    return out;
}

bool collideSpheres(BouncingSphere& a, BouncingSphere& b) {
    const glm::dvec3 between = dvec3(b.center) - dvec3(a.center);
    const double distance = glm::length(between);
    const double reach = double(a.radius) + double(b.radius);
    if (!(distance < reach)) return false;
    // Coincident centres: any axis separates them; +y keeps it deterministic.
    const dvec3 n = distance > 1e-12 ? between / distance : dvec3(0.0, 1.0, 0.0);
    const dvec3 push = n * (0.5 * (reach - distance));
    a.center = glm::vec3(dvec3(a.center) - push);
    b.center = glm::vec3(dvec3(b.center) + push);
    const double va = glm::dot(dvec3(a.velocity), n), vb = glm::dot(dvec3(b.velocity), n);
    if (va > vb) {  // approaching: equal masses swap their normal components
        a.velocity = glm::vec3(dvec3(a.velocity) + (vb - va) * n);
        b.velocity = glm::vec3(dvec3(b.velocity) + (va - vb) * n);
    }
    return true;
}

}  // namespace idk::tools
