// sphere_sweep.cpp: swept sphere against one triangle (see sphere_sweep.hpp).
#include "tools/sphere_sweep.hpp"

#include <algorithm>
#include <cmath>

namespace idk::tools {

namespace {

// A motion is "into" a surface with outward normal n when it loses distance faster than this fraction of its
// length: below that it is tangential (rounding of an earlier clip against the same plane).
constexpr double kIntoTolerance = 1e-7;

// Smallest root t of a t^2 + b t + c = 0 (a > 0); none when there is no real root.
std::optional<double> firstRoot(double a, double b, double c) {
    const double disc = b * b - 4.0 * a * c;
    if (!(a > 0.0) || disc < 0.0) return std::nullopt;
    // The numerically stable form of the smaller root.
    const double s = std::sqrt(disc);
    const double q = -0.5 * (b + (b >= 0.0 ? s : -s));
    const double r0 = q / a;
    const double r1 = q != 0.0 ? c / q : r0;
    return std::min(r0, r1);
}

struct Best {
    double t = 2.0;
    glm::dvec3 normal{0.0};
    void offer(double t, const glm::dvec3& n) {
        if (t < this->t) {
            this->t = t;
            normal = n;
        }
    }
};

}  // namespace

std::optional<SweepContact> sweepSphereTriangle(const glm::dvec3& center, double radius, const glm::dvec3& delta,
                                                const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
    const double moveLength = glm::length(delta);
    const double r2 = radius * radius;

    // Already touching: blocked now if going in, else never (convexity).
    const glm::dvec3 q0 = closestPointOnTriangle(a, b, c, center);
    const glm::dvec3 away = center - q0;
    const double dist2 = glm::dot(away, away);
    if (dist2 < r2) {
        glm::dvec3 n;
        if (dist2 > 1e-30) {
            n = away / std::sqrt(dist2);
        } else {  // centre on the surface: the face normal against the motion
            n = glm::cross(b - a, c - a);
            const double len = glm::length(n);
            if (!(len > 0.0)) return std::nullopt;
            n /= len;
            if (glm::dot(n, delta) > 0.0) n = -n;
        }
        if (glm::dot(delta, n) < -kIntoTolerance * moveLength) return SweepContact{0.0, n};
        return std::nullopt;
    }
    if (!(moveLength > 0.0)) return std::nullopt;

    Best best;
    auto offerIfInto = [&](double t, const glm::dvec3& n) {
        if (t < 0.0) t = 0.0;  // entry rounded just before the start (the start is outside)
        if (t <= 1.0 && glm::dot(delta, n) < -kIntoTolerance * moveLength) best.offer(t, n);
    };

    // Face: the centre reaches the plane offset by the radius inside the triangle.
    glm::dvec3 n = glm::cross(b - a, c - a);
    const double nLength = glm::length(n);
    if (nLength > 1e-12 * glm::length(b - a) * glm::length(c - a) && nLength > 0.0) {
        n /= nLength;
        // The side the centre starts on faces the sphere (double-sided); the inside test keeps the winding's n.
        double side = glm::dot(center - a, n);
        const glm::dvec3 towards = side < 0.0 ? -n : n;
        side = std::abs(side);
        const double approach = glm::dot(delta, towards);
        if (side >= radius && approach < 0.0) {
            const double t = (side - radius) / -approach;
            if (t <= 1.0) {
                const glm::dvec3 p = center + t * delta - radius * towards;  // touch point on the plane
                const bool inside = glm::dot(glm::cross(b - a, p - a), n) >= 0.0 &&
                                    glm::dot(glm::cross(c - b, p - b), n) >= 0.0 &&
                                    glm::dot(glm::cross(a - c, p - c), n) >= 0.0;
                if (inside) offerIfInto(t, towards);
            }
        }
    }

    // Edges: the centre reaches the cylinder of the radius around the segment.
    const glm::dvec3 corners[3] = {a, b, c};
    for (int i = 0; i < 3; ++i) {
        const glm::dvec3& p0 = corners[i];
        const glm::dvec3& p1 = corners[(i + 1) % 3];
        const glm::dvec3 e = p1 - p0;
        const double ee = glm::dot(e, e);
        if (!(ee > 0.0)) continue;
        const glm::dvec3 w = center - p0;
        const glm::dvec3 dPerp = delta - e * (glm::dot(delta, e) / ee);
        const glm::dvec3 wPerp = w - e * (glm::dot(w, e) / ee);
        const std::optional<double> t =
            firstRoot(glm::dot(dPerp, dPerp), 2.0 * glm::dot(wPerp, dPerp), glm::dot(wPerp, wPerp) - r2);
        if (!t || *t > 1.0 || *t < -1e-9) continue;
        const glm::dvec3 at = center + std::max(*t, 0.0) * delta;
        const double f = glm::dot(at - p0, e) / ee;
        if (f < 0.0 || f > 1.0) continue;  // beyond the segment: a corner sphere takes it
        const glm::dvec3 out = at - (p0 + f * e);
        const double len = glm::length(out);
        if (len > 0.0) offerIfInto(*t, out / len);
    }

    // Corners: the centre reaches the sphere of the radius around each vertex.
    for (const glm::dvec3& v : corners) {
        const glm::dvec3 w = center - v;
        const std::optional<double> t = firstRoot(glm::dot(delta, delta), 2.0 * glm::dot(w, delta), glm::dot(w, w) - r2);
        if (!t || *t > 1.0 || *t < -1e-9) continue;
        const glm::dvec3 out = center + std::max(*t, 0.0) * delta - v;
        const double len = glm::length(out);
        if (len > 0.0) offerIfInto(*t, out / len);
    }

    if (best.t > 1.0) return std::nullopt;
    return SweepContact{best.t, best.normal};
}

}  // namespace idk::tools
