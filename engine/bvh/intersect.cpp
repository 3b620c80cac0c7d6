// intersect.cpp: per-ray set-up of the box/triangle tests and the ray origin offset (see intersect.hpp).
#include "bvh/intersect.hpp"

#include <bit>

namespace idk::bvh {

PreparedRay prepareRay(const Ray& ray) {
    PreparedRay r;
    const glm::vec3& d = ray.direction;
    bool finite = std::isfinite(ray.tMin) && !std::isnan(ray.tMax) && ray.tMin < ray.tMax;
    for (int i = 0; i < 3; ++i) finite = finite && std::isfinite(ray.origin[i]) && std::isfinite(d[i]);
    if (!finite || (d.x == 0.0f && d.y == 0.0f && d.z == 0.0f)) return r;
    r.origin = ray.origin;
    r.invDirection = 1.0f / d;  // +-0 -> +-inf, which the slab test handles
    r.tMin = ray.tMin;
    r.tMax = ray.tMax;
    const glm::vec3 ad = glm::abs(d);
    r.kz = ad.x >= ad.y && ad.x >= ad.z ? 0 : (ad.y >= ad.z ? 1 : 2);
    r.kx = (r.kz + 1) % 3;
    r.ky = (r.kx + 1) % 3;
    if (d[r.kz] < 0.0f) std::swap(r.kx, r.ky);  // keep the winding, so edge function signs keep their meaning
    r.sx = d[r.kx] / d[r.kz];
    r.sy = d[r.ky] / d[r.kz];
    r.sz = 1.0f / d[r.kz];
    r.valid = true;
    return r;
}

glm::vec3 offsetRayOrigin(const glm::vec3& p, const glm::vec3& n) {
    constexpr float kOrigin = 1.0f / 32.0f;
    constexpr float kFloatScale = 1.0f / 65536.0f;
    constexpr float kIntScale = 256.0f;
    glm::vec3 out;
    for (int i = 0; i < 3; ++i) {
        const int32_t ulps = int32_t(kIntScale * n[i]);
        const uint32_t bits = std::bit_cast<uint32_t>(p[i]);
        // Adding to the bits of a negative float moves it towards -inf, so the sign of the step follows p. The sum
        // wraps in unsigned arithmetic (two's complement, as GLSL's int addition): no signed overflow for -0.0, whose
        // stepped value is computed but not used (|p| < kOrigin takes the other branch).
        const float stepped = std::bit_cast<float>(bits + uint32_t(p[i] < 0.0f ? -ulps : ulps));
        out[i] = std::abs(p[i]) < kOrigin ? p[i] + kFloatScale * n[i] : stepped;
    }
    return out;
}

}  // namespace idk::bvh
