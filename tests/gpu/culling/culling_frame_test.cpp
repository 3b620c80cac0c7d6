// culling_frame_test.cpp: whole frames with GPU culling against the same frames without it: on a procedural
// occluder scene (a wall, hundreds of boxes behind it, some peeking over its edge, some behind the camera) and on
// shared glTF scenes (instanced, skinned), along a camera path that moves and cuts, the culled image equals the
// --culling off image byte for byte (zero false culls), and the GPU counters read back equal the CPU oracle's
// counts (render::cullOracle) and really cull. DamagedHelmet and ToyCar run a path that moves and cuts too. Both rungs of the "mesh-shading" ladder run: the mesh-shader rung
// (task shader culling meshlets) on the shared context, the multi-draw-indirect rung on a --fallback context; their
// images are identical too.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "render/culling_math.hpp"
#include "render/meshlets.hpp"
#include "render/renderer.hpp"
#include "render/vk_graph_backend.hpp"
#include "scene/camera.hpp"
#include "scene/gltf_loader.hpp"
#include "support/gpu_fixture.hpp"
#include "support/placed_quads.hpp"

namespace idk::test {
namespace {

constexpr uint32_t kSize = 96;

// A 24 x 6 wall at z = 0 facing +z, 20 x 20 boxes behind it (z < 0), a row of tall ones whose tops clear the wall,
// and a ring of boxes around the origin at z > 0 (behind cameras that look at the wall from z > 0).
scene::Scene occluderScene() {
    std::vector<PlacedQuad> quads;
    PlacedQuad wall;
    wall.centre = {0.0f, 3.0f, 0.0f};
    wall.halfSize = {12.0f, 3.0f};
    wall.baseColor = {0.7f, 0.6f, 0.5f};
    quads.push_back(wall);
    for (int i = 0; i < 20; ++i)
        for (int k = 0; k < 20; ++k) {
            const bool tall = k == 0 && i % 3 == 0;  // peeks over the wall's top edge
            const glm::vec3 colour(0.2f + 0.04f * float(i), 0.3f, 0.2f + 0.04f * float(k));
            auto faces = boxFaces({-11.0f + 1.15f * float(i), 0.0f, -1.0f - 1.2f * float(k)},
                                  {0.4f, tall ? 3.6f : 0.4f, 0.4f}, colour);
            quads.insert(quads.end(), faces.begin(), faces.end());
        }
    for (int a = 0; a < 12; ++a) {
        const float t = 6.2831853f * float(a) / 12.0f;
        auto faces = boxFaces({6.0f * std::cos(t), 0.0f, 14.0f + 6.0f * std::sin(t)}, {0.5f, 0.5f, 0.5f}, {0.9f, 0.2f, 0.2f});
        quads.insert(quads.end(), faces.begin(), faces.end());
    }
    scene::Scene s = makePlacedQuadScene(quads);
    s.lights.push_back(pointLight({0.0f, 8.0f, 10.0f}, 400.0f));
    return s;
}

scene::CameraView lookAt(glm::vec3 eye, glm::vec3 target, float zfar = 0.0f) {
    scene::CameraView c;
    c.position = eye;
    c.forward = glm::normalize(target - eye);
    glm::vec3 right = glm::normalize(glm::cross(c.forward, glm::vec3(0, 1, 0)));
    c.up = glm::cross(right, c.forward);
    c.zfar = zfar;
    return c;
}

struct PathStats {
    std::vector<uint32_t> frustumDrawn, hizDrawn, tested;
    std::vector<std::vector<uint8_t>> images, frustumImages;  // the hiz frames, the frustum frames
};

class CullingFrameTest : public GpuTest {
protected:
    // Renders `cameras` in order with one renderer per mode (off, frustum, hiz; state kept between frames is
    // exercised) and compares every culled frame with the unculled one byte for byte. Checks the frustum
    // counters against the CPU oracle exactly, and that two-phase occlusion draws a subset of the frustum's.
    void comparePath(const scene::Scene& scene, const std::vector<scene::CameraView>& cameras, const char* what,
                     PathStats& stats) {
        comparePathOn(ctx(), shaders(), scene, cameras, what, stats);
    }
    // `geometry`: the culled G-buffer's path (--geometry); `allowedDiffering`: bytes a culled frame may differ from
    // the unculled one (0 but for the mesh path's triangle order, see HelmetAndToyCar... below).
    static void comparePathOn(vk::Context& ctx, vk::ShaderLibrary& shaders, const scene::Scene& scene,
                              const std::vector<scene::CameraView>& cameras, const char* what, PathStats& stats,
                              frame::GeometryPath geometry = frame::GeometryPath::Auto, size_t allowedDiffering = 0) {
        render::Renderer off(ctx, shaders), frustum(ctx, shaders), hiz(ctx, shaders);
        off.settings().culling.mode = frame::CullingMode::Off;  // hiz is the default
        frustum.settings().culling.mode = frame::CullingMode::Frustum;
        hiz.settings().culling.mode = frame::CullingMode::Hiz;
        frustum.settings().culling.geometry = hiz.settings().culling.geometry = geometry;
        off.setScene(scene);
        frustum.setScene(scene);
        hiz.setScene(scene);
        const render::GpuSceneData data = render::packGpuScene(scene, {});
        const render::MeshletData meshlets = render::buildMeshlets(data);
        const std::vector<gpu::GpuCullDraw> records = render::packCullDraws(data, &meshlets);
        for (size_t c = 0; c < cameras.size(); ++c) {
            render::FrameResult a = off.renderOffscreen(cameras[c], kSize, kSize);
            EXPECT_TRUE(a.culling.empty());
            const glm::mat4 viewProjection = scene::projectionMatrix(cameras[c], 1.0f) * scene::viewMatrix(cameras[c]);
            const std::vector<bool> visible =
                render::cullOracle(records, data.instances, render::frustumView(viewProjection));
            uint32_t tested = 0, drawn = 0, triangles = 0, meshletsOfDrawn = 0;
            for (size_t i = 0; i < records.size(); ++i) {
                tested += (records[i].flags & gpu::kCullSkip) ? 0 : 1;
                if (visible[i]) ++drawn, triangles += records[i].indexCount / 3, meshletsOfDrawn += records[i].meshletCount;
            }
            for (render::Renderer* r : {&frustum, &hiz}) {
                const char* mode = r == &frustum ? "frustum" : "hiz";
                render::FrameResult b = r->renderOffscreen(cameras[c], kSize, kSize);
                ASSERT_EQ(a.display.size(), b.display.size());
                size_t differing = 0;
                for (size_t i = 0; i < a.display.size(); ++i) differing += a.display[i] != b.display[i];
                EXPECT_LE(differing, allowedDiffering) << what << " camera " << c << " " << mode
                                                       << ": culling changed the image";
                ASSERT_FALSE(b.culling.empty());  // the camera first, then any point-shadow cube faces
                const passes::CullingViewStats& s = b.culling[0];
                EXPECT_EQ(s.view, "camera");
                EXPECT_EQ(s.instancesTested, tested) << what << " camera " << c << " " << mode;
                if (r == &frustum) {
                    EXPECT_EQ(s.instancesDrawn, drawn) << what << " camera " << c;
                    if (s.meshlets) {
                        // The task shader sees every meshlet of the drawn instances and draws a subset.
                        EXPECT_EQ(s.meshletsTested, meshletsOfDrawn) << what << " camera " << c;
                        EXPECT_LE(s.meshletsDrawn, s.meshletsTested);
                        EXPECT_LE(s.trianglesDrawn, triangles);
                    } else {
                        EXPECT_EQ(s.trianglesDrawn, triangles) << what << " camera " << c;
                    }
                    stats.frustumDrawn.push_back(s.instancesDrawn);
                    stats.frustumImages.push_back(b.display);
                } else {
                    stats.images.push_back(b.display);
                    EXPECT_LE(s.instancesDrawn, drawn) << what << " camera " << c << ": occlusion drew more than the frustum";
                    stats.hizDrawn.push_back(s.instancesDrawn);
                }
                std::cout << "[ culling ] " << what << " camera " << c << " " << mode << ": " << s.instancesDrawn
                          << " of " << s.instancesTested << " drawn\n";
            }
            stats.tested.push_back(tested);
        }
    }
};

TEST_F(CullingFrameTest, OccluderSceneAlongAMovingAndCuttingPathIsUnchanged) {
    const scene::Scene scene = occluderScene();
    std::vector<scene::CameraView> path = {
        lookAt({0, 4, 12}, {0, 3, 0}),       // the wall, tall boxes peeking over it, the ring behind the camera
        lookAt({3, 4, 10}, {0, 3, -2}),      // moving
        lookAt({6, 4, 8}, {0, 3, -4}, 40.0f),  // moving, finite far plane
        lookAt({-20, 6, -12}, {0, 0, -12}),  // cut: from the side, over the boxes
        lookAt({0, 2, 30}, {0, 1, 14}),      // cut: at the ring, the wall far behind it
        lookAt({0, 4, 12}, {0, 3, 0}),       // cut back to the first view
        lookAt({0, 4, 12}, {0, 3, 0}),       // still: the visibility bits of the frame before apply
    };
    PathStats s;
    comparePath(scene, path, "occluder", s);
    ASSERT_EQ(s.hizDrawn.size(), path.size());
    for (size_t c = 0; c < path.size(); ++c) EXPECT_LT(s.frustumDrawn[c], s.tested[c]) << "camera " << c;
    // The first frame has no visibility yet: its early phase draws nothing, so its pyramid is empty and the late
    // phase draws the frustum's set. Facing the wall again with last frame's bits, the boxes behind it are
    // occluded: two-phase culling draws under a quarter of what the frustum keeps.
    EXPECT_EQ(s.hizDrawn[0], s.frustumDrawn[0]);
    EXPECT_LT(4 * s.hizDrawn[6], s.frustumDrawn[6]);
}

TEST_F(CullingFrameTest, SharedScenesAreUnchanged) {
    const std::string root = std::string(IDK_SHARED_DIR) + "/scenes/";
    {
        const scene::Scene s = scene::loadGltf(root + "SimpleInstancing/glTF-Binary/SimpleInstancing.glb");
        const scene::CameraView base = scene::defaultCamera(s);
        scene::CameraView left = base;
        left.forward = glm::normalize(base.forward + 0.6f * glm::cross(base.forward, base.up));
        PathStats stats;
        comparePath(s, {base, left, base}, "SimpleInstancing", stats);
    }
    {
        // Skinned: its draws are never culled (their rest-pose boxes do not bound the animated vertices).
        const scene::Scene s = scene::loadGltf(root + "BrainStem/glTF-Binary/BrainStem.glb");
        PathStats stats;
        comparePath(s, {scene::defaultCamera(s), scene::defaultCamera(s)}, "BrainStem", stats);
    }
}

// A path around the scene's default view: the view, a step to the side (moving), a cut to the far side looking
// back, a cut to a view that sees nothing (the frustum culls everything), and a cut back to the view.
std::vector<scene::CameraView> movingAndCuttingPath(const scene::Scene& s) {
    const scene::CameraView base = scene::defaultCamera(s);
    const glm::vec3 target = s.bounds.centre();
    const float distance = std::max(glm::length(base.position - target), 1e-3f);
    const glm::vec3 side = glm::normalize(glm::cross(base.forward, base.up));
    scene::CameraView moved = lookAt(base.position + 0.15f * distance * side, target);
    scene::CameraView behind = lookAt(2.0f * target - base.position + 0.3f * distance * side, target);
    scene::CameraView away = lookAt(base.position, base.position - base.forward * distance);
    for (scene::CameraView* c : {&moved, &behind, &away}) c->yfov = base.yfov, c->znear = base.znear, c->zfar = base.zfar;
    return {base, moved, behind, away, base, base};
}

// Zero false culls on the MDI path: identical pixels. The mesh path is not bit-identical to the vertex path that
// draws the unculled frame: on ToyCar (the moved camera) 1 byte of 36864 differs even with every meshlet drawn
// (task-shader culling disabled) and with meshlets built in index order (meshopt_buildMeshletsScan, no
// vertex-cache reordering), so it is not a cull but lavapipe's mesh-pipeline rasterization. There the culled
// frames must equal each other (frustum vs two-phase Hi-Z, both drawing meshlets) and stay within 16 bytes of the
// unculled frame.
TEST_F(CullingFrameTest, HelmetAndToyCarAlongMovingAndCuttingPathsAreUnchanged) {
    const std::string root = std::string(IDK_SHARED_DIR) + "/scenes/";
    const bool mesh = ctx().capabilities().meshShaderExt;
    for (const char* file : {"DamagedHelmet/glTF-Binary/DamagedHelmet.glb", "ToyCar/glTF/ToyCar.gltf"}) {
        const scene::Scene s = scene::loadGltf(root + file);
        const std::vector<scene::CameraView> path = movingAndCuttingPath(s);
        PathStats mdi;
        comparePathOn(ctx(), shaders(), s, path, file, mdi, frame::GeometryPath::Mdi);
        ASSERT_EQ(mdi.frustumDrawn.size(), path.size());
        EXPECT_GT(mdi.frustumDrawn[0], 0u) << file << ": the default view sees the scene";
        EXPECT_EQ(mdi.frustumDrawn[3], 0u) << file << ": the view away from the scene culls every draw";
        if (!mesh) continue;
        PathStats meshlets;
        comparePathOn(ctx(), shaders(), s, path, file, meshlets, frame::GeometryPath::Mesh, 16);
        ASSERT_EQ(meshlets.images.size(), path.size());
        for (size_t c = 0; c < path.size(); ++c)
            EXPECT_TRUE(meshlets.images[c] == meshlets.frustumImages[c]) << file << " camera " << c
                                                                         << ": mesh path, hiz and frustum differ";
        EXPECT_EQ(meshlets.hizDrawn, mdi.hizDrawn) << file << ": both paths cull the same instances";
    }
}

// The benchmarks' ground truth (bench/culling_bench.cpp): the surface-ID buffer of the unculled frame names the
// visible draws. On the occluder scene facing the wall: every visible draw is in the CPU frustum oracle's set, the
// wall is visible, most boxes in the frustum are not; and two-phase culling, warm, draws every visible draw (its
// drawn set follows from the visibility bits before and after the frame and the frustum oracle).
TEST_F(CullingFrameTest, SurfaceIdsNameVisibleDrawsAndHizDrawsThemAll) {
    const scene::Scene scene = occluderScene();
    const scene::CameraView camera = lookAt({0, 4, 12}, {0, 3, 0});
    render::Renderer off(ctx(), shaders()), hiz(ctx(), shaders());
    off.settings().culling.mode = frame::CullingMode::Off;
    hiz.settings().culling.mode = frame::CullingMode::Hiz;
    off.setScene(scene);
    hiz.setScene(scene);
    const std::vector<glm::uvec2> ids = off.renderSurfaceIds(camera, kSize, kSize);
    const render::GpuSceneData& data = off.gpuScene()->data();
    const std::vector<gpu::GpuCullDraw> records = render::packCullDraws(data);
    const std::vector<bool> inFrustum = render::cullOracle(
        records, data.instances, render::frustumView(scene::projectionMatrix(camera, 1.0f) * scene::viewMatrix(camera)));
    std::vector<bool> visible(records.size(), false);
    size_t background = 0;
    for (const glm::uvec2& id : ids) {
        if (id.x == UINT32_MAX) {
            ++background;
            continue;
        }
        ASSERT_LT(id.x, records.size());
        ASSERT_LT(id.y, data.draws[id.x].indexCount / 3) << "triangle id past the draw's triangles";
        visible[id.x] = true;
    }
    EXPECT_GT(background, 0u) << "the sky above the wall";
    EXPECT_TRUE(visible[0]) << "the wall (the scene's first quad)";
    size_t visibleCount = 0, frustumCount = 0;
    for (size_t i = 0; i < records.size(); ++i) {
        if (visible[i]) {
            EXPECT_TRUE(inFrustum[i]) << "draw " << i << " is visible outside the frustum";
        }
        visibleCount += visible[i];
        frustumCount += inFrustum[i];
    }
    EXPECT_LT(4 * visibleCount, frustumCount) << "the wall hides most boxes in the frustum";
    hiz.renderOffscreen(camera, kSize, kSize);
    hiz.renderOffscreen(camera, kSize, kSize);
    const std::vector<uint32_t> before = hiz.cullingVisibility();
    const render::FrameResult frame = hiz.renderOffscreen(camera, kSize, kSize);
    const std::vector<uint32_t> after = hiz.cullingVisibility();
    ASSERT_EQ(before.size(), records.size());
    ASSERT_EQ(after.size(), records.size());
    size_t drawn = 0;
    for (size_t i = 0; i < records.size(); ++i) {
        const bool drawnNow = before[i] != 0 ? bool(inFrustum[i]) : after[i] != 0;
        if (visible[i]) {
            EXPECT_TRUE(drawnNow) << "visible draw " << i << " was culled";
        }
        drawn += drawnNow;
    }
    ASSERT_FALSE(frame.culling.empty());
    EXPECT_EQ(frame.culling[0].instancesDrawn, drawn) << "the drawn set derived from the bits matches the counter";
    EXPECT_LT(drawn, frustumCount);
}

// The viewer's path (Renderer::renderFrame): each frame's FrameInfo carries the previous frame's counters per view
// (the Frame panel's culling table) and geometry path; they equal the CPU oracle's frustum counts.
TEST_F(CullingFrameTest, RenderFrameCarriesThePreviousFramesCounters) {
    const scene::Scene scene = occluderScene();
    const scene::CameraView camera = lookAt({0, 4, 12}, {0, 3, 0});
    const render::GpuSceneData data = render::packGpuScene(scene, {});
    const std::vector<bool> visible = render::cullOracle(
        render::packCullDraws(data), data.instances,
        render::frustumView(scene::projectionMatrix(camera, 1.0f) * scene::viewMatrix(camera)));
    vk::ImageDesc desc;
    desc.format = VK_FORMAT_R8G8B8A8_UNORM;
    desc.extent = {kSize, kSize, 1};
    desc.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;  // as a swapchain image (transfer usage is implied)
    desc.name = "viewer target";
    vk::Image image = ctx().createImage(desc);
    {
        render::Renderer r(ctx(), shaders());
        r.settings().culling.mode = frame::CullingMode::Frustum;
        r.settings().culling.geometry = frame::GeometryPath::Mdi;
        r.setScene(scene);
        render::FrameTarget target;
        target.image = render::physicalOf(image);
        target.finalUse = graph::FinalUse{graph::Access::TransferSrc};
        const render::FrameInfo first = r.renderFrame(camera, target);
        EXPECT_TRUE(first.culling.empty()) << "no frame before the first";
        const render::FrameInfo second = r.renderFrame(camera, target);
        ASSERT_EQ(second.culling.size(), 7u) << "the camera, then the point light's six cube faces";
        EXPECT_EQ(second.culling[0].view, "camera");
        EXPECT_EQ(second.culling[0].instancesDrawn, uint32_t(std::count(visible.begin(), visible.end(), true)));
        EXPECT_EQ(second.geometryPath, "mdi");
        ctx().waitIdle();
    }
    ctx().destroy(image);
}

// --cull-freeze: culling keeps the frustum of the frame it was turned on while the camera moves on, and follows
// the camera again once it is turned off (counts against the CPU oracle of each view).
TEST_F(CullingFrameTest, FreezeKeepsTheFrozenFrustum) {
    const scene::Scene scene = occluderScene();
    const render::GpuSceneData data = render::packGpuScene(scene, {});
    const std::vector<gpu::GpuCullDraw> records = render::packCullDraws(data);
    auto oracleDrawn = [&](const scene::CameraView& c) {
        const glm::mat4 vp = scene::projectionMatrix(c, 1.0f) * scene::viewMatrix(c);
        const std::vector<bool> v = render::cullOracle(records, data.instances, render::frustumView(vp));
        return uint32_t(std::count(v.begin(), v.end(), true));
    };
    const scene::CameraView a = lookAt({0, 4, 12}, {0, 3, 0}), b = lookAt({0, 2, 30}, {0, 1, 14});
    ASSERT_NE(oracleDrawn(a), oracleDrawn(b));
    render::Renderer r(ctx(), shaders());
    r.settings().culling.mode = frame::CullingMode::Hiz;  // occlusion pauses while frozen: frustum counts apply
    r.settings().culling.freeze = true;
    r.setScene(scene);
    r.renderOffscreen(a, kSize, kSize);
    render::FrameResult frozen = r.renderOffscreen(b, kSize, kSize);
    ASSERT_EQ(frozen.culling.size(), 7u) << "the camera, then the point light's six cube faces";
    EXPECT_EQ(frozen.culling[0].instancesDrawn, oracleDrawn(a)) << "culled with the frozen view a";
    r.settings().culling.mode = frame::CullingMode::Frustum;
    r.settings().culling.freeze = false;
    render::FrameResult live = r.renderOffscreen(b, kSize, kSize);
    ASSERT_EQ(live.culling.size(), 7u);
    EXPECT_EQ(live.culling[0].instancesDrawn, oracleDrawn(b)) << "culled with the live view b";
}

// The mesh rung (shared context, where the device has VK_EXT_mesh_shader) and the MDI rung (--fallback context)
// draw identical frames along the occluder path, and each equals its unculled frame.
TEST_F(CullingFrameTest, MeshAndMdiRungsGiveIdenticalImages) {
    if (ctx().ladder("mesh shading").chosen != vk::Rung::Native)
        GTEST_SKIP() << "device lacks VK_EXT_mesh_shader: only the MDI rung runs (the other tests cover it)";
    const scene::Scene scene = occluderScene();
    const std::vector<scene::CameraView> path = {lookAt({0, 4, 12}, {0, 3, 0}), lookAt({2, 4, 11}, {0, 3, -1}),
                                                 lookAt({-20, 6, -12}, {0, 0, -12})};
    PathStats mesh, mdi;
    comparePath(scene, path, "mesh rung", mesh);
    vk::ContextDesc desc = ctx().desc();
    desc.forceFallbackRungs = true;  // what `idk render --fallback` selects
    uint32_t fallbackErrors = 0;
    {
        vk::Context fallbackCtx(desc);
        vk::ShaderLibrary fallbackShaders(fallbackCtx);
        EXPECT_EQ(fallbackCtx.ladder("mesh shading").chosen, vk::Rung::Fallback);
        comparePathOn(fallbackCtx, fallbackShaders, scene, path, "mdi rung", mdi);
        fallbackCtx.waitIdle();
        fallbackErrors = fallbackCtx.validationErrors();
    }
    EXPECT_EQ(fallbackErrors, 0u) << "validation errors on the fallback context";
    ASSERT_EQ(mesh.images.size(), mdi.images.size());
    for (size_t c = 0; c < mesh.images.size(); ++c)
        EXPECT_TRUE(mesh.images[c] == mdi.images[c]) << "camera " << c << ": the rungs' images differ";
    EXPECT_EQ(mesh.hizDrawn, mdi.hizDrawn) << "both rungs cull the same instances";
}

}  // namespace
}  // namespace idk::test
