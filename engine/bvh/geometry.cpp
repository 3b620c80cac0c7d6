// geometry.cpp: triangle split by an axis plane (for pre-splitting) and triangle/box clipped area (for EPO).
#include "bvh/geometry.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace idk::bvh {

bool Triangle::isFinite() const {
    for (const glm::vec3* v : {&v0, &v1, &v2}) {
        if (!std::isfinite(v->x) || !std::isfinite(v->y) || !std::isfinite(v->z)) return false;
    }
    return true;
}

void splitTriangle(const Triangle& tri, int axis, float position, const Box& clipTo, Box& left, Box& right) {
    left = Box::empty();
    right = Box::empty();
    const std::array<glm::vec3, 3> v{tri.v0, tri.v1, tri.v2};
    for (int i = 0; i < 3; ++i) {
        const glm::vec3& a = v[i];
        const glm::vec3& b = v[(i + 1) % 3];
        if (a[axis] <= position) left.grow(a);
        if (a[axis] >= position) right.grow(a);
        const bool crosses = (a[axis] < position && b[axis] > position) || (a[axis] > position && b[axis] < position);
        if (!crosses) continue;
        const float t = (position - a[axis]) / (b[axis] - a[axis]);
        glm::vec3 p = a + (b - a) * t;
        // The crossing is rounded on the two other axes: pad it so the part boxes cover the exact triangle.
        glm::vec3 pad = glm::max(glm::abs(a), glm::abs(b)) * 1e-6f + glm::vec3(1e-30f);
        pad[axis] = 0.0f;
        p[axis] = position;
        for (Box* side : {&left, &right}) {
            side->grow(p - pad);
            side->grow(p + pad);
        }
    }
    for (Box* side : {&left, &right}) {
        if (side->isEmpty()) continue;
        side->clip(clipTo);
    }
}

namespace {

using Polygon = std::array<glm::dvec3, 10>;

// Keeps the part of polygon `in` (n vertices) with sign * (p[axis] - plane) >= 0; returns the new count.
int clipPolygon(const Polygon& in, int n, Polygon& out, int axis, double plane, double sign) {
    int m = 0;
    for (int i = 0; i < n; ++i) {
        const glm::dvec3& a = in[i];
        const glm::dvec3& b = in[(i + 1) % n];
        const double da = sign * (a[axis] - plane);
        const double db = sign * (b[axis] - plane);
        if (da >= 0.0) out[m++] = a;
        if ((da < 0.0 && db > 0.0) || (da > 0.0 && db < 0.0)) {
            glm::dvec3 p = a + (b - a) * (da / (da - db));
            p[axis] = plane;
            out[m++] = p;
        }
    }
    return m;
}

}  // namespace

double clippedTriangleArea(const Triangle& tri, const Box& box) {
    const Box triBox = tri.box();
    if (box.isEmpty() || !box.overlaps(triBox)) return 0.0;
    const glm::dvec3 a(tri.v0), b(tri.v1), c(tri.v2);
    if (box.contains(triBox)) return 0.5 * glm::length(glm::cross(b - a, c - a));
    Polygon poly{a, b, c};
    Polygon scratch{};
    int n = 3;
    for (int axis = 0; axis < 3 && n >= 3; ++axis) {
        n = clipPolygon(poly, n, scratch, axis, box.min[axis], 1.0);
        if (n < 3) break;
        n = clipPolygon(scratch, n, poly, axis, box.max[axis], -1.0);
    }
    if (n < 3) return 0.0;
    glm::dvec3 sum(0.0);
    for (int i = 1; i + 1 < n; ++i) sum += glm::cross(poly[i] - poly[0], poly[i + 1] - poly[0]);
    return 0.5 * glm::length(sum);
}

Box clippedTriangleBox(const Triangle& tri, const Box& box) {
    const Box triBox = tri.box();
    if (box.isEmpty() || !box.overlaps(triBox)) return Box::empty();
    if (box.contains(triBox)) return triBox;
    // Unlike the area, a degenerate (segment or point) polygon still has a box: clip whatever vertices remain.
    Polygon poly{glm::dvec3(tri.v0), glm::dvec3(tri.v1), glm::dvec3(tri.v2)};
    Polygon scratch{};
    int n = 3;
    for (int axis = 0; axis < 3 && n > 0; ++axis) {
        n = clipPolygon(poly, n, scratch, axis, box.min[axis], 1.0);
        if (n == 0) break;
        n = clipPolygon(scratch, n, poly, axis, box.max[axis], -1.0);
    }
    Box out;
    for (int i = 0; i < n; ++i) {
        for (int axis = 0; axis < 3; ++axis) {
            // Round outwards by one float step past the nearest float: covers the double rounding of the crossing.
            const double x = poly[i][axis];
            const float lo = std::nextafter(float(x), -kInfinity);
            const float hi = std::nextafter(float(x), kInfinity);
            out.min[axis] = std::min(out.min[axis], lo);
            out.max[axis] = std::max(out.max[axis], hi);
        }
    }
    if (out.isEmpty()) return out;
    out.clip(box);  // the exact part lies inside `box`
    return out;
}

}  // namespace idk::bvh
