// pt_tables.cpp: uploads PT-A's light, environment and material tables (see pt_tables.hpp).
#include "render/pt_tables.hpp"

#include "pathtrace/albedo_integrator.hpp"
#include "vk/context.hpp"
#include "vk/transfer.hpp"

namespace idk::render {
namespace {

template <class T>
VkDeviceAddress upload(vk::Context& ctx, PtTables& t, const std::vector<T>& v, const std::string& name) {
    return t.buffers.emplace_back(uploadPtBuffer(ctx, v.data(), v.size() * sizeof(T), name)).address;
}

}  // namespace

vk::Buffer uploadPtBuffer(vk::Context& ctx, const void* data, size_t bytes, const std::string& name) {
    vk::BufferDesc desc;
    desc.size = std::max<VkDeviceSize>(bytes, 16);
    desc.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    desc.name = name;
    desc.category = "path tracer";
    vk::Buffer b = ctx.createBuffer(desc);
    if (bytes > 0) vk::uploadBuffer(ctx, b, data, bytes);
    return b;
}

PtTables uploadPtTables(vk::Context& ctx, const pathtrace::PathTraceScene& pts,
                        const std::vector<PtTextureBinding>& textures, PtTextureBinding white) {
    PtTables t;
    std::vector<gpu::GpuPtMaterial> materials = pts.ptMaterials;
    std::vector<uint32_t> samplers(materials.size(), white.sampler);
    for (size_t i = 0; i < materials.size(); ++i) {
        gpu::GpuPtMaterial& m = materials[i];
        PtTextureBinding b = white;
        if (m.transmissionTexture != gpu::kPtNoTexture && m.transmissionTexture < textures.size() &&
            textures[m.transmissionTexture].texture != UINT32_MAX)
            b = textures[m.transmissionTexture];
        m.transmissionTexture = b.texture;
        samplers[i] = b.sampler;
    }
    t.desc.ptMaterials = upload(ctx, t, materials, "pt materials");
    t.desc.albedoTables = upload(ctx, t, pathtrace::albedoTableData(), "pt albedo tables");
    t.desc.ptSamplers = upload(ctx, t, samplers, "pt material samplers");
    t.desc.lights = upload(ctx, t, pts.lights, "pt lights");
    t.desc.lightAlias = upload(ctx, t, pts.lightAlias, "pt light alias");
    t.desc.lightCount = pts.lightAlias.empty() ? 0u : uint32_t(pts.lights.size());
    std::vector<float> radiance;
    radiance.reserve(pts.environment.radiance.size() * 3);
    for (const glm::vec3& r : pts.environment.radiance) radiance.insert(radiance.end(), {r.x, r.y, r.z});
    t.desc.envRadiance = upload(ctx, t, radiance, "pt environment radiance");
    t.desc.envAlias = pts.environment.aliasTable.empty() ? 0 : upload(ctx, t, pts.environment.aliasTable, "pt environment alias");
    t.desc.envWidth = pts.environment.width;
    t.desc.envHeight = pts.environment.height;
    t.desc.envSelectProbability = pts.environmentDesc.selectProbability;
    return t;
}

void destroyPtTables(vk::Context& ctx, PtTables& tables) {
    for (vk::Buffer& b : tables.buffers) ctx.destroyDeferred(b);
    tables.buffers.clear();
}

}  // namespace idk::render
