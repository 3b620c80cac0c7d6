// blend_order_test.cpp: BLEND materials through the transparency pass (passes/transparency.cpp) against CPU
// oracles, 128x128 linear HDR frames with a constant environment (radiance 0.5: the sky behind everything).
//  * Order: two overlapping unlit BLEND quads (far red alpha 0.6, near blue alpha 0.5) and an opaque unlit
//    green quad in front of one corner, declared far-first and near-first: both frames must equal the CPU
//    "over" composite of the quads each pixel centre sees, farthest first (RGB and the coverage alpha), within
//    2e-3 (RGBA16F steps are 2.4e-4 at 0.5). Pixels within one pixel of a quad edge are skipped. Behind the opaque
//    quad nothing blends (depth test against the G-buffer depth).
//  * The CPU sort itself (render::sortBlendDraws): farthest first, and reversed for an eye on the other side.
//  * Forward = deferred: a lit, shadowed quad drawn OPAQUE (G-buffer + deferred lighting) and BLEND with alpha 1
//    (forward) agrees within 2% + 2e-3 per channel (the G-buffer's 8-bit storage of albedo and roughness).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "render/blend_draws.hpp"
#include "render/draw_bounds.hpp"
#include "render/renderer.hpp"
#include "support/gpu_fixture.hpp"
#include "support/placed_quads.hpp"

