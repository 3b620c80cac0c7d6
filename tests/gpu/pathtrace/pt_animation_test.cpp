// pt_animation_test.cpp: the path tracer renders the posed scene (`idk render --pathtrace --time T`). The GPU
// tracer poses skins and morphs on the GPU (render/pt_pose.hpp: the rasterizer's skinning compute, BLAS refit,
// TLAS rebuilt); the CPU reference poses them itself (pathtrace::PtPosing::Cpu: world-space copies, BVHs built),
// and is the oracle:
// - at the same seed, GPU-posed and CPU-posed tracing of SimpleSkin, Fox and AnimatedMorphCube at T > 0 (and the
//   Fox's rest pose) agree pixel by pixel (>= 90% of the pixels within 1e-3 relative; paths whose hit point moves
//   by a rounding step may take another branch) and in mean radiance (1%), while the rest pose's image is far off;
// - a scene without skins or morphs is traced bit for bit as before (nothing is GPU-posed);
// - PathTracer::setPose(T2) on a tracer built at T1 (refit + TLAS rebuild) gives a tracer built at T2's image
//   bit for bit (every pixel within 1e-3 relative; measured: identical. A tracer's second render used to differ
//   from its first in a few pixels, 4 of 4096 here: the tracer had released its textures after construction and
//   the second render sampled freed slots; it now keeps them for its lifetime);
// - a skinned Fox mid-run path-traced at T has the rasterizer's silhouette at the same T (coverage masks: the
//   tracer's first-hit depth guide > 0 against the raster's HDR alpha), and not the rest pose's.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "gpu/pathtrace/pt_image_util.hpp"
#include "pathtrace/cpu_path_tracer.hpp"
#include "pathtrace/pt_scene.hpp"
#include "render/path_tracer.hpp"
#include "render/renderer.hpp"
#include "scene/animation.hpp"
#include "scene/gltf_loader.hpp"
#include "support/gpu_fixture.hpp"

namespace idk::test {
namespace {

constexpr uint32_t kSize = 96;

std::vector<bool> rasterMask(const scene::Scene& scene, const scene::CameraView& camera) {
    render::RenderSettings settings;
    settings.output = render::OutputKind::Hdr;
    render::Renderer renderer(sharedContext(), sharedShaders(), settings);
    renderer.setScene(scene);
    const core::ImageRgba32f image = renderer.renderOffscreen(camera, kSize, kSize).image;
    std::vector<bool> mask(size_t(kSize) * kSize);
    for (size_t i = 0; i < mask.size(); ++i) mask[i] = image.pixels[4 * i + 3] > 0.5f;
    return mask;
}

std::vector<bool> traceMask(const scene::Scene& scene, const scene::CameraView& camera) {
    render::PathTracerOptions options;
    options.traversal = render::PtTraversal::Bvh;
    options.readGuides = true;
    render::PathTracer tracer(sharedContext(), sharedShaders(), scene, options);
    render::PathTraceSettings s;
    s.spp = 1;
    s.maxDepth = 1;
    const render::PathTraceResult r = tracer.render(camera, kSize, kSize, s);
    std::vector<bool> mask(size_t(kSize) * kSize);
    for (size_t i = 0; i < mask.size(); ++i) mask[i] = r.depth.pixels[4 * i] > 0.0f;
    return mask;
}

struct MaskMatch {
    double iou = 0.0;
    size_t offEdgeMismatches = 0;  // pixels that differ although their 3x3 raster neighbourhood is all one side
    size_t covered = 0;
};

// The tracer's one jittered sample per pixel may fall on either side of a silhouette crossing the pixel, so pixels
// on the raster mask's boundary (mixed 3x3 neighbourhood) may differ; every other pixel must agree.
MaskMatch match(const std::vector<bool>& traced, const std::vector<bool>& raster) {
    MaskMatch m;
    size_t both = 0, either = 0;
    const int n = int(kSize);
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const size_t i = size_t(y) * kSize + x;
            both += traced[i] && raster[i];
            either += traced[i] || raster[i];
            m.covered += raster[i];
            bool mixed = false;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const int qx = x + dx, qy = y + dy;
                    if (qx >= 0 && qy >= 0 && qx < n && qy < n) mixed |= raster[size_t(qy) * kSize + qx] != raster[i];
                }
            if (!mixed && traced[i] != raster[i]) ++m.offEdgeMismatches;
        }
    m.iou = either ? double(both) / double(either) : 1.0;
    return m;
}

class PtAnimationTest : public GpuTest {};

constexpr uint32_t kAgreeSize = 64;
const glm::vec3 kSky(0.6f, 0.7f, 0.8f);

pathtrace::PtSettings agreeSettings() {
    pathtrace::PtSettings s;
    s.spp = 4;
    s.seed = 31;
    s.maxDepth = 3;
    return s;
}

