// ssao_oracle.cpp: ambient visibility traced through our BVH on the CPU for SSAO's G-buffer (see ssao_oracle.hpp).
#include "frame/ssao_oracle.hpp"

#include <cmath>
#include <cstring>
#include <random>

#include "bvh/blas.hpp"
#include "bvh/traverse.hpp"
#include "render/bvh_gpu.hpp"

namespace idk::frame {
namespace {

glm::vec3 octDecode(glm::vec2 e) {  // shaders_glsl/include/octahedral.glsl
    glm::vec3 n(e, 1.0f - std::abs(e.x) - std::abs(e.y));
    if (n.z < 0.0f) {
        const glm::vec2 s(n.x >= 0.0f ? 1.0f : -1.0f, n.y >= 0.0f ? 1.0f : -1.0f);
        n = glm::vec3((1.0f - std::abs(n.y)) * s.x, (1.0f - std::abs(n.x)) * s.y, n.z);
    }
    return glm::normalize(n);
}

}  // namespace

AoComparison compareWithTracedAo(const scene::Scene& scene, const scene::CameraView& camera, uint32_t width,
                                 uint32_t height, const std::vector<uint32_t>& planes, float radius, int rays,
                                 uint32_t seed) {
    const size_t count = size_t(width) * height;
    AoComparison c;
    if (planes.size() < count * 3 || rays <= 0) return c;
    const render::TriangleMesh mesh = render::worldTriangles(scene);
    std::vector<bvh::Triangle> triangles;
    for (const glm::uvec3& t : mesh.indices)
        triangles.push_back({mesh.positions[t.x], mesh.positions[t.y], mesh.positions[t.z]});
    const bvh::Blas blas = bvh::buildBlas(triangles);
    const glm::mat4 inverse = glm::inverse(scene::projectionMatrix(camera, float(width) / float(height)) *
                                           scene::viewMatrix(camera));
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::vector<double> ssao, traced;
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) {
            const size_t i = size_t(y) * width + x;
            float depth, visibility;
            std::memcpy(&visibility, &planes[i], 4);
            std::memcpy(&depth, &planes[count + i], 4);
            if (depth >= 1.0f) continue;
            const uint32_t bits = planes[2 * count + i];
            const glm::vec2 e(float(int16_t(bits & 0xFFFF)) / 32767.0f, float(int16_t(bits >> 16)) / 32767.0f);
            const glm::vec3 n = octDecode(glm::clamp(e, -1.0f, 1.0f));
            const glm::vec2 ndc = (glm::vec2(x, y) + 0.5f) / glm::vec2(width, height) * 2.0f - 1.0f;
            const glm::vec4 h = inverse * glm::vec4(ndc, depth, 1.0f);
            const glm::vec3 p = glm::vec3(h) / h.w;
            const glm::vec3 t = glm::normalize(std::abs(n.x) > 0.5f ? glm::cross(n, glm::vec3(0, 1, 0))
                                                                    : glm::cross(n, glm::vec3(1, 0, 0)));
            const glm::vec3 b = glm::cross(n, t);
            int escaped = 0;
            for (int r = 0; r < rays; ++r) {
                const float u1 = u(rng), phi = 6.2831853f * u(rng), s = std::sqrt(u1);
                bvh::Ray ray;
                ray.direction = t * (s * std::cos(phi)) + b * (s * std::sin(phi)) + n * std::sqrt(1.0f - u1);
                ray.origin = p + n * (1e-3f * radius);
                ray.tMax = radius;
                if (!bvh::anyHit(blas, ray)) ++escaped;
            }
            ssao.push_back(visibility);
            traced.push_back(double(escaped) / rays);
        }
    c.pixels = ssao.size();
    if (ssao.empty()) return c;
    for (size_t i = 0; i < ssao.size(); ++i) c.meanSsao += ssao[i], c.meanTraced += traced[i];
    c.meanSsao /= double(ssao.size());
    c.meanTraced /= double(ssao.size());
    double cov = 0, varS = 0, varT = 0;
    for (size_t i = 0; i < ssao.size(); ++i) {
        c.mae += std::abs(ssao[i] - traced[i]);
        c.maeConstant += std::abs(c.meanTraced - traced[i]);
        cov += (ssao[i] - c.meanSsao) * (traced[i] - c.meanTraced);
        varS += (ssao[i] - c.meanSsao) * (ssao[i] - c.meanSsao);
        varT += (traced[i] - c.meanTraced) * (traced[i] - c.meanTraced);
    }
    c.mae /= double(ssao.size());
    c.maeConstant /= double(ssao.size());
    c.correlation = varS > 0 && varT > 0 ? cov / std::sqrt(varS * varT) : 0.0;
    return c;
}

}  // namespace idk::frame
