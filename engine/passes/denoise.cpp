// denoise.cpp: records the denoiser (passes/denoise.hpp) as 2 + iterations compute passes over transient RGBA32F
// illumination images that ping-pong between iterations; the render graph plans every barrier between them.
// Ports the role of IDKEngine's OIDN.cs / PathTracerPipeline denoise step (reference 2.2) with an a-trous filter.
#include "passes/denoise.hpp"

#include <memory>
#include <string>

#include "core/log.hpp"
#include "vk/bindless.hpp"
#include "vk/pipeline.hpp"
#include "shared/denoise_filter.h"

namespace idk::passes {
namespace {

constexpr VkPipelineStageFlags2 kCs = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;

uint32_t rgbaFormatBit(const graph::PhysicalTexture& t, uint32_t bit, const char* what) {
    if (t.format == VK_FORMAT_R32G32B32A32_SFLOAT) return bit;
    if (t.format == VK_FORMAT_R16G16B16A16_SFLOAT) return 0;
    throw graph::GraphError(core::concat("denoise: the ", what, " input must be RGBA32F or RGBA16F (VkFormat ",
                                         int(t.format), ")"));
}

// Everything a pass needs from the declared handles, in the push block.
gpu::DenoisePush basePush(const graph::PassContext& pc, const DenoiseInputs& in, const DenoiseSettings& s) {
    const graph::PhysicalTexture& color = pc.texture(in.color);
    const graph::PhysicalTexture& albedo = pc.texture(in.albedo);
    const graph::PhysicalTexture& normal = pc.texture(in.normal);
    const graph::PhysicalTexture& depth = pc.texture(in.depth);
    if (depth.format != VK_FORMAT_R32_SFLOAT)
        throw graph::GraphError(core::concat("denoise: the depth input must be R32F (VkFormat ", int(depth.format), ")"));
    for (const graph::PhysicalTexture* t : {&albedo, &normal, &depth})
        if (t->extent.width != color.extent.width || t->extent.height != color.extent.height)
            throw graph::GraphError("denoise: the albedo, normal and depth inputs must have the colour's extent");
    for (const graph::PhysicalTexture* t : {&color, &albedo, &normal, &depth})
        if (t->storageIndex == graph::kNoBindlessIndex)
            throw graph::GraphError("denoise: an input has no bindless storage-image slot (import it with one)");
    // The intermediate images are output-relative transients.
    if (color.extent.width != pc.outputExtent().width || color.extent.height != pc.outputExtent().height)
        throw graph::GraphError("denoise: the inputs must have the render graph's output extent");
    gpu::DenoisePush push{};
    push.color = color.storageIndex;
    push.albedo = albedo.storageIndex;
    push.normal = normal.storageIndex;
    push.depth = depth.storageIndex;
    push.formats = rgbaFormatBit(color, gpu::kDenoiseColor32f, "colour") |
                   rgbaFormatBit(albedo, gpu::kDenoiseAlbedo32f, "albedo") |
                   rgbaFormatBit(normal, gpu::kDenoiseNormal32f, "normal");
    push.extent = {color.extent.width, color.extent.height};
    push.sigmaLuminance = s.sigmaLuminance;
    push.sigmaNormal = s.sigmaNormal;
    push.sigmaDepth = s.sigmaDepth;
    push.fireflyClamp = s.fireflyClamp;
    push.variance = gpu::kDenoiseNoVariance;
    if (in.variance.valid()) {
        const graph::PhysicalTexture& variance = pc.texture(in.variance);
        if (variance.format != VK_FORMAT_R32_SFLOAT || variance.extent.width != color.extent.width ||
            variance.extent.height != color.extent.height || variance.storageIndex == graph::kNoBindlessIndex)
            throw graph::GraphError("denoise: the variance input must be an R32F storage image of the colour's extent");
        push.variance = variance.storageIndex;
    }
    return push;
}

void dispatch(graph::PassContext& pc, vk::Context& ctx, vk::ShaderLibrary& shaders, vk::ShaderId shader,
              const gpu::DenoisePush& push) {
    VkCommandBuffer cmd = pc.commandBuffer();
    vk::ComputePipelineDesc desc;
    desc.shader = shader;
    desc.pushBytes = sizeof(gpu::DenoisePush);
    desc.localSize = {gpu::kDenoiseGroupSize, gpu::kDenoiseGroupSize, 1};
    vk::bindPipeline(cmd, shaders.compute(desc));
    ctx.bindless().bind(cmd);
    vk::pushConstants(cmd, ctx, push);
    vkCmdDispatch(cmd, vk::groupCount(push.extent.x, gpu::kDenoiseGroupSize),
                  vk::groupCount(push.extent.y, gpu::kDenoiseGroupSize), 1);
}

void readInputs(graph::PassBuilder& b, const DenoiseInputs& in) {
    for (graph::TextureHandle t : {in.color, in.albedo, in.normal, in.depth}) b.read(t, graph::Access::StorageRead, kCs);
    if (in.variance.valid()) b.read(in.variance, graph::Access::StorageRead, kCs);
}

}  // namespace

graph::TextureHandle addDenoisePass(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                    const DenoiseInputs& inputs, const DenoiseSettings& settings) {
    // Handles are filled by the setup callbacks (run inside addPass) and read later by the exec callbacks.
    struct State {
        graph::TextureHandle illum[2];  // ping-pong illumination + variance
        graph::TextureHandle gradient;
        graph::TextureHandle output;
        gpu::DenoisePush base{};  // inputs, formats, extent, sigmas: filled by denoise_prepare's exec, which runs first
    };
    auto st = std::make_shared<State>();
    const DenoiseInputs in = inputs;
    const DenoiseSettings s = settings;

    graph.addPass(
        "denoise_prepare",
        [&](graph::PassBuilder& b) {
            readInputs(b, in);
            graph::TextureDesc rgba;
            rgba.format = VK_FORMAT_R32G32B32A32_SFLOAT;
            graph::TextureDesc r32;
            r32.format = VK_FORMAT_R32_SFLOAT;
            st->illum[0] = b.write(b.create("denoise illumination A", rgba), graph::Access::StorageWrite, kCs);
            st->gradient = b.write(b.create("denoise depth gradient", r32), graph::Access::StorageWrite, kCs);
        },
        [&ctx, &shaders, in, s, st](graph::PassContext& pc) {
            st->base = basePush(pc, in, s);
            gpu::DenoisePush push = st->base;
            push.illumOut = pc.texture(st->illum[0]).storageIndex;
            push.gradient = pc.texture(st->gradient).storageIndex;
            dispatch(pc, ctx, shaders, vk::ShaderId::denoise_prepare_comp, push);
        });

    uint32_t current = 0;
    for (uint32_t i = 0; i < s.iterations; ++i) {
        const uint32_t src = current, dst = 1 - current;
        auto handles = std::make_shared<std::pair<graph::TextureHandle, graph::TextureHandle>>();  // in, out
        graph.addPass(
            core::concat("denoise_atrous_", i),
            [&](graph::PassBuilder& b) {
                b.read(in.albedo, graph::Access::StorageRead, kCs);
                b.read(in.normal, graph::Access::StorageRead, kCs);
                b.read(in.depth, graph::Access::StorageRead, kCs);
                b.read(st->gradient, graph::Access::StorageRead, kCs);
                handles->first = b.read(st->illum[src], graph::Access::StorageRead, kCs);
                graph::TextureHandle target = st->illum[dst];
                if (!target.valid()) {
                    graph::TextureDesc rgba;
                    rgba.format = VK_FORMAT_R32G32B32A32_SFLOAT;
                    target = b.create("denoise illumination B", rgba);
                }
                st->illum[dst] = handles->second = b.write(target, graph::Access::StorageWrite, kCs);
            },
            [&ctx, &shaders, st, handles, step = 1u << i](graph::PassContext& pc) {
                gpu::DenoisePush push = st->base;
                push.gradient = pc.texture(st->gradient).storageIndex;
                push.illumIn = pc.texture(handles->first).storageIndex;
                push.illumOut = pc.texture(handles->second).storageIndex;
                push.step = step;
                dispatch(pc, ctx, shaders, vk::ShaderId::denoise_atrous_comp, push);
            });
        current = dst;
    }

    const graph::TextureHandle filtered = st->illum[current];
    graph.addPass(
        "denoise_remodulate",
        [&](graph::PassBuilder& b) {
            readInputs(b, in);
            b.read(filtered, graph::Access::StorageRead, kCs);
            graph::TextureDesc rgba;
            rgba.format = VK_FORMAT_R32G32B32A32_SFLOAT;
            st->output = b.write(b.create("denoised", rgba), graph::Access::StorageWrite, kCs);
        },
        [&ctx, &shaders, st, filtered](graph::PassContext& pc) {
            gpu::DenoisePush push = st->base;
            push.illumIn = pc.texture(filtered).storageIndex;
            push.target = pc.texture(st->output).storageIndex;
            dispatch(pc, ctx, shaders, vk::ShaderId::denoise_remodulate_comp, push);
        });
    return st->output;
}

}  // namespace idk::passes
