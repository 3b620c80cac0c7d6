// shadow_caster_draws.cpp: the shadow passes' draw commands, BLEND draws included (see shadow_caster_draws.hpp).
#include "render/shadow_caster_draws.hpp"

#include "passes/indirect_draw.hpp"

#include "vk/context.hpp"
#include "vk/transfer.hpp"

namespace idk::render {

std::vector<VkDrawIndexedIndirectCommand> shadowCasterDraws(const GpuSceneData& scene, uint32_t instancesPerDraw) {
    std::vector<VkDrawIndexedIndirectCommand> draws = scene.draws;
    for (VkDrawIndexedIndirectCommand& d : draws) d.instanceCount = d.indexCount > 0 ? instancesPerDraw : 0u;
    return draws;
}

vk::Buffer createShadowCasterDraws(vk::Context& ctx, const GpuSceneData& scene, uint32_t instancesPerDraw,
                                   const char* name) {
    const std::vector<uint8_t> bytes = passes::withCountWord(shadowCasterDraws(scene, instancesPerDraw));
    vk::BufferDesc desc;
    desc.size = bytes.size();  // the commands and the count word of passes/indirect_draw.hpp
    desc.usage = VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT;
    desc.name = name;
    desc.category = "shadow maps";
    return vk::createBufferWithData(ctx, desc, bytes.data(), desc.size);
}

}  // namespace idk::render
