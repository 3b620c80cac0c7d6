// vrs_classify.cpp: the shading-rate classifier, one workgroup of 256 invocations per tile (vrs/classify.comp.glsl;
// ports IDKEngine's ShadingRateClassification/compute.glsl). The tile size and the reduction variant are
// specialization constants, so a 8x8 or 32x32 hardware shading-rate texel and a device without subgroup
// arithmetic each get their own pipeline.
#include <memory>

#include "passes/vrs_passes.hpp"

namespace idk::passes {

void recordVrsClassify(VkCommandBuffer cmd, vk::Context& ctx, vk::ShaderLibrary& shaders, const VrsClassifyParams& params,
                       uint32_t lit, uint32_t width, uint32_t height, VkDeviceAddress velocity, VkDeviceAddress rates) {
    vk::ComputePipelineDesc desc;
    desc.shader = vk::ShaderId::vrs_classify_comp;
    desc.spec = {{gpu::kSpecVrsTileSize, params.tileSize}, {gpu::kSpecVrsSubgroupReduce, params.subgroupReduce ? 1u : 0u}};
    desc.pushBytes = sizeof(gpu::VrsClassifyPush);
    desc.localSize = {gpu::kVrsGroupSize, 1, 1};
    vk::bindPipeline(cmd, shaders.compute(desc));
    ctx.bindless().bind(cmd);
    gpu::VrsClassifyPush push{};
    push.rates = rates;
    push.velocity = velocity;
    push.lit = lit;
    push.width = width;
    push.height = height;
    push.invFrameSeconds = 1.0f / params.frameSeconds;
    push.speedFactor = params.speedFactor;
    push.lumVarianceFactor = params.lumVarianceFactor;
    vk::pushConstants(cmd, ctx, push);
    vkCmdDispatch(cmd, vk::groupCount(width, params.tileSize), vk::groupCount(height, params.tileSize), 1);
}

graph::BufferHandle addVrsClassifyPass(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                       const VrsClassifyParams& params, graph::TextureHandle lit,
                                       graph::BufferHandle velocity, graph::BufferHandle rates) {
    auto written = std::make_shared<graph::BufferHandle>();
    graph.addPass(
        "vrs_classify",
        [&](graph::PassBuilder& b) {
            constexpr VkPipelineStageFlags2 kCs = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
            b.read(lit, graph::Access::StorageRead, kCs);
            if (velocity.valid()) b.read(velocity, graph::Access::StorageRead, kCs);
            // Read-write: the header stays, the rates are replaced.
            *written = b.write(rates, graph::Access::StorageReadWrite, kCs);
        },
        [&ctx, &shaders, params, lit, velocity, written](graph::PassContext& pc) {
            VkExtent3D extent = pc.texture(lit).extent;
            recordVrsClassify(pc.commandBuffer(), ctx, shaders, params, pc.texture(lit).storageIndex, extent.width,
                              extent.height, velocity.valid() ? pc.buffer(velocity).address : 0,
                              pc.buffer(*written).address);
        });
    return *written;
}

}  // namespace idk::passes
