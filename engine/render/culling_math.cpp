// culling_math.cpp: frustum planes, culling records and the culling oracle (see culling_math.hpp).
#include "render/culling_math.hpp"

#include "render/depth_pyramid.hpp"
#include "render/draw_bounds.hpp"
#include "render/meshlets.hpp"

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

std::vector<gpu::GpuCullDraw> packCullDraws(const GpuSceneData& scene, const MeshletData* meshlets) {
    const std::vector<scene::Aabb> boxes = meshBounds(scene);
    std::vector<gpu::GpuCullDraw> out(scene.draws.size());
    for (size_t i = 0; i < scene.draws.size(); ++i) {
        const VkDrawIndexedIndirectCommand& d = scene.draws[i];
        const uint32_t mesh = scene.instances[i].mesh;
        gpu::GpuCullDraw& c = out[i];
        c.indexCount = d.indexCount;
        c.firstIndex = d.firstIndex;
        c.vertexOffset = d.vertexOffset;
        if (d.instanceCount == 0) c.flags |= gpu::kCullSkip;
        if (mesh >= scene.meshes.size() || d.vertexOffset != scene.meshes[mesh].baseVertex)
            c.flags |= gpu::kCullAlwaysVisible;
        if (mesh < scene.meshes.size()) {
            const uint32_t material = scene.meshes[mesh].material;
            if (material < scene.materials.size() && !(scene.materials[material].flags & gpu::kMaterialDoubleSided))
                c.flags |= gpu::kCullSingleSided;
            if (meshlets) {
                c.firstMeshlet = meshlets->firstMeshlet[mesh];
                c.meshletCount = meshlets->meshletCount[mesh];
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

std::vector<bool> cullOracle(const std::vector<gpu::GpuCullDraw>& draws, const std::vector<gpu::GpuInstance>& instances,
                             const gpu::GpuCullView& view, uint32_t phase, std::vector<uint32_t>* visibility,
                             const std::vector<float>* pyramid) {
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
            if (phase == gpu::kCullEarly ? !drawnEarly : drawnEarly) visible = false;
        }
        drawn[i] = visible;
    }
    return drawn;
}

}  // namespace idk::render
