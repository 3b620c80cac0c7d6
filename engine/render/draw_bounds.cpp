// draw_bounds.cpp: mesh boxes from the merged index and vertex arrays, world boxes through instance transforms.
// Supports point_shadow_maps.cpp (cube far planes) and blend_draws.cpp (sorting); IDKEngine keeps the same
// per-mesh boxes for culling.
#include "render/draw_bounds.hpp"

namespace idk::render {

std::vector<scene::Aabb> meshBounds(const GpuSceneData& scene) {
    std::vector<scene::Aabb> boxes(scene.meshes.size());
    for (size_t m = 0; m < scene.meshes.size(); ++m) {
        const gpu::GpuMesh& mesh = scene.meshes[m];
        for (uint32_t i = 0; i < mesh.indexCount; ++i) {
            size_t v = size_t(int64_t(mesh.baseVertex) + scene.indices[mesh.firstIndex + i]);
            if (v < scene.vertices.size()) boxes[m].extend(scene.vertices[v].position);
        }
    }
    return boxes;
}

scene::Aabb worldBounds(const scene::Aabb& box, const glm::mat4& model) {
    scene::Aabb out;
    if (box.empty()) return out;
    for (int c = 0; c < 8; ++c) {
        glm::vec3 corner((c & 1) ? box.max.x : box.min.x, (c & 2) ? box.max.y : box.min.y,
                         (c & 4) ? box.max.z : box.min.z);
        out.extend(glm::vec3(model * glm::vec4(corner, 1.0f)));
    }
    return out;
}

scene::Aabb sceneBounds(const GpuSceneData& scene, const std::vector<scene::Aabb>& meshBoxes) {
    scene::Aabb out;
    for (const gpu::GpuInstance& instance : scene.instances) {
        if (instance.mesh >= meshBoxes.size()) continue;
        scene::Aabb box = worldBounds(meshBoxes[instance.mesh], instance.model);
        if (box.empty()) continue;
        out.extend(box.min);
        out.extend(box.max);
    }
    return out;
}

}  // namespace idk::render
