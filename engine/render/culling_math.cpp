// culling_math.cpp: frustum planes, culling records and the culling oracle (see culling_math.hpp).
#include "render/culling_math.hpp"

#include <algorithm>

#include "render/depth_pyramid.hpp"
#include "render/draw_bounds.hpp"
#include "render/meshlets.hpp"
#include "shared/meshlet_culling.h"

namespace idk::render {

gpu::GpuCullView frustumView(const glm::mat4& m, glm::uvec2 viewport) {
    // Row r of the matrix (glm is column-major: m[column][row]).
    auto row = [&](int r) { return glm::vec4(m[0][r], m[1][r], m[2][r], m[3][r]); };
    gpu::GpuCullView v{};
    v.planes[0] = row(3) + row(0);  // x >= -w
    v.planes[1] = row(3) - row(0);  // x <= w
    v.planes[2] = row(3) + row(1);  // y >= -w
    v.planes[3] = row(3) - row(1);  // y <= w
    v.planes[4] = row(2);           // z >= 0 (Vulkan depth range)
    v.planes[5] = row(3) - row(2);  // z <= w
    v.viewProjection = m;
    v.viewport = viewport;
    return v;
}

std::vector<gpu::GpuCullDraw> packCullDraws(const GpuSceneData& scene, const MeshletData* meshlets, bool blendCasts) {
    const std::vector<scene::Aabb> boxes = meshBounds(scene);
    std::vector<gpu::GpuCullDraw> out(scene.draws.size());
    static_assert(gpu::kTaskGroupSize == 32, "one meshlet visibility word per task workgroup");
    uint32_t visibilityWords = 0;
    for (size_t i = 0; i < scene.draws.size(); ++i) {
        const VkDrawIndexedIndirectCommand& d = scene.draws[i];
        const uint32_t mesh = scene.instances[i].mesh;
        gpu::GpuCullDraw& c = out[i];
        c.indexCount = d.indexCount;
        c.firstIndex = d.firstIndex;
        c.vertexOffset = d.vertexOffset;
        // The scene's commands leave BLEND and transmissive draws without an instance (the forward passes draw
        // them); they cast shadows by coverage like the others.
        const bool blend = mesh < scene.meshes.size() && scene.meshes[mesh].material < scene.materials.size() &&
                           drawnForward(scene.materials[scene.meshes[mesh].material]);
        if (d.instanceCount == 0 && !(blendCasts && blend)) c.flags |= gpu::kCullSkip;
        if (mesh >= scene.meshes.size() || d.vertexOffset != scene.meshes[mesh].baseVertex)
            c.flags |= gpu::kCullAlwaysVisible;
        if (mesh < scene.meshes.size()) {
            const uint32_t material = scene.meshes[mesh].material;
            if (material < scene.materials.size() && !(scene.materials[material].flags & gpu::kMaterialDoubleSided))
                c.flags |= gpu::kCullSingleSided;
            if (meshlets) {
                c.firstMeshlet = meshlets->firstMeshlet[mesh];
                c.meshletCount = meshlets->meshletCount[mesh];
                c.meshletVisibilityWord = visibilityWords;
                visibilityWords += (c.meshletCount + 31) / 32;
            }
        }
        if (mesh < boxes.size() && !boxes[mesh].empty()) {
            c.boxCenter = boxes[mesh].centre();
            c.boxExtent = 0.5f * (boxes[mesh].max - boxes[mesh].min);
        } else {
            c.flags |= gpu::kCullSkip;  // no vertices: nothing to draw
        }
    }
    return out;
}

uint32_t meshletVisibilityWords(const std::vector<gpu::GpuCullDraw>& draws) {
    uint32_t words = 0;
    for (const gpu::GpuCullDraw& d : draws) words = std::max(words, d.meshletVisibilityWord + (d.meshletCount + 31) / 32);
    return words;
}

std::vector<bool> cullOracle(const std::vector<gpu::GpuCullDraw>& draws, const std::vector<gpu::GpuInstance>& instances,
                             const gpu::GpuCullView& view, uint32_t phase, std::vector<uint32_t>* visibility,
                             const std::vector<float>* pyramid, bool meshTasks) {
    std::vector<bool> drawn(draws.size(), false);
    for (size_t i = 0; i < draws.size(); ++i) {
        const gpu::GpuCullDraw& d = draws[i];
        if (d.flags & gpu::kCullSkip) continue;
        bool visible = true;
        if (!(d.flags & gpu::kCullAlwaysVisible)) {
            glm::vec3 center, extent;
            gpu::worldBox(instances[i].model, d.boxCenter, d.boxExtent, center, extent);
            visible = gpu::boxInFrustum(view, center, extent) &&
                      (phase != gpu::kCullLate || hizBoxVisible(*pyramid, view, center, extent));
        }
        if (phase != gpu::kCullFrustum) {
            const bool drawnEarly = (*visibility)[i] != 0;
            if (phase == gpu::kCullLate) (*visibility)[i] = visible ? 1u : 0u;
            const bool relaunch = phase == gpu::kCullLate && drawnEarly && meshTasks;
            if (phase == gpu::kCullEarly ? !drawnEarly : drawnEarly && !relaunch) visible = false;
        }
        drawn[i] = visible;
    }
    return drawn;
}

MeshletCounts meshletOracle(const std::vector<gpu::GpuCullDraw>& draws, const std::vector<gpu::GpuInstance>& instances,
                            const std::vector<gpu::GpuMeshlet>& meshlets, const gpu::GpuCullView& view, glm::vec3 eye,
                            uint32_t phase, const std::vector<bool>& launched, const std::vector<bool>& drawnEarly,
                            std::vector<uint32_t>& meshletBits, const std::vector<float>* pyramid) {
    MeshletCounts counts;
    for (size_t i = 0; i < draws.size(); ++i) {
        if (!launched[i]) continue;
        const gpu::GpuCullDraw& d = draws[i];
        const glm::mat4& model = instances[i].model;
        for (uint32_t group = 0; group * gpu::kTaskGroupSize < d.meshletCount; ++group) {
            uint32_t& word = meshletBits.at(d.meshletVisibilityWord + group);
            uint32_t newWord = 0;
            for (uint32_t lane = 0; lane < gpu::kTaskGroupSize; ++lane) {
                const uint32_t local = group * gpu::kTaskGroupSize + lane;
                const bool wasVisible = phase != gpu::kCullFrustum && ((word >> lane) & 1u);
                if (local >= d.meshletCount || (phase == gpu::kCullEarly && !wasVisible)) continue;
                const gpu::GpuMeshlet& m = meshlets.at(d.firstMeshlet + local);
                bool visible = gpu::meshletInView(m, d.flags, model, view, eye);
                if (visible && phase == gpu::kCullLate && !(d.flags & gpu::kCullAlwaysVisible)) {
                    glm::vec3 center, extent;
                    gpu::meshletBox(m, model, center, extent);
                    visible = hizBoxVisible(*pyramid, view, center, extent);
                }
                if (visible) newWord |= 1u << lane;
                const bool early = phase == gpu::kCullLate && drawnEarly[i] && wasVisible;
                if (early) continue;
                ++counts.tested;
                if (visible) ++counts.drawn, counts.triangles += m.triangleCount;
            }
            if (phase == gpu::kCullLate) word = newWord;
        }
    }
    return counts;
}

}  // namespace idk::render
