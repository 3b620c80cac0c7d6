// bvh_double_oracle.hpp: the former double-precision watertight ray/triangle test, kept as a CPU test oracle for the
// single-precision kernel (intersect.hpp). Its edge functions are exact in sign: the sheared coordinates are floats,
// a product of two floats is exact in double and each difference is rounded once, so a sign is wrong never and zero
// only when exact. Same shear, same rules (two-sided, edges inside, degenerate misses, t > tMin).
#pragma once

#include "bvh/intersect.hpp"

namespace idk::bvh::test {

struct DoubleEdges {
    double u = 0.0, v = 0.0, w = 0.0;  // exact-signed edge functions of the float sheared coordinates
};

// The sheared coordinates as the fp32 kernel computes them (subnormals flushed), widened to double.
inline DoubleEdges doubleEdges(const PreparedRay& r, const Triangle& tri) {
    const glm::vec3 a = tri.v0 - r.origin;
    const glm::vec3 b = tri.v1 - r.origin;
    const glm::vec3 c = tri.v2 - r.origin;
    const double ax = flushSubnormal(a[r.kx] - r.sx * a[r.kz]), ay = flushSubnormal(a[r.ky] - r.sy * a[r.kz]);
    const double bx = flushSubnormal(b[r.kx] - r.sx * b[r.kz]), by = flushSubnormal(b[r.ky] - r.sy * b[r.kz]);
    const double cx = flushSubnormal(c[r.kx] - r.sx * c[r.kz]), cy = flushSubnormal(c[r.ky] - r.sy * c[r.kz]);
    return {cx * by - cy * bx, ax * cy - ay * cx, bx * ay - by * ax};
}

inline bool intersectTriangleDouble(const PreparedRay& r, const Triangle& tri, TriangleHit& hit) {
    const DoubleEdges e = doubleEdges(r, tri);
    if ((e.u < 0.0 || e.v < 0.0 || e.w < 0.0) && (e.u > 0.0 || e.v > 0.0 || e.w > 0.0)) return false;
    const double det = e.u + e.v + e.w;
    if (det == 0.0) return false;
    const glm::vec3 a = tri.v0 - r.origin;
    const glm::vec3 b = tri.v1 - r.origin;
    const glm::vec3 c = tri.v2 - r.origin;
    const double az = double(r.sz) * a[r.kz], bz = double(r.sz) * b[r.kz], cz = double(r.sz) * c[r.kz];
    const double rcp = 1.0 / det;
    const double t = (e.u * az + e.v * bz + e.w * cz) * rcp;
    if (!(t > double(r.tMin)) || !(t < double(kInfinity))) return false;
    hit.t = float(t);
    if (!(hit.t > r.tMin)) return false;
    hit.u = float(e.v * rcp);
    hit.v = float(e.w * rcp);
    return true;
}

}  // namespace idk::bvh::test
