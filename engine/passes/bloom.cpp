// bloom.cpp: "CoD" bloom (Jimenez, SIGGRAPH 2014): levels of half, quarter, ... resolution made with the 13-tap
// downsample (Karis average on the first), summed back up with 3x3 tent upsamples, then blended into the HDR image
// with an energy-conserving mix. All transient images. Ports IDKEngine's Bloom.cs + Bloom/compute.glsl
// (reference 2.11); deviations: no threshold prefilter and a normalized blend (energy conserving) instead of
// adding the unnormalized sum in the tonemap pass.
#include "passes/bloom.hpp"

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "shared/bloom_types.h"
#include "vk/bindless.hpp"

namespace idk::passes {
namespace {

constexpr VkPipelineStageFlags2 kCs = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;

VkExtent2D levelSize(uint32_t width, uint32_t height, uint32_t level) {
    return {std::max(1u, width >> (level + 1)), std::max(1u, height >> (level + 1))};
}

void dispatch(VkCommandBuffer cmd, VkExtent2D size) {
    vkCmdDispatch(cmd, vk::groupCount(size.width, gpu::kBloomGroupSize), vk::groupCount(size.height, gpu::kBloomGroupSize), 1);
}

template <class Push>
void run(VkCommandBuffer cmd, vk::Context& ctx, vk::ShaderLibrary& shaders, vk::ShaderId shader, const Push& push,
         VkExtent2D size) {
    vk::ComputePipelineDesc desc;
    desc.shader = shader;
    desc.pushBytes = sizeof(Push);
    desc.localSize = {gpu::kBloomGroupSize, gpu::kBloomGroupSize, 1};
    vk::bindPipeline(cmd, shaders.compute(desc));
    ctx.bindless().bind(cmd);
    vk::pushConstants(cmd, ctx, push);
    dispatch(cmd, size);
}

graph::TextureHandle level(graph::PassBuilder& b, const std::string& name, VkExtent2D size) {
    graph::TextureDesc desc;
    desc.format = VK_FORMAT_R16G16B16A16_SFLOAT;
    desc.sizeMode = graph::SizeMode::Absolute;
    desc.extent = {size.width, size.height, 1};
    return b.write(b.create(name, desc), graph::Access::StorageWrite, kCs);
}

}  // namespace

uint32_t bloomLevels(uint32_t width, uint32_t height) {
    const uint32_t half = std::max(1u, std::max(width, height) / 2);
    uint32_t mips = 1;
    while ((half >> mips) > 0) ++mips;  // floor(log2(half)) + 1
    uint32_t levels = std::max(mips > 3 ? mips - 3 : 0u, 2u);
    while (levels > 1 && (std::min(width, height) >> levels) == 0) --levels;
    return levels;
}

graph::TextureHandle addBloomPasses(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                    graph::TextureHandle hdr, uint32_t width, uint32_t height,
                                    const BloomParams& params) {
    const uint32_t levels = bloomLevels(width, height);
    std::vector<graph::TextureHandle> down(levels);
    for (uint32_t i = 0; i < levels; ++i) {
        const graph::TextureHandle source = i == 0 ? hdr : down[i - 1];
        const VkExtent2D src = i == 0 ? VkExtent2D{width, height} : levelSize(width, height, i - 1);
        const VkExtent2D dst = levelSize(width, height, i);
        auto out = std::make_shared<graph::TextureHandle>();
        graph.addPass(
            "bloom_down" + std::to_string(i),
            [&](graph::PassBuilder& b) {
                b.read(source, graph::Access::StorageRead, kCs);
                *out = level(b, "bloom down " + std::to_string(i), dst);
            },
            [&ctx, &shaders, source, out, src, dst, karis = params.karis && i == 0](graph::PassContext& pc) {
                gpu::BloomDownPush push{pc.texture(source).storageIndex, pc.texture(*out).storageIndex,
                                        {src.width, src.height}, {dst.width, dst.height}, karis ? 1u : 0u, 0};
                run(pc.commandBuffer(), ctx, shaders, vk::ShaderId::bloom_downsample_comp, push, dst);
            });
        down[i] = *out;
    }
    graph::TextureHandle up = down[levels - 1];
    for (uint32_t i = levels - 1; i-- > 0;) {
        const graph::TextureHandle coarse = up, detail = down[i];
        const VkExtent2D coarseSize = levelSize(width, height, i + 1), dst = levelSize(width, height, i);
        auto out = std::make_shared<graph::TextureHandle>();
        graph.addPass(
            "bloom_up" + std::to_string(i),
            [&](graph::PassBuilder& b) {
                b.read(coarse, graph::Access::StorageRead, kCs);
                b.read(detail, graph::Access::StorageRead, kCs);
                *out = level(b, "bloom up " + std::to_string(i), dst);
            },
            [&ctx, &shaders, coarse, detail, out, coarseSize, dst](graph::PassContext& pc) {
                gpu::BloomUpPush push{pc.texture(coarse).storageIndex, pc.texture(detail).storageIndex,
                                      pc.texture(*out).storageIndex, 0, {coarseSize.width, coarseSize.height},
                                      {dst.width, dst.height}};
                run(pc.commandBuffer(), ctx, shaders, vk::ShaderId::bloom_upsample_comp, push, dst);
            });
        up = *out;
    }
    auto written = std::make_shared<graph::TextureHandle>();
    const VkExtent2D bloomSize = levelSize(width, height, 0);
    graph.addPass(
        "bloom_composite",
        [&](graph::PassBuilder& b) {
            b.read(up, graph::Access::StorageRead, kCs);
            *written = b.write(hdr, graph::Access::StorageReadWrite, kCs);
        },
        [&ctx, &shaders, up, written, bloomSize, width, height, levels, params](graph::PassContext& pc) {
            gpu::BloomCompositePush push{pc.texture(*written).storageIndex, pc.texture(up).storageIndex,
                                         {bloomSize.width, bloomSize.height}, {width, height}, params.strength,
                                         float(levels)};
            run(pc.commandBuffer(), ctx, shaders, vk::ShaderId::bloom_composite_comp, push, VkExtent2D{width, height});
        });
    return *written;
}

}  // namespace idk::passes
