// vxgi_cornell_injection_test.cpp: the radiance the voxelization injects into the embedded Cornell box's walls
// (64^3 voxels, default conservative raster, cube shadows) against the exact value. Oracle: for every voxel column
// of a wall's dominant axis, the wall's point under the column's centre (where the voxelization's fragment lies)
// leaves albedo / pi * E, E = I * colour * cos / d^2 from the point light (glTF candela, no range), zero where a
// CPU ray to the light meets a triangle of the scene; the GPU voxel holding that point is read back
// (conformance::readVoxelGrid). Asserted per wall (floor, back, left, right): sum of GPU voxel luminance / sum of
// exact luminance within 4% of 1 (measured 0.993, 0.980, 0.983, 0.983: the walls are injected right; the few
// percent low are corner voxels shared by two walls, which average them, and the cube shadow's soft edge).
// This rules out, for the Cornell box's indirect deficit (issue 11: VXGI indirect 0.69 of the path tracer's),
// the voxel pass's self-shadowing, coverage, fp16 range and attenuation.
// The light panel (the same sums over its columns): its voxels hold the panel's exact radiance (its emission plus
// the point light reflected 1 cm below it) within 2%. The panel lies 0.5 mm under the ceiling, in the same voxel
// layer, both facing down; before the front-most rule (shared/vxgi_depth_key.h) the count-averaging rung mixed it
// with the ceiling behind it, which the panel shadows, and the panel's voxels held 0.53 of its radiance.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "app/default_scene.hpp"
#include "conformance/voxel_oracle.hpp"
#include "render/renderer.hpp"
#include "scene/camera.hpp"
#include "support/gpu_fixture.hpp"

