// footprint_cone_test.cpp: the diffuse cone set (shared/vxgi_cone.h, through the CPU cone tracer
// support/vxgi_cone_oracle.hpp, which cone_trace_test.cpp holds to the GPU pass) against the exact irradiance of a
// small emitter: a 3 m floor lit only by a 0.3 x 0.3 emissive panel 0.6 above it (no punctual light, environment
// off, 64^3 voxels of 4.76 cm, 5 ring cones), so the grid's only radiance is the panel's and the exact one-bounce
// irradiance at a floor point is the panel's form factor times its radiance (Lambert's polygon formula). The
// reference is the panel as the grid holds it (the square of the voxels it touches, each fully covered: the
// conservative voxelization's dilation is not the cone tracer's error). A wall 1 m high, one voxel thin, stands
// between the panel and the floor point (-0.9, 0), which gets no light from it.
// What this guards: every cone samples a tube narrower than itself (the receiver-plane clamp holds the cell to a
// third of the sample's height), so one cone per direction either hits the small panel with its whole weight or
// misses it; footprint cones (--gi-footprint 4 / 7: each cone traced as narrower cones tiling it, each with its
// own transmittance) gather the panel in proportion to the solid angle it covers.
// Measured, traced / exact at the four lit points: footprint 1: 1.83, 0.71, 1.65, 2.07 (mean |log ratio| 0.546);
// 4: 1.32, 1.11, 1.32, 1.07 (0.182); 7: 1.11, 1.13, 1.13, 1.30 (0.152). Behind the wall, over the mirror point's
// exact irradiance: 0.065, 0.047, 0.116: the one-voxel wall's inherent leak (a trilinear, Beer-Lambert march
// passes 0..19% straight through a fully opaque voxel layer, by the samples' phase; VxgiFrameTest's thin wall),
// larger with 7 narrow cones because more of them aim at the panel through it.
// Asserted: with 4 and 7 footprint cones every lit point within 0.8..1.45 of exact and the mean |log ratio| below
// 0.25 and below half of one cone's; behind the wall below 0.13 of the mirror's exact with every setting.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "render/renderer.hpp"
#include "support/gpu_fixture.hpp"
#include "support/placed_quads.hpp"
#include "support/vxgi_cone_oracle.hpp"