namespace idk::test {
namespace {

constexpr uint32_t kSize = 128;

scene::CameraView frontCamera() {
    scene::CameraView c;
    c.position = glm::vec3(0.0f, 0.0f, 3.0f);
    c.znear = 0.1f;
    c.zfar = 100.0f;
    return c;
}

render::FrameResult renderHdr(vk::Context& ctx, vk::ShaderLibrary& shaders, const scene::Scene& scene,
                              float environmentIntensity = 1.0f, uint32_t shadowLights = 8) {
    render::RenderSettings settings;
    settings.pointShadows.maxLights = shadowLights;
    settings.output = render::OutputKind::Hdr;
    settings.environment = std::filesystem::path();  // constant radiance 0.5
    settings.environmentIntensity = environmentIntensity;
    render::Renderer renderer(ctx, shaders, settings);
    renderer.setScene(scene);
    return renderer.renderOffscreen(frontCamera(), kSize, kSize);
}

std::vector<PlacedQuad> orderQuads(bool farFirst) {
    PlacedQuad far, near, opaque;
    far.centre = {-0.25f, 0.1f, -0.6f};
    far.baseColor = {1.0f, 0.0f, 0.0f};
    far.alpha = 0.6f;
    near.centre = {0.2f, -0.1f, 0.0f};
    near.baseColor = {0.0f, 0.0f, 1.0f};
    near.alpha = 0.5f;
    opaque.centre = {-0.6f, 0.55f, 0.4f};
    opaque.halfSize = {0.3f, 0.3f};
    opaque.baseColor = {0.0f, 1.0f, 0.0f};
    for (PlacedQuad* q : {&far, &near}) q->alphaMode = scene::AlphaMode::Blend;
    for (PlacedQuad* q : {&far, &near, &opaque}) q->unlit = true;
    return farFirst ? std::vector<PlacedQuad>{far, near, opaque} : std::vector<PlacedQuad>{near, far, opaque};
}

class BlendOrderTest : public GpuTest {};

TEST_F(BlendOrderTest, OverlappingQuadsCompositeFarthestFirstWhateverTheDeclarationOrder) {
    const scene::CameraView camera = frontCamera();
    glm::dmat4 inv = glm::inverse(glm::dmat4(scene::projectionMatrix(camera, 1.0f) * scene::viewMatrix(camera)));
    for (bool farFirst : {true, false}) {
        std::vector<PlacedQuad> quads = orderQuads(farFirst);
        render::FrameResult frame = renderHdr(ctx(), shaders(), makePlacedQuadScene(quads));
        ASSERT_NE(std::find(frame.passesRun.begin(), frame.passesRun.end(), "transparency"), frame.passesRun.end());

        // Per pixel: the quads the centre ray crosses (all of them, not only the nearest), sorted far to near.
        auto covering = [&](double px, double py) {
            glm::dvec2 ndc(px / kSize * 2.0 - 1.0, py / kSize * 2.0 - 1.0);
            glm::dvec4 a = inv * glm::dvec4(ndc, 0.0, 1.0), b = inv * glm::dvec4(ndc, 0.5, 1.0);
            glm::dvec3 o = glm::dvec3(a) / a.w, d = glm::normalize(glm::dvec3(b) / b.w - o);
            std::vector<std::pair<double, uint32_t>> hits;
            for (uint32_t q = 0; q < quads.size(); ++q)
                if (auto h = castRay({quads[q]}, o, d, 0.0, 1e9)) hits.push_back({h->t, q});
            std::sort(hits.rbegin(), hits.rend());
            return hits;
        };
        uint32_t checked = 0, overlap = 0, hidden = 0, failures = 0;
        std::string first;
        for (uint32_t py = 1; py + 1 < kSize; ++py) {
            for (uint32_t px = 1; px + 1 < kSize; ++px) {
                auto hits = covering(px + 0.5, py + 0.5);
                bool stable = true;  // the same quads at the pixel's corners: not on an edge
                for (int c = 0; c < 4 && stable; ++c) {
                    auto h = covering(px + 0.5 + ((c & 1) ? 1.0 : -1.0), py + 0.5 + ((c & 2) ? 1.0 : -1.0));
                    auto sameQuad = [](auto& x, auto& y) { return x.second == y.second; };
                    stable = h.size() == hits.size() && std::equal(h.begin(), h.end(), hits.begin(), sameQuad);
                }
                if (!stable) continue;
                glm::dvec4 want(0.5, 0.5, 0.5, 0.0);  // the sky, alpha 0
                for (auto [t, q] : hits) {
                    const PlacedQuad& quad = quads[q];
                    double a = quad.alphaMode == scene::AlphaMode::Blend ? quad.alpha : 1.0;
                    want = glm::dvec4(glm::dvec3(quad.baseColor) * a + glm::dvec3(want) * (1.0 - a),
                                      a + want.a * (1.0 - a));
                }
                const float* got = &frame.image.pixels[(size_t(py) * kSize + px) * 4];
                bool ok = true;
                for (int ch = 0; ch < 4; ++ch) ok &= std::abs(got[ch] - want[ch]) <= 2e-3;
                ++checked;
                overlap += hits.size() == 2 && quads[hits[1].second].alphaMode == scene::AlphaMode::Blend;
                hidden += hits.size() >= 2 && quads[hits.back().second].alphaMode == scene::AlphaMode::Opaque;
                if (!ok && failures++ == 0)
                    first = std::to_string(px) + "," + std::to_string(py) + " got (" + std::to_string(got[0]) + ", " +
                            std::to_string(got[1]) + ", " + std::to_string(got[2]) + ", " + std::to_string(got[3]) +
                            ") want (" + std::to_string(want.r) + ", " + std::to_string(want.g) + ", " +
                            std::to_string(want.b) + ", " + std::to_string(want.a) + ")";
            }
        }
        EXPECT_EQ(failures, 0u) << (farFirst ? "far first" : "near first") << ": first " << first;
        EXPECT_GT(overlap, 400u) << "pixels where the two BLEND quads overlap";
        EXPECT_GT(hidden, 100u) << "pixels where the opaque quad hides a BLEND quad";
        EXPECT_GT(checked, 12000u);
    }
}

TEST(BlendSort, FarthestFirstFromEitherSide) {
    std::vector<PlacedQuad> quads = orderQuads(false);  // near (draw 0), far (draw 1), opaque (draw 2)
    render::GpuSceneData data = render::packGpuScene(makePlacedQuadScene(quads), {});
    std::vector<scene::Aabb> boxes = render::meshBounds(data);
    EXPECT_EQ(render::blendDrawCount(data), 2u);
    EXPECT_EQ(data.draws[0].instanceCount, 0u) << "BLEND draws leave the G-buffer's indirect buffer";
    EXPECT_EQ(data.draws[2].instanceCount, 1u);
    auto order = [&](glm::vec3 eye) {
        std::vector<uint32_t> o;
        for (const VkDrawIndexedIndirectCommand& c : render::sortBlendDraws(data, boxes, eye)) {
            EXPECT_EQ(c.instanceCount, 1u);
            EXPECT_EQ(c.firstIndex, data.draws[c.firstInstance].firstIndex);
            o.push_back(c.firstInstance);
        }
        return o;
    };
    EXPECT_EQ(order({0.0f, 0.0f, 3.0f}), (std::vector<uint32_t>{1, 0}));
    EXPECT_EQ(order({0.0f, 0.0f, -3.0f}), (std::vector<uint32_t>{0, 1}));
}

TEST_F(BlendOrderTest, ForwardShadedBlendWithAlphaOneMatchesTheDeferredOpaqueSurface) {
    auto sceneWith = [](scene::AlphaMode mode) {
        PlacedQuad target, occluder;
        target.halfSize = {0.8f, 0.8f};
        target.baseColor = {0.7f, 0.5f, 0.3f};
        target.roughness = 0.6f;
        target.alphaMode = mode;
        occluder.centre = {0.3f, 0.3f, 0.5f};  // between the light and the target: a shadow across it
        occluder.halfSize = {0.2f, 0.2f};
        occluder.doubleSided = true;
        scene::Scene s = makePlacedQuadScene({target, occluder});
        s.lights.push_back(pointLight({0.6f, 0.6f, 1.5f}, 2.0f));
        return s;
    };
    render::FrameResult opaque = renderHdr(ctx(), shaders(), sceneWith(scene::AlphaMode::Opaque), 0.5f);
    render::FrameResult blend = renderHdr(ctx(), shaders(), sceneWith(scene::AlphaMode::Blend), 0.5f);
    render::FrameResult unshadowed = renderHdr(ctx(), shaders(), sceneWith(scene::AlphaMode::Opaque), 0.5f, 0);
    EXPECT_EQ(std::count(blend.passesRun.begin(), blend.passesRun.end(), "transparency"), 1);
    EXPECT_EQ(std::count(opaque.passesRun.begin(), opaque.passesRun.end(), "transparency"), 0);
    uint32_t compared = 0, shadowed = 0, failures = 0;
    double worst = 0.0;
    for (size_t i = 0; i < size_t(kSize) * kSize; ++i) {
        const float* a = &opaque.image.pixels[i * 4];
        const float* b = &blend.image.pixels[i * 4];
        if (a[3] != 1.0f || b[3] != 1.0f) continue;  // sky or partial coverage
        ++compared;
        shadowed += a[0] < 0.9f * unshadowed.image.pixels[i * 4];
        for (int c = 0; c < 3; ++c) {
            double err = std::abs(double(a[c]) - b[c]);
            worst = std::max(worst, err / (std::abs(a[c]) + 1e-3));
            failures += err > 0.02 * std::abs(a[c]) + 2e-3;
        }
    }
    EXPECT_EQ(failures, 0u) << "worst relative difference " << worst;
    EXPECT_GT(compared, 6000u);
    EXPECT_GT(shadowed, 100u) << "the occluder's shadow falls on the target";
}

}  // namespace
}  // namespace idk::test