scene::CameraView fitCamera(const scene::Scene& scene) {
    const float radius = 0.5f * glm::length(scene.bounds.max - scene.bounds.min);
    return scene::orbitCamera(scene.bounds.centre(), 0.9f * scene::autoFitDistance(radius), glm::radians(70.0f),
                              glm::radians(75.0f));
}

core::ImageRgba32f gpuTrace(const scene::Scene& scene, const pathtrace::PathTraceScene& pts,
                            const scene::CameraView& camera) {
    render::PathTracerOptions options;
    options.traversal = render::PtTraversal::Bvh;
    render::PathTracer tracer(sharedContext(), sharedShaders(), scene, pts, options);
    return tracer.render(camera, kAgreeSize, kAgreeSize, agreeSettings()).image;
}

// Pixels whose RGB agree within 1e-3 relative.
size_t samePixels(const core::ImageRgba32f& a, const core::ImageRgba32f& b) {
    size_t same = 0;
    for (size_t p = 0; p < a.pixels.size() / 4; ++p) {
        bool close = true;
        for (int k = 0; k < 3; ++k) close &= std::abs(a.pixels[4 * p + k] - b.pixels[4 * p + k]) <= 1e-3f * (1.0f + std::abs(b.pixels[4 * p + k]));
        same += close;
    }
    return same;
}

struct PoseCase {
    const char* file;  // under ../shared/scenes
    double time;       // < 0: the rest pose (no animation evaluated)
    uint32_t animation;
};

void PrintTo(const PoseCase& c, std::ostream* os) { *os << c.file << " at T = " << c.time; }

class PtPoseAgreementTest : public GpuTest, public ::testing::WithParamInterface<PoseCase> {};

TEST_P(PtPoseAgreementTest, GpuPoseGivesTheCpuPosesSamples) {
    const PoseCase c = GetParam();
    const scene::Scene rest = scene::loadGltf(std::string(IDK_SHARED_DIR) + "/scenes/" + c.file);
    scene::Scene posed = rest;
    if (c.time >= 0.0) scene::evaluateAnimations(posed, c.time, c.animation);
    const scene::CameraView camera = fitCamera(rest);
    const pathtrace::PathTraceScene cpuPts = pathtrace::buildPathTraceScene(posed, nullptr, 1.0f, kSky);
    const pathtrace::PathTraceScene gpuPts =
        pathtrace::buildPathTraceScene(posed, nullptr, 1.0f, kSky, pathtrace::PtPosing::Gpu);
    ASSERT_FALSE(gpuPts.gpuPosedInstances.empty()) << "the GPU poses something";
    ASSERT_FALSE(gpuPts.cpuPosedDeformation);

    const core::ImageRgba32f cpu = pathtrace::renderReference(cpuPts, camera, kAgreeSize, kAgreeSize, agreeSettings());
    const core::ImageRgba32f gpu = gpuTrace(posed, gpuPts, camera);
    EXPECT_EQ(nonFiniteCount(gpu), 0u);
    const size_t pixels = size_t(kAgreeSize) * kAgreeSize, same = samePixels(gpu, cpu);
    const double meanCpu = meanRadiance(cpu), meanGpu = meanRadiance(gpu), error = rmse(gpu, cpu);
    std::printf("%s at T = %.2f: GPU-posed vs CPU-posed tracing: %zu of %zu pixels equal, mean %.5f vs %.5f, "
                "RMSE %.5f\n", c.file, c.time, same, pixels, meanGpu, meanCpu, error);
    EXPECT_GT(double(same), 0.9 * double(pixels));
    EXPECT_NEAR(meanGpu, meanCpu, 0.01 * meanCpu);
    if (c.time < 0.0) return;
    // The control: the rest pose is another image (the pose was applied, not left at the BLAS's build pose).
    const pathtrace::PathTraceScene restPts = pathtrace::buildPathTraceScene(rest, nullptr, 1.0f, kSky);
    const double restError = rmse(pathtrace::renderReference(restPts, camera, kAgreeSize, kAgreeSize, agreeSettings()), cpu);
    std::printf("%s at T = %.2f: rest pose vs posed RMSE %.5f\n", c.file, c.time, restError);
    EXPECT_LT(error, 0.25 * restError);
}

INSTANTIATE_TEST_SUITE_P(Scenes, PtPoseAgreementTest,
                         ::testing::Values(PoseCase{"SimpleSkin/glTF/SimpleSkin.gltf", 2.0, 0},
                                           PoseCase{"Fox/glTF-Binary/Fox.glb", 0.55, 2},
                                           PoseCase{"Fox/glTF-Binary/Fox.glb", -1.0, 0},
                                           PoseCase{"AnimatedMorphCube/glTF-Binary/AnimatedMorphCube.glb", 1.0, 0}),
                         [](const auto& info) {
                             std::string name = std::filesystem::path(info.param.file).stem().string();
                             return name + (info.param.time < 0.0 ? "Rest" : "Posed");
                         });