namespace idk::test {
namespace {

constexpr float kPanelRadiance = 10.0f;
constexpr float kPanelHeight = 0.6f;
constexpr float kPanelHalf = 0.15f;

// Irradiance at `p` (unit normal `n`) from a uniform Lambertian polygon of radiance L seen fully from p's side
// (Lambert's formula: E = L / 2 * sum over edges of the edge's angle at p times its plane normal's cosine with n).
double polygonIrradiance(const std::vector<glm::dvec3>& corners, glm::dvec3 p, glm::dvec3 n, double radiance) {
    double sum = 0.0;
    for (size_t i = 0; i < corners.size(); ++i) {
        const glm::dvec3 a = glm::normalize(corners[i] - p), b = glm::normalize(corners[(i + 1) % corners.size()] - p);
        const glm::dvec3 c = glm::cross(a, b);
        sum += std::acos(glm::clamp(glm::dot(a, b), -1.0, 1.0)) * glm::dot(glm::normalize(c), n);
    }
    return 0.5 * radiance * std::abs(sum);
}

class VxgiFootprintConeTest : public GpuTest {};

TEST_F(VxgiFootprintConeTest, SmallPanelIrradianceNearExactWithoutLeaks) {
    std::vector<PlacedQuad> quads = {
        placedQuad({0, 0, 0}, {0, 1, 0}, {1.5f, 1.5f}, glm::vec3(0.5f)),                               // floor
        placedQuad({0, kPanelHeight, 0}, {0, -1, 0}, {kPanelHalf, kPanelHalf}, glm::vec3(0.5f)),       // panel
        placedQuad({-0.5f, 0.5f, 0}, {-1, 0, 0}, {0.5f, 0.5f}, glm::vec3(0.5f)),                        // wall
    };
    scene::Scene s = makePlacedQuadScene(quads);
    for (scene::Material& m : s.materials) m.metallic = 0.0f;
    s.materials[1].emissive = glm::vec3(kPanelRadiance);
    render::RenderSettings settings;
    settings.output = render::OutputKind::Hdr;
    settings.environmentIntensity = 0.0f;
    settings.vxgi.mode = frame::GiMode::Vxgi;
    settings.vxgi.voxels = 64;
    scene::CameraView camera;
    camera.position = {0.0f, 1.5f, 2.5f};
    camera.forward = glm::normalize(glm::vec3(0.0f, -1.5f, -2.5f));
    camera.up = glm::normalize(glm::cross(glm::cross(camera.forward, glm::vec3(0, 1, 0)), camera.forward));
    render::Renderer renderer(ctx(), shaders(), settings);
    renderer.setScene(s);
    (void)renderer.renderOffscreen(camera, 32, 32);
    ASSERT_NE(renderer.vxgi().grid(), nullptr);
    const ConeGridData grid = readConeGrid(ctx(), renderer.vxgi());

    // The panel as the grid holds it: conservative voxelization marks every voxel the panel touches, each fully
    // covered with the panel's radiance, so the emitter the cones can see is the square of those voxels (8 x 8 voxels
    // of 4.76 cm here: 0.381 m where the panel is 0.3 m). Its exact irradiance is the reference (at the panel's
    // height): the cone tracer's error apart from the voxelization's.
    const passes::VoxelGridBox box = renderer.vxgi().box();
    const int n = int(box.size);
    glm::ivec2 lo(n), hi(-1);
    double radiance = 0.0;
    int count = 0;
    for (int z = 0; z < n; ++z)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                const glm::vec4 v = grid.grid.levels[0][(size_t(z) * n + y) * n + x];
                if (v.r <= 0.5f * kPanelRadiance) continue;
                lo = glm::min(lo, glm::ivec2(x, z));
                hi = glm::max(hi, glm::ivec2(x, z));
                radiance += double(v.r) * v.w;
                ++count;
            }
    ASSERT_GT(count, 0) << "the panel is voxelized";
    radiance /= count;
    ASSERT_EQ(count, (hi.x - lo.x + 1) * (hi.y - lo.y + 1)) << "the panel's voxels fill a rectangle in one layer";
    EXPECT_NEAR(radiance, kPanelRadiance, 0.01 * kPanelRadiance) << "a panel voxel holds the panel's radiance";
    const double x0 = box.gridMin.x + lo.x * box.voxelSize, x1 = box.gridMin.x + (hi.x + 1) * box.voxelSize;
    const double z0 = box.gridMin.z + lo.y * box.voxelSize, z1 = box.gridMin.z + (hi.y + 1) * box.voxelSize;
    const std::vector<glm::dvec3> panel = {
        {x0, kPanelHeight, z0}, {x1, kPanelHeight, z0}, {x1, kPanelHeight, z1}, {x0, kPanelHeight, z1}};
    std::printf("panel voxels: %d (x %.3f .. %.3f, z %.3f .. %.3f), radiance %.3f\n", count, x0, x1, z0, z1, radiance);
    const glm::vec3 up(0, 1, 0);
    const std::vector<glm::vec3> lit = {{0.0f, 0, 0.0f}, {0.25f, 0, 0.1f}, {0.5f, 0, -0.2f}, {0.9f, 0, 0.0f}};
    const glm::vec3 shadowed(-0.9f, 0.0f, 0.0f);  // behind the wall; its mirror point lit[3] sees the panel
    double logError[8] = {};
    for (uint32_t split : {1u, 4u, 7u}) {
        frame::VxgiSettings v = settings.vxgi;
        v.footprintCones = split;
        const gpu::ConeTracePush c = conePush(renderer.vxgi(), v);
        for (const glm::vec3& p : lit) {
            const double exact = polygonIrradiance(panel, glm::dvec3(p), glm::dvec3(up), radiance);
            const double traced = diffuseIrradianceOnCpu(grid, c, p, up, up, glm::vec3(0.0f)).g;
            std::printf("footprint %u, floor (%.2f, %.2f): traced %.4f, exact %.4f, ratio %.3f\n", split, p.x, p.z,
                        traced, exact, traced / exact);
            logError[split] += std::abs(std::log(std::max(traced, 1e-6) / exact)) / double(lit.size());
            if (split > 1u) {
                EXPECT_GT(traced, 0.8 * exact) << "footprint " << split << " at (" << p.x << ", " << p.z << ")";
                EXPECT_LT(traced, 1.45 * exact) << "footprint " << split << " at (" << p.x << ", " << p.z << ")";
            }
        }
        const double behind = diffuseIrradianceOnCpu(grid, c, shadowed, up, up, glm::vec3(0.0f)).g;
        const double mirror = polygonIrradiance(panel, glm::dvec3(lit[3]), glm::dvec3(up), radiance);
        std::printf("footprint %u: mean |log(traced / exact)| %.3f; behind the wall %.5f (%.4f of the mirror's "
                    "exact)\n",
                    split, logError[split], behind, behind / mirror);
        EXPECT_LT(behind, 0.13 * mirror) << "footprint " << split << " sees the panel through the wall";
    }
    for (uint32_t split : {4u, 7u}) {
        EXPECT_LT(logError[split], 0.25) << "footprint " << split;
        EXPECT_LT(logError[split], 0.5 * logError[1]) << "footprint " << split << " gathers the panel no better";
    }
}

}  // namespace
}  // namespace idk::test
