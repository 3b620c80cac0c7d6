// cull_kernel_checks.cpp: "culling/cull kernel": the culling kernel (culling/cull_instances.comp.glsl through
// passes::recordCull) against its CPU oracle (render::cullOracle) on random instances (rotated, scaled, mirrored)
// and boxes, for perspective, infinite-far and orthographic views: the set of drawn instances is identical, every
// command copies its draw's index range, and the counters are exact. In the two phases of occlusion culling (random
// visibility bits, the Hi-Z pyramid of a depth image with a wall) the drawn sets and the rewritten visibility bits
// are identical too. Independently of the shared box test, no culled box has a point inside the clip volume (zero
// false culls), and each view culls and keeps a fair share (the check can fail both ways).
// Moved from tests/conformance/culling/cull_kernel_test.cpp.
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <random>

#include "conformance/conformance.hpp"
#include "passes/culling.hpp"
#include "render/culling_math.hpp"
#include "render/depth_pyramid.hpp"
#include "render/gpu_scene.hpp"
#include "scene/camera.hpp"
#include "vk/context.hpp"
#include "vk/transfer.hpp"

namespace idk::conformance {
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

// The check's buffers, released when it returns or throws.
struct Buffers {
    vk::Context& ctx;
    std::vector<vk::Buffer> list;
    ~Buffers() {
        for (vk::Buffer& b : list) ctx.destroyDeferred(b);
    }
    template <class T>
    vk::Buffer& add(const T* data, size_t count, const char* name) {
        list.push_back(ctx.createBuffer(
            {std::max<size_t>(count, 1) * sizeof(T), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUsage::GpuOnly, name, "test"}));
        if (data) vk::uploadBuffer(ctx, list.back(), data, count * sizeof(T));
        return list.back();
    }
};

struct Phase {
    uint32_t phase = gpu::kCullFrustum;
    std::vector<uint32_t>* visibility = nullptr;  // early: read; late: rewritten (compared with the oracle's)
    const std::vector<float>* pyramid = nullptr;
    glm::uvec2 viewport{1};
};

// Runs one phase on the GPU and compares it with the oracle; returns the number drawn.
uint32_t checkView(CheckEnv& env, Verdict& v, const RandomScene& s, const glm::mat4& viewProjection,
                   const std::string& what, const Phase& p = {}) {
    const uint32_t n = uint32_t(s.draws.size());
    const gpu::GpuCullView view = render::frustumView(viewProjection, p.viewport);
    Buffers b{env.ctx, {}};
    b.list.reserve(8);
    const gpu::GpuCullCounters zero{};
    gpu::CullPush push{};
    push.instances = b.add(s.instances.data(), n, "instances").address;
    push.draws = b.add(s.draws.data(), n, "draws").address;
    push.views = b.add(&view, 1, "views").address;
    const vk::Buffer commands = b.add<VkDrawIndexedIndirectCommand>(nullptr, n, "commands");
    const vk::Buffer counters = b.add(&zero, 1, "counters");
    push.commands = commands.address;
    push.counters = counters.address;
    push.drawCount = n;
    push.phase = p.phase;
    vk::Buffer bits;
    if (p.visibility) push.visibility = (bits = b.add(p.visibility->data(), n, "visibility")).address;
    if (p.pyramid) push.pyramid = b.add(p.pyramid->data(), p.pyramid->size(), "pyramid").address;
    env.ctx.runImmediate([&](VkCommandBuffer cmd) { passes::recordCull(cmd, env.ctx, env.shaders, push); });
    const auto got = vk::downloadBuffer<gpu::GpuCullCounters>(env.ctx, counters, 1)[0];
    const auto cmds = vk::downloadBuffer<VkDrawIndexedIndirectCommand>(env.ctx, commands, n);

    const std::vector<bool> expected = render::cullOracle(s.draws, s.instances, view, p.phase, p.visibility, p.pyramid);
    if (p.visibility)
        v.expect(vk::downloadBuffer<uint32_t>(env.ctx, bits, n) == *p.visibility, what + ": visibility bits differ");
    uint32_t tested = 0, visible = 0, triangles = 0;
    for (uint32_t i = 0; i < n; ++i) {
        tested += (s.draws[i].flags & gpu::kCullSkip) ? 0 : 1;
        if (expected[i]) ++visible, triangles += s.draws[i].indexCount / 3;
    }
    v.expectEq(got.instancesTested, tested, what + ": instances tested");
    v.expectEq(got.trianglesDrawn, triangles, what + ": triangles drawn");
    if (!v.expectEq(got.drawCount, visible, what + ": draw count")) return visible;
    std::vector<int> drawn(n, 0);
    for (uint32_t k = 0; k < got.drawCount; ++k) {
        const VkDrawIndexedIndirectCommand& c = cmds[k];
        if (!v.expect(c.firstInstance < n, what + ": command " + std::to_string(k) + " names no draw")) return visible;
        const gpu::GpuCullDraw& d = s.draws[c.firstInstance];
        v.expect(c.instanceCount == 1 && c.indexCount == d.indexCount && c.firstIndex == d.firstIndex &&
                     c.vertexOffset == d.vertexOffset,
                 what + ": command " + std::to_string(k) + " does not copy draw " + std::to_string(c.firstInstance));
        ++drawn[c.firstInstance];
    }
    std::mt19937 rng(7);
    uint32_t culled = 0;
    for (uint32_t i = 0; i < n; ++i) {
        v.expect(drawn[i] == (expected[i] ? 1 : 0), what + ": draw " + std::to_string(i) + " drawn " +
                                                        std::to_string(drawn[i]) + " times, the oracle says " +
                                                        (expected[i] ? "once" : "never"));
        if (expected[i] || (s.draws[i].flags & gpu::kCullSkip)) continue;
        ++culled;
        if (p.phase != gpu::kCullFrustum) continue;  // not drawn by this phase, not necessarily outside the view
        v.expect(!boxHasVisiblePoint(s.draws[i], s.instances[i].model, viewProjection, rng),
                 what + ": draw " + std::to_string(i) + " was culled but has a point in view");
    }
    if (p.phase == gpu::kCullFrustum) {
        v.expect(culled > tested / 10, what + ": the view should cull a fair share (" + std::to_string(culled) + ")");
        v.expect(visible > tested / 20, what + ": the view should keep a fair share (" + std::to_string(visible) + ")");
    }
    return visible;
}

glm::mat4 lookFrom(glm::vec3 eye, glm::vec3 target) { return glm::lookAt(eye, target, glm::vec3(0, 1, 0)); }

void cullKernel(CheckEnv& env, Verdict& v) {
    checkView(env, v, randomScene(20000, 1),
              scene::perspectiveVulkan(1.0f, 16.0f / 9.0f, 0.1f, 80.0f) * lookFrom({5, 3, -70}, {0, 0, 0}), "perspective");
    // The eye among the boxes: many straddle the near plane or sit behind the camera.
    checkView(env, v, randomScene(20000, 2),
              scene::perspectiveVulkan(1.3f, 1.0f, 0.05f, 0.0f) * lookFrom({1, 2, 3}, {-20, 0, 10}), "infinite far");
    checkView(env, v, randomScene(5000, 3),
              scene::orthographicVulkan(30.0f, 20.0f, 0.0f, 100.0f) * lookFrom({0, 50, 0.01f}, {0, 0, 0}), "orthographic");

    // Two-phase occlusion. A depth image whose left half is a wall 77 units from the eye (the boxes lie 15..135
    // away) and right half is background: the late phase must cull behind the wall only.
    const RandomScene s = randomScene(20000, 4);
    const glm::uvec2 viewport(173, 97);  // odd, not a power of two
    const glm::mat4 vp = scene::perspectiveVulkan(1.0f, float(viewport.x) / float(viewport.y), 0.1f, 0.0f) *
                         lookFrom({0, 0, -75}, {0, 0, 0});
    std::vector<float> depth(size_t(viewport.x) * viewport.y, 1.0f);
    for (uint32_t y = 0; y < viewport.y; ++y)
        for (uint32_t x = 0; x < viewport.x / 2; ++x) depth[size_t(y) * viewport.x + x] = 0.9987f;  // 1 - n / d: d = 77
    const std::vector<float> pyramid = render::buildDepthPyramid(depth, viewport);
    std::vector<uint32_t> visibility(s.draws.size());
    std::mt19937 rng(5);
    for (uint32_t& bit : visibility) bit = rng() % 2;
    const std::vector<uint32_t> before = visibility;
    const uint32_t early = checkView(env, v, s, vp, "early", {gpu::kCullEarly, &visibility, &pyramid, viewport});
    v.expect(visibility == before, "the early phase must not change the bits");
    const uint32_t late = checkView(env, v, s, vp, "late", {gpu::kCullLate, &visibility, &pyramid, viewport});
    const uint32_t frustum = checkView(env, v, s, vp, "frustum", {gpu::kCullFrustum, nullptr, nullptr, viewport});
    uint32_t nowVisible = 0;
    for (uint32_t bit : visibility) nowVisible += bit;
    v.expect(early > 0 && late > 0, "two-phase: both phases draw something");
    v.expect(nowVisible < frustum, "two-phase: the wall should occlude some draws (" + std::to_string(nowVisible) +
                                       " visible of " + std::to_string(frustum) + " in the frustum)");
}

}  // namespace

std::vector<Check> cullKernelChecks() {
    return {{"culling/cull kernel", "", "exact (drawn set, commands, counters, visibility bits)", cullKernel}};
}

}  // namespace idk::conformance