namespace idk::test {
namespace {

constexpr uint32_t kVoxels = 64;

struct Triangle {
    glm::dvec3 a, b, c, n;  // n: the geometric normal on the shading normal's side
    glm::dvec3 albedo, emission;
    uint32_t mesh = 0;
};

std::vector<Triangle> sceneTriangles(const scene::Scene& s) {
    std::vector<Triangle> out;
    for (const scene::Instance& instance : s.instances) {
        for (const scene::Primitive& p : s.meshes[instance.mesh].primitives) {
            const scene::Material& m = s.materials[p.material.value_or(0)];
            for (size_t i = 0; i + 2 < p.indices.size(); i += 3) {
                Triangle t;
                t.a = glm::dvec3(instance.world * glm::vec4(p.positions[p.indices[i]], 1.0f));
                t.b = glm::dvec3(instance.world * glm::vec4(p.positions[p.indices[i + 1]], 1.0f));
                t.c = glm::dvec3(instance.world * glm::vec4(p.positions[p.indices[i + 2]], 1.0f));
                t.n = glm::normalize(glm::cross(t.b - t.a, t.c - t.a));
                if (glm::dot(t.n, glm::dvec3(glm::mat3(instance.world) * p.normals[p.indices[i]])) < 0.0) t.n = -t.n;
                t.albedo = glm::dvec3(m.baseColorFactor);
                t.emission = glm::dvec3(m.emissive);
                t.mesh = instance.mesh;
                out.push_back(t);
            }
        }
    }
    return out;
}

// Distance to the ray's hit with t (Moller-Trumbore), or a negative value.
double hitDistance(const Triangle& t, const glm::dvec3& o, const glm::dvec3& d) {
    const glm::dvec3 e1 = t.b - t.a, e2 = t.c - t.a, pv = glm::cross(d, e2);
    const double det = glm::dot(e1, pv);
    if (std::abs(det) < 1e-14) return -1.0;
    const glm::dvec3 tv = o - t.a, qv = glm::cross(tv, e1);
    const double u = glm::dot(tv, pv) / det, v = glm::dot(d, qv) / det;
    if (u < 0.0 || v < 0.0 || u + v > 1.0) return -1.0;
    return glm::dot(e2, qv) / det;
}

// The radiance a wall point p of triangle t leaves: albedo / pi * E from the light (shadowed by any triangle).
glm::dvec3 exactRadiance(const std::vector<Triangle>& tris, const Triangle& t, const scene::Light& light,
                         const glm::dvec3& p) {
    const glm::dvec3 toLight = glm::dvec3(light.position) - p;
    const double d = glm::length(toLight);
    const glm::dvec3 l = toLight / d;
    const double cosine = glm::dot(t.n, l);
    if (cosine <= 0.0) return t.emission;
    for (const Triangle& o : tris) {
        const double h = hitDistance(o, p + t.n * 1e-6, l);
        if (h > 1e-7 && h < d) return t.emission;
    }
    return t.albedo / 3.14159265358979323846 * glm::dvec3(light.color) * double(light.intensity) * cosine / (d * d) +
           t.emission;
}

double luminance(const glm::dvec3& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

class VxgiCornellInjectionTest : public GpuTest {};

TEST_F(VxgiCornellInjectionTest, WallVoxelsHoldTheExactReflectedRadiance) {
    const scene::Scene scene = app::loadDefaultScene();
    ASSERT_EQ(scene.lights.size(), 1u);
    const scene::Light& light = scene.lights[0];
    const std::vector<Triangle> tris = sceneTriangles(scene);
    render::RenderSettings settings;
    settings.output = render::OutputKind::Hdr;
    settings.environmentIntensity = 0.0f;
    settings.vxgi.mode = frame::GiMode::Vxgi;
    settings.vxgi.voxels = kVoxels;
    render::Renderer renderer(ctx(), shaders(), settings);
    renderer.setScene(scene);
    renderer.renderOffscreen(scene::defaultCamera(scene), 64, 64);
    const passes::VoxelGridBox box = renderer.vxgi().box();
    const std::vector<glm::vec4> grid = conformance::readVoxelGrid(ctx(), *renderer.vxgi().grid());
    const int n = int(box.size);
    const double v = box.voxelSize;

    // Mesh order of cornell_box.gltf.
    const char* names[] = {"floor", "ceiling", "back", "left", "right", "short block", "tall block", "light panel"};
    for (uint32_t mesh = 0; mesh < 8; ++mesh) {
        double gpuSum = 0.0, exactSum = 0.0;
        for (const Triangle& t : tris) {
            if (t.mesh != mesh) continue;
            const glm::dvec3 an = glm::abs(t.n);
            const int a = an.x >= an.y && an.x >= an.z ? 0 : (an.y >= an.z ? 1 : 2), u = (a + 1) % 3, w = (a + 2) % 3;
            for (int i = 0; i < n; ++i) {
                for (int j = 0; j < n; ++j) {
                    glm::dvec3 o(0.0), d(0.0);
                    o[u] = box.gridMin[u] + (i + 0.5) * v;
                    o[w] = box.gridMin[w] + (j + 0.5) * v;
                    o[a] = box.gridMin[a] - 1.0;
                    d[a] = 1.0;
                    const double h = hitDistance(t, o, d);
                    if (h <= 0.0) continue;
                    const glm::dvec3 p = o + d * h;
                    const glm::ivec3 q(glm::floor((p - glm::dvec3(box.gridMin)) / v));
                    if (glm::any(glm::lessThan(q, glm::ivec3(0))) || glm::any(glm::greaterThanEqual(q, glm::ivec3(n))))
                        continue;
                    gpuSum += luminance(glm::dvec3(grid[(size_t(q.z) * n + q.y) * n + q.x]));
                    exactSum += luminance(exactRadiance(tris, t, light, p));
                }
            }
        }
        const double ratio = gpuSum / exactSum;
        std::printf("%-12s GPU / exact injected radiance %.3f\n", names[mesh], ratio);
        // The walls that share no voxel with another surface's interior (the ceiling shares its layer with the
        // panel, the blocks stand on the floor's layer).
        if (mesh == 0 || mesh == 2 || mesh == 3 || mesh == 4) {
            EXPECT_NEAR(ratio, 1.0, 0.04) << names[mesh];
        }
        // The panel is the front-most surface facing down in its voxels: the ceiling it hides must not dilute it.
        if (mesh == 7) {
            EXPECT_NEAR(ratio, 1.0, 0.02) << names[mesh];
        }
    }
}

}  // namespace
}  // namespace idk::test
