// cull_kernel_test.cpp: the culling kernel (culling/cull_instances.comp.glsl) against its CPU oracle
// (render::cullOracle): on random instances (rotated, scaled, mirrored) and boxes, for perspective, infinite-far
// and orthographic views, the set of drawn instances is identical, every command copies its draw's index range,
// and the counters are exact; in the two phases of occlusion culling (random visibility bits, a Hi-Z pyramid of a
// random depth image) the drawn sets and the rewritten visibility bits are identical too. Independently of the shared box test, no culled box has a point inside the clip
// volume (zero false culls), and the scenes cull and keep a fair share each (the test can fail both ways).
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <random>

#include "passes/culling.hpp"
#include "render/culling_math.hpp"
#include "render/depth_pyramid.hpp"
#include "render/gpu_scene.hpp"
#include "scene/camera.hpp"
#include "support/gpu_fixture.hpp"
#include "vk/transfer.hpp"

namespace idk::test {
namespace {

struct RandomScene {
    std::vector<gpu::GpuInstance> instances;
    std::vector<gpu::GpuCullDraw> draws;
};

RandomScene randomScene(uint32_t count, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> pos(-60.0f, 60.0f), unit(-1.0f, 1.0f), size(0.05f, 4.0f), any(0.0f, 1.0f);
    RandomScene s;
    for (uint32_t i = 0; i < count; ++i) {
        glm::vec3 axis = glm::normalize(glm::vec3(unit(rng), unit(rng), unit(rng)) + glm::vec3(0.0f, 0.0f, 1e-3f));
        glm::mat4 model = glm::translate(glm::mat4(1.0f), glm::vec3(pos(rng), pos(rng), pos(rng)));
        model = glm::rotate(model, 6.2831853f * any(rng), axis);
        model = glm::scale(model, glm::vec3(size(rng), size(rng), any(rng) < 0.1f ? -size(rng) : size(rng)));
        s.instances.push_back(render::packInstance(model, 0));
        gpu::GpuCullDraw d{};
        d.boxCenter = glm::vec3(unit(rng), unit(rng), unit(rng));
        d.boxExtent = glm::vec3(size(rng), size(rng), size(rng)) * 0.5f;
        d.indexCount = 3 * (1 + i % 97);
        d.firstIndex = i * 7;
        d.vertexOffset = int32_t(i % 13) - 6;
        float r = any(rng);
        d.flags = r < 0.05f ? gpu::kCullSkip : r < 0.08f ? gpu::kCullAlwaysVisible : 0u;
        s.draws.push_back(d);
    }
    return s;
}

// True when some of 64 points of the instance's object box (its corners and random interior points) lands
// inside the clip volume: then the box must not have been culled.
bool boxHasVisiblePoint(const gpu::GpuCullDraw& d, const glm::mat4& model, const glm::mat4& viewProjection,
                        std::mt19937& rng) {
    std::uniform_real_distribution<float> t(-1.0f, 1.0f);
    for (int k = 0; k < 64; ++k) {
        glm::vec3 u = k < 8 ? glm::vec3((k & 1) ? 1 : -1, (k & 2) ? 1 : -1, (k & 4) ? 1 : -1)
                            : glm::vec3(t(rng), t(rng), t(rng));
        glm::vec4 clip = viewProjection * model * glm::vec4(d.boxCenter + u * d.boxExtent, 1.0f);
        if (clip.w > 0.0f && std::abs(clip.x) <= clip.w && std::abs(clip.y) <= clip.w && clip.z >= 0.0f &&
            clip.z <= clip.w)
            return true;
    }
    return false;
}

class CullKernelTest : public GpuTest {
protected:
    vk::Buffer buffer(VkDeviceSize size, vk::MemoryUsage memory, const char* name) {
        buffers_.push_back(ctx().createBuffer({size, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, memory, name, "test"}));
        return buffers_.back();
    }
    void TearDown() override {
        for (vk::Buffer& b : buffers_) ctx().destroyDeferred(b);
        GpuTest::TearDown();
    }

