// lambert_scene.cpp: flattening instances into world-space triangles and uploading them.
#include "render/lambert_scene.hpp"

#include <algorithm>

#include "vk/context.hpp"
#include "vk/transfer.hpp"

namespace idk::render {

LambertSceneData packLambertScene(const scene::Scene& s) {
    LambertSceneData out;
    for (const scene::Material& m : s.materials) out.materials.push_back({glm::vec3(m.baseColorFactor), m.emissive});
    const auto defaultMaterial = static_cast<uint32_t>(out.materials.size());
    out.materials.push_back({glm::vec3(1.0f), glm::vec3(0.0f)});  // glTF's default material: white, no emission

    for (const scene::Instance& instance : s.instances) {
        glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(instance.world)));
        for (const scene::Primitive& prim : s.meshes[instance.mesh].primitives) {
            uint32_t material = prim.material.value_or(defaultMaterial);
            for (uint32_t index : prim.indices) {
                glm::vec3 p = glm::vec3(instance.world * glm::vec4(prim.positions[index], 1.0f));
                glm::vec3 n = normalMatrix * prim.normals[index];
                float len = glm::length(n);
                out.vertices.push_back({p, len > 0.0f ? n / len : glm::vec3(0, 1, 0), material});
            }
        }
    }
    for (const scene::Light& l : s.lights) {
        if (l.type == scene::LightType::Directional || out.lights.size() >= gpu::kLambertMaxLights) continue;
        out.lights.push_back({l.position, l.color * l.intensity});
    }
    return out;
}

namespace {
template <class T>
vk::Buffer upload(vk::Context& ctx, const std::vector<T>& values, const char* name) {
    vk::BufferDesc desc;
    desc.size = std::max<size_t>(values.size() * sizeof(T), sizeof(T));  // never zero-sized
    desc.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    desc.name = name;
    desc.category = "geometry";
    vk::Buffer b = ctx.createBuffer(desc);
    if (!values.empty()) vk::uploadBuffer(ctx, b, values.data(), values.size() * sizeof(T));
    return b;
}
}  // namespace

GpuLambertScene uploadLambertScene(vk::Context& ctx, const LambertSceneData& data) {
    GpuLambertScene g;
    g.vertices = upload(ctx, data.vertices, "lambert vertices");
    g.materials = upload(ctx, data.materials, "lambert materials");
    g.lights = upload(ctx, data.lights, "lambert lights");
    g.vertexIndex = ctx.bindless().addBuffer(g.vertices.buffer, g.vertices.size, g.vertices.name);
    g.materialIndex = ctx.bindless().addBuffer(g.materials.buffer, g.materials.size, g.materials.name);
    g.lightIndex = ctx.bindless().addBuffer(g.lights.buffer, g.lights.size, g.lights.name);
    g.vertexCount = static_cast<uint32_t>(data.vertices.size());
    g.lightCount = static_cast<uint32_t>(data.lights.size());
    return g;
}

void destroyLambertScene(vk::Context& ctx, GpuLambertScene& g) {
    ctx.bindless().release(g.vertexIndex);
    ctx.bindless().release(g.materialIndex);
    ctx.bindless().release(g.lightIndex);
    ctx.destroyDeferred(g.vertices);
    ctx.destroyDeferred(g.materials);
    ctx.destroyDeferred(g.lights);
    g = {};
}

}  // namespace idk::render
