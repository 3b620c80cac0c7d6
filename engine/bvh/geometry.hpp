// geometry.hpp: the plain shapes of the BVH code: axis-aligned boxes, triangles, rays, plus the exact
// geometric helpers the builder and the metrics need (triangle split by a plane, area of a triangle clipped to a
// box). An empty box has min = +inf and max = -inf, so growing it by anything gives that thing's box.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <limits>

namespace idk::bvh {

inline constexpr float kInfinity = std::numeric_limits<float>::infinity();
inline constexpr uint32_t kInvalidIndex = 0xFFFFFFFFu;

struct Box {
    glm::vec3 min{kInfinity};
    glm::vec3 max{-kInfinity};

    static Box empty() { return {}; }
    void grow(const glm::vec3& p) {
        min = glm::min(min, p);
        max = glm::max(max, p);
    }
    void grow(const Box& b) {
        min = glm::min(min, b.min);
        max = glm::max(max, b.max);
    }
    // Intersection with `b` (ClipAgainst in IDKEngine); may leave the box empty (min > max on some axis).
    void clip(const Box& b) {
        min = glm::max(min, b.min);
        max = glm::min(max, b.max);
    }
    bool isEmpty() const { return !(min.x <= max.x && min.y <= max.y && min.z <= max.z); }
    glm::vec3 extent() const { return max - min; }
    // Half the surface area: the SAH only ever uses ratios, so the factor 2 is dropped everywhere.
    float halfArea() const {
        if (isEmpty()) return 0.0f;
        glm::vec3 d = max - min;
        return d.x * d.y + d.y * d.z + d.z * d.x;
    }
    int largestAxis() const {
        glm::vec3 d = extent();
        return d.x >= d.y && d.x >= d.z ? 0 : (d.y >= d.z ? 1 : 2);
    }
    float largestExtent() const { return extent()[largestAxis()]; }
    bool contains(const Box& b) const {
        return glm::all(glm::lessThanEqual(min, b.min)) && glm::all(glm::lessThanEqual(b.max, max));
    }
    bool overlaps(const Box& b) const {
        return glm::all(glm::lessThanEqual(min, b.max)) && glm::all(glm::lessThanEqual(b.min, max));
    }
    friend bool operator==(const Box&, const Box&) = default;
};

struct Triangle {
    glm::vec3 v0{0.0f};
    glm::vec3 v1{0.0f};
    glm::vec3 v2{0.0f};

    Box box() const {
        Box b;
        b.grow(v0);
        b.grow(v1);
        b.grow(v2);
        return b;
    }
    float area() const { return 0.5f * glm::length(glm::cross(v1 - v0, v2 - v0)); }
    bool isFinite() const;
};

// A ray with the parametric interval (tMin, tMax): hits at t <= tMin or t >= tMax are not reported.
struct Ray {
    glm::vec3 origin{0.0f};
    glm::vec3 direction{0.0f, 0.0f, 1.0f};
    float tMin = 0.0f;
    float tMax = kInfinity;
};

// Boxes of the two parts of `tri` on either side of the plane x[axis] = position, each clipped to `clipTo`.
// The part boxes are padded by a few ulps on the two other axes so that together they always cover the exact
// triangle (the plane crossings are rounded). A side the triangle does not reach comes back empty.
void splitTriangle(const Triangle& tri, int axis, float position, const Box& clipTo, Box& left, Box& right);

// Area of the part of `tri` inside `box` (exact polygon clipping, Sutherland-Hodgman on the six planes),
// computed in double precision.
double clippedTriangleArea(const Triangle& tri, const Box& box);

// Tight box of the part of `tri` inside `box` (the same polygon clipping, then rounded outwards to float and
// clamped to `box`), so it always holds the exact part. Empty when the triangle misses the box. Used for the
// chopped references of spatial splits (sbvh.hpp), where it is tighter than splitTriangle's padded boxes.
Box clippedTriangleBox(const Triangle& tri, const Box& box);

}  // namespace idk::bvh
