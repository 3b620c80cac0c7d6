// pt_animation_test.cpp: the path tracer renders the posed scene (`idk render --pathtrace --time T`): a skinned
// Fox mid-run path-traced at T has the rasterizer's silhouette at the same T (coverage masks: the tracer's
// first-hit depth guide > 0 against the raster's HDR alpha), and not the rest pose's. The tracer poses skins and
// morphs on the CPU when it builds its scene (pathtrace::buildPathTraceScene: world-space copies, BVHs rebuilt);
// the raster skins on the GPU (render/gpu_animation), so the two poses come from independent code.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

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