    // Runs one phase on the GPU and compares it with the oracle; *drawnOut = the number drawn.
    void checkView(const RandomScene& s, const glm::mat4& viewProjection, const char* what,
                   uint32_t phase = gpu::kCullFrustum, std::vector<uint32_t>* visibility = nullptr,
                   const std::vector<float>* pyramid = nullptr, glm::uvec2 viewport = glm::uvec2(1),
                   uint32_t* drawnOut = nullptr) {
        const uint32_t n = uint32_t(s.draws.size());
        const gpu::GpuCullView view = render::frustumView(viewProjection, viewport);
        vk::Buffer instances = buffer(n * sizeof(gpu::GpuInstance), vk::MemoryUsage::GpuOnly, "instances");
        vk::Buffer draws = buffer(n * sizeof(gpu::GpuCullDraw), vk::MemoryUsage::GpuOnly, "draws");
        vk::Buffer views = buffer(sizeof view, vk::MemoryUsage::GpuOnly, "views");
        vk::Buffer commands = buffer(n * sizeof(VkDrawIndexedIndirectCommand), vk::MemoryUsage::GpuOnly, "commands");
        vk::Buffer counters = buffer(sizeof(gpu::GpuCullCounters), vk::MemoryUsage::GpuOnly, "counters");
        vk::uploadBuffer(ctx(), instances, s.instances.data(), n * sizeof(gpu::GpuInstance));
        vk::uploadBuffer(ctx(), draws, s.draws.data(), n * sizeof(gpu::GpuCullDraw));
        vk::uploadBuffer(ctx(), views, &view, sizeof view);
        const gpu::GpuCullCounters zero{};
        vk::uploadBuffer(ctx(), counters, &zero, sizeof zero);
        gpu::CullPush push{};
        push.instances = instances.address;
        push.draws = draws.address;
        push.views = views.address;
        push.commands = commands.address;
        push.counters = counters.address;
        push.drawCount = n;
        push.phase = phase;
        vk::Buffer bits, levels;
        if (visibility) {
            bits = buffer(n * sizeof(uint32_t), vk::MemoryUsage::GpuOnly, "visibility");
            vk::uploadBuffer(ctx(), bits, visibility->data(), n * sizeof(uint32_t));
            push.visibility = bits.address;
        }
        if (pyramid) {
            levels = buffer(pyramid->size() * sizeof(float), vk::MemoryUsage::GpuOnly, "pyramid");
            vk::uploadBuffer(ctx(), levels, pyramid->data(), pyramid->size() * sizeof(float));
            push.pyramid = levels.address;
        }
        ctx().runImmediate([&](VkCommandBuffer cmd) { passes::recordCull(cmd, ctx(), shaders(), push); });
        const auto got = vk::downloadBuffer<gpu::GpuCullCounters>(ctx(), counters, 1)[0];
        const auto cmds = vk::downloadBuffer<VkDrawIndexedIndirectCommand>(ctx(), commands, n);

        const std::vector<bool> expected = render::cullOracle(s.draws, s.instances, view, phase, visibility, pyramid);
        if (visibility) {
            EXPECT_EQ(vk::downloadBuffer<uint32_t>(ctx(), bits, n), *visibility) << what << ": visibility bits differ";
        }
        uint32_t tested = 0, visible = 0, triangles = 0;
        for (uint32_t i = 0; i < n; ++i) {
            tested += (s.draws[i].flags & gpu::kCullSkip) ? 0 : 1;
            if (expected[i]) ++visible, triangles += s.draws[i].indexCount / 3;
        }
        EXPECT_EQ(got.instancesTested, tested) << what;
        ASSERT_EQ(got.drawCount, visible) << what;
        EXPECT_EQ(got.trianglesDrawn, triangles) << what;
        std::vector<int> drawn(n, 0);
        for (uint32_t k = 0; k < got.drawCount; ++k) {
            const VkDrawIndexedIndirectCommand& c = cmds[k];
            ASSERT_LT(c.firstInstance, n) << what;
            const gpu::GpuCullDraw& d = s.draws[c.firstInstance];
            EXPECT_EQ(c.instanceCount, 1u);
            EXPECT_EQ(c.indexCount, d.indexCount);
            EXPECT_EQ(c.firstIndex, d.firstIndex);
            EXPECT_EQ(c.vertexOffset, d.vertexOffset);
            ++drawn[c.firstInstance];
        }
        std::mt19937 rng(7);
        uint32_t culled = 0;
        for (uint32_t i = 0; i < n; ++i) {
            ASSERT_EQ(drawn[i], expected[i] ? 1 : 0) << what << ": draw " << i << " differs from the oracle";
            if (expected[i] || (s.draws[i].flags & gpu::kCullSkip)) continue;
            ++culled;
            if (phase != gpu::kCullFrustum) continue;  // not drawn by this phase, not necessarily outside the view
            EXPECT_FALSE(boxHasVisiblePoint(s.draws[i], s.instances[i].model, viewProjection, rng))
                << what << ": draw " << i << " was culled but has a point in view";
        }
        std::cout << "[ cull ] " << what << ": " << tested << " tested, " << visible << " drawn, " << culled
                  << " culled\n";
        if (phase == gpu::kCullFrustum) {
            EXPECT_GT(culled, tested / 10) << what << ": the view should cull a fair share";
            EXPECT_GT(visible, tested / 20) << what << ": the view should keep a fair share";
        }
        if (drawnOut) *drawnOut = visible;
    }

private:
    std::vector<vk::Buffer> buffers_;
};

glm::mat4 lookFrom(glm::vec3 eye, glm::vec3 target) { return glm::lookAt(eye, target, glm::vec3(0, 1, 0)); }

TEST_F(CullKernelTest, PerspectiveViewMatchesOracle) {
    const RandomScene s = randomScene(20000, 1);
    checkView(s, scene::perspectiveVulkan(1.0f, 16.0f / 9.0f, 0.1f, 80.0f) * lookFrom({5, 3, -70}, {0, 0, 0}),
              "perspective");
}

TEST_F(CullKernelTest, InfiniteFarAndInsideTheCloudMatchOracle) {
    const RandomScene s = randomScene(20000, 2);
    // The eye among the boxes: many straddle the near plane or sit behind the camera.
    checkView(s, scene::perspectiveVulkan(1.3f, 1.0f, 0.05f, 0.0f) * lookFrom({1, 2, 3}, {-20, 0, 10}),
              "infinite far");
}

TEST_F(CullKernelTest, OrthographicViewMatchesOracle) {
    const RandomScene s = randomScene(5000, 3);
    checkView(s, scene::orthographicVulkan(30.0f, 20.0f, 0.0f, 100.0f) * lookFrom({0, 50, 0.01f}, {0, 0, 0}),
              "orthographic");
}

TEST_F(CullKernelTest, TwoPhaseOcclusionMatchesOracle) {
    const RandomScene s = randomScene(20000, 4);
    const glm::uvec2 viewport(173, 97);  // odd, not a power of two
    const glm::mat4 vp = scene::perspectiveVulkan(1.0f, float(viewport.x) / float(viewport.y), 0.1f, 0.0f) *
                         lookFrom({0, 0, -75}, {0, 0, 0});
    // A depth image whose left half is a wall 77 units from the eye (the boxes lie 15..135 away)
    // and right half is background: the late phase must cull behind the wall only.
    std::vector<float> depth(size_t(viewport.x) * viewport.y, 1.0f);
    for (uint32_t y = 0; y < viewport.y; ++y)
        for (uint32_t x = 0; x < viewport.x / 2; ++x) depth[size_t(y) * viewport.x + x] = 0.9987f;  // 1 - n / d: d = 77
    const std::vector<float> pyramid = render::buildDepthPyramid(depth, viewport);
    std::vector<uint32_t> visibility(s.draws.size());
    std::mt19937 rng(5);
    for (uint32_t& v : visibility) v = rng() % 2;
    const std::vector<uint32_t> before = visibility;
    uint32_t early = 0, late = 0, frustum = 0;
    checkView(s, vp, "early", gpu::kCullEarly, &visibility, &pyramid, viewport, &early);
    EXPECT_EQ(visibility, before) << "the early phase must not change the bits";
    checkView(s, vp, "late", gpu::kCullLate, &visibility, &pyramid, viewport, &late);
    checkView(s, vp, "frustum", gpu::kCullFrustum, nullptr, nullptr, viewport, &frustum);
    uint32_t nowVisible = 0;
    for (uint32_t v : visibility) nowVisible += v;
    std::cout << "[ cull ] two-phase: early " << early << ", late " << late << ", frustum " << frustum
              << ", visible now " << nowVisible << "\n";
    EXPECT_GT(early, 0u);
    EXPECT_GT(late, 0u);
    EXPECT_LT(nowVisible, frustum) << "the wall should occlude some draws";
}

}  // namespace
}  // namespace idk::test
