// pt_stages.cpp: the wavefront stages as render-graph passes (see pt_stages.hpp). Shaders: shaders_glsl/pathtrace.
#include "render/pt_stages.hpp"

#include <string>
#include <vector>

#include <stdexcept>

#include "render/compute_primitives.hpp"
#include "vk/context.hpp"
#include "vk/shader_library.hpp"

#if __has_include("passes/denoise.hpp")
#include "passes/denoise.hpp"
#define IDK_PT_HAS_DENOISER 1
#else
#define IDK_PT_HAS_DENOISER 0
#endif

namespace idk::render {
namespace {

using graph::Access;
using vk::ShaderId;
constexpr VkPipelineStageFlags2 kCs = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;

struct BufferUse {
    const vk::Buffer* buffer;
    Access access;
};
struct ImageUse {
    const vk::Image* image;
    Access access;
};

uint32_t storageIndexOf(const PtFrameResources& f, const vk::Image* image) {
    if (image == &f.colorImage) return f.colorStorage.value;
    if (image == &f.albedoImage) return f.albedoStorage.value;
    if (image == &f.normalImage) return f.normalStorage.value;
    if (image == &f.depthImage) return f.depthStorage.value;
    if (image == &f.varianceImage) return f.varianceStorage.value;
    return graph::kNoBindlessIndex;
}

bool isWrite(Access a) { return a == Access::StorageWrite || a == Access::StorageReadWrite || a == Access::TransferDst; }

// Declares the uses (storage accesses in the compute stage, others at the table's default stages) and records
// `record`. Every pass is a side effect: its results live in owned buffers that later graphs read.
void addPass(const PtStageContext& s, const std::string& name, std::vector<BufferUse> buffers,
             std::vector<ImageUse> images, std::function<void(VkCommandBuffer)> record) {
    s.graph.addPass(
        name,
        [&](graph::PassBuilder& b) {
            for (const BufferUse& u : buffers) {
                const VkPipelineStageFlags2 stages =
                    u.access == Access::IndirectRead || u.access == Access::TransferDst ? VK_PIPELINE_STAGE_2_NONE : kCs;
                graph::BufferHandle& h = s.res.buffer(*u.buffer);
                if (isWrite(u.access)) h = b.write(h, u.access, stages);
                else b.read(h, u.access, stages);
            }
            for (const ImageUse& u : images) {
                graph::TextureHandle& h = s.res.image(*u.image, storageIndexOf(s.frame, u.image));
                if (isWrite(u.access)) h = b.write(h, u.access, kCs);
                else b.read(h, u.access, kCs);
            }
            b.sideEffect();
        },
        [record = std::move(record)](graph::PassContext& pc) { record(pc.commandBuffer()); });
}

gpu::GpuPtStagePush basePush(const PtStageContext& s) {
    gpu::GpuPtStagePush p{};
    p.scene = s.config.scene;
    p.paths = s.frame.paths.address;
    p.hits = s.frame.hits.address;
    p.shadowRays = s.frame.shadowRays.address;
    p.accum = s.config.accum;
    p.extent = glm::uvec2(s.frame.width, s.frame.height);
    p.seed = s.config.seed;
    p.maxDepth = s.config.maxDepth;
    p.rouletteDepth = s.config.rouletteDepth;
    p.flags = s.config.sobol ? gpu::kPtPushSobol : 0u;
    return p;
}

const vk::Pipeline& pipeline(const PtStageContext& s, ShaderId id, bool traced, std::array<uint32_t, 3> local) {
    vk::ComputePipelineDesc desc;
    desc.shader = id;
    desc.pushBytes = sizeof(gpu::GpuPtStagePush);
    desc.localSize = local;
    if (traced) {
        desc.spec = {{gpu::kSpecPtHasAlpha, s.config.hasAlpha ? 1u : 0u},
                     {gpu::kSpecPtNee, s.config.nee ? 1u : 0u},
                     {gpu::kSpecPtStackSize, std::max(s.config.blasStack, 1u)},
                     {gpu::kSpecPtTlasStackSize, std::max(s.config.tlasStack, 1u)}};
    }
    return s.shaders.compute(desc);
}

constexpr std::array<uint32_t, 3> kLinear = {gpu::kPtGroupSize, 1, 1};

void bindAndPush(const PtStageContext& s, VkCommandBuffer cmd, const vk::Pipeline& p, const gpu::GpuPtStagePush& push) {
    s.ctx.bindless().bind(cmd);
    vk::bindPipeline(cmd, p);
    vk::pushConstants(cmd, s.ctx, push);
}

}  // namespace

void addPtClear(const PtStageContext& s) {
    PtFrameResources& f = s.frame;
    addPass(s, "pt_clear",
            {{&f.accumColor, Access::TransferDst}, {&f.accumAlbedo, Access::TransferDst},
             {&f.accumNormal, Access::TransferDst}, {&f.accumDepth, Access::TransferDst},
             {&f.accumMoment, Access::TransferDst}},
            {}, [&f](VkCommandBuffer cmd) {
                for (const vk::Buffer* b : {&f.accumColor, &f.accumAlbedo, &f.accumNormal, &f.accumDepth, &f.accumMoment})
                    vkCmdFillBuffer(cmd, b->buffer, 0, VK_WHOLE_SIZE, 0);
            });
}

void addPtSample(const PtStageContext& s, uint32_t sampleIndex, PtStop stop) {
    PtFrameResources& f = s.frame;
    const std::string tag = " s" + std::to_string(sampleIndex);
    const uint32_t pixels = f.width * f.height;
    const bool rq = s.config.rayQuery;
    const ShaderId traceShader = rq ? ShaderId::pathtrace_trace_rq_comp
                                 : s.config.wideBvh ? ShaderId::pathtrace_trace_bvh_wide_comp
                                                    : ShaderId::pathtrace_trace_bvh_comp;
    const ShaderId shadowShader = rq ? ShaderId::pathtrace_shadow_rq_comp
                                  : s.config.wideBvh ? ShaderId::pathtrace_shadow_bvh_wide_comp
                                                     : ShaderId::pathtrace_shadow_bvh_comp;

    gpu::GpuPtStagePush camera = basePush(s);
    camera.sampleIndex = sampleIndex;
    camera.accum = s.config.camera;
    camera.queueIn = f.queue[0].address;
    camera.argsOut = f.args[0].address;
    camera.queueOut = f.queue[1].address;
    camera.shadow = f.shadow[0].address;
    camera.aux = f.shadow[1].address;
    addPass(s, "pt_camera" + tag,
            {{&f.paths, Access::StorageWrite}, {&f.queue[0], Access::StorageWrite}, {&f.args[0], Access::StorageWrite},
             {&f.queue[1], Access::StorageWrite}, {&f.shadow[0], Access::StorageWrite}, {&f.shadow[1], Access::StorageWrite}},
            {}, [s, camera, pixels](VkCommandBuffer cmd) {
                bindAndPush(s, cmd, pipeline(s, ShaderId::pathtrace_camera_comp, false, kLinear), camera);
                vkCmdDispatch(cmd, vk::groupCount(pixels, gpu::kPtGroupSize), 1, 1);
            });
    if (stop.kind == PtStop::AfterCamera) return;

    for (uint32_t bounce = 0; bounce < s.config.maxDepth; ++bounce) {
        const int in = int(bounce % 2), out = 1 - in;
        const std::string btag = tag + " b" + std::to_string(bounce);
        gpu::GpuPtStagePush push = basePush(s);
        push.sampleIndex = sampleIndex;
        push.bounce = bounce;
        push.queueIn = f.queue[in].address;
        push.queueOut = f.queue[out].address;
        push.argsOut = f.args[out].address;
        push.shadow = f.shadow[in].address;
        push.argsShadow = f.shadowArgs[in].address;
        const vk::Buffer* inArgs = &f.args[in];

        if (s.config.sort) {
            addPass(s, "pt_sortclear" + btag, {{&f.keys, Access::TransferDst}}, {}, [&f](VkCommandBuffer cmd) {
                vkCmdFillBuffer(cmd, f.keys.buffer, 0, VK_WHOLE_SIZE, gpu::kPtSortKeyDead);
            });
        }
        gpu::GpuPtStagePush trace = push;
        trace.aux = s.config.sort ? f.keys.address : 0;
        std::vector<BufferUse> traceUses = {{&f.queue[in], Access::StorageRead}, {inArgs, Access::IndirectRead},
                                            {&f.paths, Access::StorageRead}, {&f.hits, Access::StorageWrite}};
        if (s.config.sort) traceUses.push_back({&f.keys, Access::StorageWrite});
        addPass(s, "pt_trace" + btag, traceUses, {}, [s, trace, inArgs, traceShader](VkCommandBuffer cmd) {
            bindAndPush(s, cmd, pipeline(s, traceShader, true, kLinear), trace);
            vkCmdDispatchIndirect(cmd, inArgs->buffer, 0);
        });
        if (s.config.sort) {
            addPass(s, "pt_sort" + btag,
                    {{&f.keys, Access::StorageReadWrite}, {&f.queue[in], Access::StorageReadWrite},
                     {&f.sortScratch, Access::StorageReadWrite}},
                    {}, [s, in, pixels, &f](VkCommandBuffer cmd) {
                        ComputeKernels kernels{s.ctx, s.shaders};
                        recordRadixSort(cmd, kernels, GpuArray{f.keysIndex, 0},
                                        GpuArray{f.queueIndex[in], gpu::kPtQueueHeaderWords}, pixels,
                                        GpuArray{f.scratchIndex, 0}, gpu::kPtSortKeyBits);
                    });
        }
        std::vector<BufferUse> shadeUses = {{&f.queue[in], Access::StorageRead},     {inArgs, Access::IndirectRead},
                                            {&f.hits, Access::StorageRead},          {&f.paths, Access::StorageReadWrite},
                                            {&f.queue[out], Access::StorageReadWrite}, {&f.shadow[in], Access::StorageReadWrite},
                                            {&f.shadowRays, Access::StorageWrite}};
        if (bounce == 0) shadeUses.push_back({&f.guides, Access::StorageWrite});
        addPass(s, "pt_shade" + btag, shadeUses, {}, [s, push, inArgs](VkCommandBuffer cmd) {
            bindAndPush(s, cmd, pipeline(s, ShaderId::pathtrace_shade_comp, true, kLinear), push);
            vkCmdDispatchIndirect(cmd, inArgs->buffer, 0);
        });
        if (stop.kind == PtStop::AfterShade && stop.bounce == bounce) return;

        gpu::GpuPtStagePush args = push;
        args.aux = f.shadow[out].address;
        addPass(s, "pt_args" + btag,
                {{&f.queue[out], Access::StorageRead}, {&f.shadow[in], Access::StorageRead},
                 {&f.queue[in], Access::StorageWrite}, {&f.shadow[out], Access::StorageWrite},
                 {&f.args[out], Access::StorageWrite}, {&f.shadowArgs[in], Access::StorageWrite}},
                {}, [s, args](VkCommandBuffer cmd) {
                    bindAndPush(s, cmd, pipeline(s, ShaderId::pathtrace_args_comp, false, {1, 1, 1}), args);
                    vkCmdDispatch(cmd, 1, 1, 1);
                });
        if (stop.kind == PtStop::AfterArgs && stop.bounce == bounce) return;
        const vk::Buffer* shadowArgs = &f.shadowArgs[in];
        addPass(s, "pt_shadow" + btag,
                {{&f.shadow[in], Access::StorageRead}, {shadowArgs, Access::IndirectRead},
                 {&f.shadowRays, Access::StorageRead}, {&f.paths, Access::StorageReadWrite}},
                {}, [s, push, shadowArgs, shadowShader](VkCommandBuffer cmd) {
                    bindAndPush(s, cmd, pipeline(s, shadowShader, true, kLinear), push);
                    vkCmdDispatchIndirect(cmd, shadowArgs->buffer, 0);
                });
    }

    gpu::GpuPtStagePush acc = basePush(s);
    acc.sampleIndex = sampleIndex;
    addPass(s, "pt_accumulate" + tag,
            {{&f.paths, Access::StorageRead}, {&f.guides, Access::StorageRead}, {&f.accumColor, Access::StorageReadWrite},
             {&f.accumAlbedo, Access::StorageReadWrite}, {&f.accumNormal, Access::StorageReadWrite},
             {&f.accumDepth, Access::StorageReadWrite}, {&f.accumMoment, Access::StorageReadWrite}},
            {}, [s, acc, pixels](VkCommandBuffer cmd) {
                bindAndPush(s, cmd, pipeline(s, ShaderId::pathtrace_accumulate_comp, false, kLinear), acc);
                vkCmdDispatch(cmd, vk::groupCount(pixels, gpu::kPtGroupSize), 1, 1);
            });
}

void addPtDenoise(const PtStageContext& s) {
#if IDK_PT_HAS_DENOISER
    PtFrameResources& f = s.frame;
    passes::DenoiseInputs in;
    in.color = s.res.image(f.colorImage, f.colorStorage.value);
    in.albedo = s.res.image(f.albedoImage, f.albedoStorage.value);
    in.normal = s.res.image(f.normalImage, f.normalStorage.value);
    in.depth = s.res.image(f.depthImage, f.depthStorage.value);
    in.variance = s.res.image(f.varianceImage, f.varianceStorage.value);
    const graph::TextureHandle denoised = passes::addDenoisePass(s.graph, s.ctx, s.shaders, in, passes::DenoiseSettings{});
    graph::TextureHandle& target = s.res.image(f.denoisedImage);
    s.graph.addPass(
        "pt_denoisecopy",
        [&](graph::PassBuilder& b) {
            b.read(denoised, Access::TransferSrc);
            target = b.write(target, Access::TransferDst);
            b.sideEffect();
        },
        [denoised, &f](graph::PassContext& pc) {
            VkImageCopy copy{};
            copy.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
            copy.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
            copy.extent = {f.width, f.height, 1};
            vkCmdCopyImage(pc.commandBuffer(), pc.image(denoised), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                           f.denoisedImage.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
        });
#else
    (void)s;
    throw std::runtime_error("path tracer: this build has no denoiser (engine/passes/denoise.hpp)");
#endif
}

bool denoiserAvailable() { return IDK_PT_HAS_DENOISER != 0; }

void addPtResolve(const PtStageContext& s) {
    PtFrameResources& f = s.frame;
    gpu::GpuPtStagePush push = basePush(s);
    addPass(s, "pt_resolve",
            {{&f.accumColor, Access::StorageRead}, {&f.accumAlbedo, Access::StorageRead},
             {&f.accumNormal, Access::StorageRead}, {&f.accumDepth, Access::StorageRead},
             {&f.accumMoment, Access::StorageRead}},
            {{&f.colorImage, Access::StorageWrite}, {&f.albedoImage, Access::StorageWrite},
             {&f.normalImage, Access::StorageWrite}, {&f.depthImage, Access::StorageWrite},
             {&f.varianceImage, Access::StorageWrite}},
            [s, push, &f](VkCommandBuffer cmd) {
                bindAndPush(s, cmd, pipeline(s, ShaderId::pathtrace_resolve_comp, false, {8, 8, 1}), push);
                vkCmdDispatch(cmd, vk::groupCount(f.width, 8), vk::groupCount(f.height, 8), 1);
            });
}

}  // namespace idk::render
