// shadow_cascades.cpp: directional-light cascade fitting (practical split scheme, bounding spheres, texel
// snapping) and spot-light perspective maps. See shadow_cascades.hpp.
#include "render/shadow_cascades.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "shared/shadow_types.h"

namespace idk::render {
namespace {

// Light-space basis: columns u, v across the light, w = direction. u avoids the axis most parallel to w.
glm::mat3 lightBasis(glm::vec3 w) {
    glm::vec3 helper = std::abs(w.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    glm::vec3 u = glm::normalize(glm::cross(helper, w));
    glm::vec3 v = glm::cross(w, u);
    return glm::mat3(u, v, w);
}

// Depth range of the box along w.
glm::vec2 boxRange(const scene::Aabb& box, glm::vec3 w) {
    glm::vec2 r(std::numeric_limits<float>::max(), std::numeric_limits<float>::lowest());
    for (int c = 0; c < 8; ++c) {
        glm::vec3 p((c & 1) ? box.max.x : box.min.x, (c & 2) ? box.max.y : box.min.y,
                    (c & 4) ? box.max.z : box.min.z);
        float d = glm::dot(p, w);
        r = {std::min(r.x, d), std::max(r.y, d)};
    }
    return r;
}

}  // namespace

float cascadeShadowDistance(const scene::CameraView& camera, const scene::Aabb& box, float maxDistance) {
    float far = camera.zfar > 0.0f ? camera.zfar : std::numeric_limits<float>::max();
    if (!box.empty()) {
        float deepest = 0.0f;
        for (int c = 0; c < 8; ++c) {
            glm::vec3 p((c & 1) ? box.max.x : box.min.x, (c & 2) ? box.max.y : box.min.y,
                        (c & 4) ? box.max.z : box.min.z);
            deepest = std::max(deepest, glm::dot(p - camera.position, camera.forward));
        }
        far = std::min(far, deepest);
    }
    if (maxDistance > 0.0f) far = std::min(far, maxDistance);
    return std::max(far, 2.0f * camera.znear);
}

std::vector<ShadowProjection> directionalCascades(const scene::CameraView& camera, float aspect,
                                                  const scene::Aabb& sceneBox, glm::vec3 direction, uint32_t count,
                                                  uint32_t resolution, float maxDistance) {
    count = std::clamp(count, 1u, 4u);
    const float n = camera.znear, f = cascadeShadowDistance(camera, sceneBox, maxDistance);
    const float a = camera.aspectRatio > 0.0f ? camera.aspectRatio : aspect;
    const bool ortho = camera.type == scene::CameraType::Orthographic;
    // Half-diagonal of the view cross-section per unit distance (perspective), or in world units (orthographic).
    const float halfY = ortho ? camera.ymag : std::tan(0.5f * camera.yfov);
    const float halfX = ortho ? camera.xmag : halfY * a;
    const float k2 = halfX * halfX + halfY * halfY;

    const glm::mat3 basis = lightBasis(glm::normalize(direction));
    const glm::mat3 toLight = glm::transpose(basis);
    const glm::vec2 depth = boxRange(sceneBox, basis[2]);
    const float depthPad = 1e-3f * std::max(1.0f, depth.y - depth.x);
    const float z0 = depth.x - depthPad, z1 = depth.y + depthPad;

    std::vector<ShadowProjection> out;
    float near = n;
    for (uint32_t i = 1; i <= count; ++i) {
        // Practical split scheme (Zhang et al. 2006): mostly logarithmic, blended towards uniform.
        const float t = float(i) / float(count);
        const float far = i == count ? f : 0.75f * n * std::pow(f / n, t) + 0.25f * (n + (f - n) * t);
        // Bounding sphere of the slice's 8 corners, centre on the view axis at depth zc.
        float zc, r;
        if (ortho) {
            zc = 0.5f * (near + far);
            r = std::sqrt(0.25f * (far - near) * (far - near) + k2);
        } else {
            zc = std::min(far, 0.5f * (1.0f + k2) * (near + far));
            r = std::sqrt((zc - near) * (zc - near) + k2 * near * near);
            r = std::max(r, std::sqrt((far - zc) * (far - zc) + k2 * far * far));
        }
        r *= 1.0f + 2.0f * gpu::kShadowMapMargin / float(resolution);  // room for the lookup's filter margin
        const float texel = 2.0f * r / float(resolution);
        glm::vec3 centre = toLight * (camera.position + camera.forward * zc);
        centre.x = std::floor(centre.x / texel) * texel;  // texel snapping: the grid stays fixed in light space
        centre.y = std::floor(centre.y / texel) * texel;

        // world -> light (u, v, w) -> [-1, 1]^2 x [0, 1].
        glm::mat4 m(1.0f);
        for (int c = 0; c < 3; ++c) {
            m[c][0] = toLight[c][0] / r;
            m[c][1] = toLight[c][1] / r;
            m[c][2] = toLight[c][2] / (z1 - z0);
        }
        m[3][0] = -centre.x / r;
        m[3][1] = -centre.y / r;
        m[3][2] = -z0 / (z1 - z0);
        out.push_back({m, texel, false, far});
        near = far;
    }
    return out;
}

float spotOuterAngle(float spotScale, float spotOffset) {
    float cosOuter = spotScale > 0.0f ? -spotOffset / spotScale : 0.0f;
    return std::acos(std::clamp(cosOuter, -1.0f, 1.0f));
}

ShadowProjection spotShadowProjection(glm::vec3 position, glm::vec3 direction, float outerAngle, glm::vec2 planes,
                                      uint32_t resolution) {
    // The cone must fit inside the map minus the lookup margin: tan(half) = tan(outer) / (1 - 2 margin / size).
    const float half = std::atan(std::tan(std::min(outerAngle, kMaxSpotMapHalfAngle)) /
                                 (1.0f - 2.0f * gpu::kShadowMapMargin / float(resolution)));
    const glm::mat3 basis = lightBasis(glm::normalize(direction));
    glm::mat4 view = scene::lookAtView(position, position + basis[2], basis[1]);
    ShadowProjection p;
    p.viewProjection = scene::perspectiveVulkan(2.0f * half, 1.0f, planes.x, planes.y) * view;
    p.texelScale = 2.0f * std::tan(half) / float(resolution);
    p.perspective = true;
    return p;
}

}  // namespace idk::render