TEST_F(PtAnimationTest, StaticSceneIsTracedAsBefore) {
    const scene::Scene sc = scene::loadGltf(std::string(IDK_SHARED_DIR) + "/scenes/SimpleInstancing/glTF-Binary/SimpleInstancing.glb");
    const pathtrace::PathTraceScene cpuPts = pathtrace::buildPathTraceScene(sc, nullptr, 1.0f, kSky);
    const pathtrace::PathTraceScene gpuPts =
        pathtrace::buildPathTraceScene(sc, nullptr, 1.0f, kSky, pathtrace::PtPosing::Gpu);
    EXPECT_TRUE(gpuPts.gpuPosedInstances.empty());
    ASSERT_EQ(gpuPts.geometries.size(), cpuPts.geometries.size());
    const scene::CameraView camera = fitCamera(sc);
    const core::ImageRgba32f a = gpuTrace(sc, cpuPts, camera), b = gpuTrace(sc, gpuPts, camera);
    ASSERT_EQ(a.pixels.size(), b.pixels.size());
    size_t differing = 0;
    for (size_t i = 0; i < a.pixels.size(); ++i) differing += a.pixels[i] != b.pixels[i];
    EXPECT_EQ(differing, 0u);
    EXPECT_GT(meanRadiance(a), 0.0);
}

TEST_F(PtAnimationTest, SetPoseRefitsToTheNewTime) {
    const scene::Scene rest = scene::loadGltf(std::string(IDK_SHARED_DIR) + "/scenes/Fox/glTF-Binary/Fox.glb");
    scene::Scene at1 = rest, at2 = rest;
    scene::evaluateAnimations(at1, 0.2, 2);
    scene::evaluateAnimations(at2, 0.55, 2);
    const scene::CameraView camera = fitCamera(rest);
    render::PathTracerOptions options;
    options.traversal = render::PtTraversal::Bvh;
    options.environment = std::filesystem::path();  // constant grey: no HDR file needed
    render::PathTracer refit(sharedContext(), sharedShaders(), at1, options);
    const core::ImageRgba32f before = refit.render(camera, kAgreeSize, kAgreeSize, agreeSettings()).image;
    refit.setPose(at2);
    const core::ImageRgba32f moved = refit.render(camera, kAgreeSize, kAgreeSize, agreeSettings()).image;
    render::PathTracer built(sharedContext(), sharedShaders(), at2, options);
    const core::ImageRgba32f expected = built.render(camera, kAgreeSize, kAgreeSize, agreeSettings()).image;
    const size_t pixels = size_t(kAgreeSize) * kAgreeSize, same = samePixels(moved, expected);
    std::printf("Fox setPose 0.2 s -> 0.55 s (refit) vs built at 0.55 s: %zu of %zu pixels equal, RMSE %.5f "
                "(before the pose: %.5f)\n", same, pixels, rmse(moved, expected), rmse(before, expected));
    EXPECT_EQ(same, pixels);
    EXPECT_LT(rmse(moved, expected), 0.25 * rmse(before, expected));
    // A scene that is not the tracer's is refused with a clear error.
    scene::Scene other = at2;
    other.instances.pop_back();
    EXPECT_THROW(refit.setPose(other), std::invalid_argument);
}

TEST_F(PtAnimationTest, SkinnedFoxAtTimeTHasTheRasterSilhouette) {
    const std::string path = std::string(IDK_SHARED_DIR) + "/scenes/Fox/glTF-Binary/Fox.glb";
    const scene::Scene rest = scene::loadGltf(path);
    scene::Scene posed = rest;
    scene::evaluateAnimations(posed, 0.55, 2);  // clip 2 "Run", mid-stride
    const float radius = 0.5f * glm::length(rest.bounds.max - rest.bounds.min);
    const scene::CameraView camera = scene::orbitCamera(rest.bounds.centre(), 0.9f * scene::autoFitDistance(radius),
                                                        glm::radians(90.0f), glm::radians(80.0f));
    const std::vector<bool> traced = traceMask(posed, camera);
    const MaskMatch same = match(traced, rasterMask(posed, camera));
    const MaskMatch other = match(traced, rasterMask(rest, camera));
    std::printf("Fox at T = 0.55 s: path-traced vs raster silhouette IoU %.4f (%zu off-edge mismatches of %zu covered); "
                "vs the raster's rest pose IoU %.4f (%zu)\n",
                same.iou, same.offEdgeMismatches, same.covered, other.iou, other.offEdgeMismatches);
    ASSERT_GT(same.covered, size_t(kSize * kSize / 20)) << "the fox is in view";
    EXPECT_GE(same.iou, 0.93);
    EXPECT_LE(same.offEdgeMismatches, same.covered / 200) << "away from the silhouette's edge the masks agree";
    // The control: the pose matters at this T (the rest pose's silhouette is clearly another one).
    EXPECT_LT(other.iou, 0.9 * same.iou);
    EXPECT_GT(other.offEdgeMismatches, same.covered / 20);
}

}  // namespace
}  // namespace idk::test
