// float_splat.cpp: the float-atomics ladder's three rungs and the two-pass render graph around them.
#include "render/float_splat.hpp"

#include <array>
#include <fstream>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "gl/gl_compute.hpp"
#include "gl/gl_sync.hpp"
#include "gl/shared_memory.hpp"
#include "graph/render_graph.hpp"
#include "render/vk_graph_backend.hpp"
#include "shared/splat_push.h"
#include "vk/bindless.hpp"
#include "vk/context.hpp"
#include "vk/shader_library.hpp"
#include "vk/transfer.hpp"

namespace idk::render {
namespace {

// From `dir` when it has the file (a --shader-dir override), else from the build's shaders_glsl/.
std::string readGlSource(const std::filesystem::path& dir) {
    const std::filesystem::path name = std::filesystem::path("gl") / "splat_add.comp.glsl";
    const std::filesystem::path path = !dir.empty() && std::filesystem::exists(dir / name)
                                           ? dir / name
                                           : std::filesystem::path(shaders::kShaderSourceDir) / name;
    std::ifstream file(path);
    if (!file) throw std::runtime_error(path.string() + ": cannot open the GL splat shader");
    std::stringstream text;
    text << file.rdbuf();
    return text.str();
}

const vk::RungOption& rungOption(const vk::Ladder& ladder, vk::Rung rung) {
    for (const vk::RungOption& o : ladder.options) {
        if (o.rung != rung) continue;
        if (!o.available)
            throw std::runtime_error(std::string("float-atomics rung ") + vk::rungName(rung) + " is unavailable: " + o.note);
        return o;
    }
    throw std::invalid_argument("the float-atomics ladder has no such rung");
}

// One of the three buffers of a splat: shared with GL on the GL rung, plain Vulkan otherwise.
struct SplatBuffer {
    std::unique_ptr<gl::SharedBuffer> shared;
    vk::Buffer plain;
    vk::StorageBufferIndex index;
    const vk::Buffer& vk() const { return shared ? shared->vk() : plain; }
};

graph::PhysicalBuffer physical(const vk::Buffer& b) {
    graph::PhysicalBuffer p;
    p.buffer = b.buffer;
    p.size = b.size;
    return p;
}

}  // namespace

void recordSplatAdd(VkCommandBuffer cmd, const ComputeKernels& kernels, vk::Rung rung, GpuArray bins,
                    GpuArray sampleBins, GpuArray sampleValues, uint32_t count, uint32_t binCount) {
    if (rung == vk::Rung::GlInterop) throw std::invalid_argument("recordSplatAdd: the GL rung runs in runSplatGraph");
    if (bins.offset || sampleBins.offset || sampleValues.offset)
        throw std::invalid_argument("recordSplatAdd: arrays start at element 0 of their buffers");
    if (count == 0) return;
    const vk::ShaderId id =
        rung == vk::Rung::Native ? vk::ShaderId::atomics_splat_add_native_comp : vk::ShaderId::atomics_splat_add_cas_comp;
    const vk::Pipeline& pipeline = kernels.shaders.compute(
        {id, {}, sizeof(gpu::SplatPush), std::array<uint32_t, 3>{gpu::kSplatGroupSize, 1, 1}});
    kernels.ctx.bindless().bind(cmd);
    vk::bindPipeline(cmd, pipeline);
    vk::pushConstants(cmd, kernels.ctx,
                      gpu::SplatPush{bins.buffer.value, sampleBins.buffer.value, sampleValues.buffer.value, count, binCount});
    vkCmdDispatch(cmd, vk::groupCount(count, gpu::kSplatGroupSize), 1, 1);
}

SplatResult runSplatGraph(vk::Context& ctx, vk::ShaderLibrary& shaders, const SplatInput& input,
                          std::optional<vk::Rung> rung, const std::filesystem::path& glShaderDir) {
    if (input.bins.size() != input.values.size()) throw std::invalid_argument("runSplatGraph: bins and values differ in size");
    if (input.binCount == 0) throw std::invalid_argument("runSplatGraph: no bins");
    const vk::Ladder& ladder = ctx.ladder("float-atomics");
    const vk::Rung r = rung.value_or(ladder.chosen);
    rungOption(ladder, r);
    const bool onGl = r == vk::Rung::GlInterop;
    const gl::GlContext* gl = ctx.glContext();
    const uint32_t count = uint32_t(input.bins.size());

    // bins, sample bins, sample values; then the consumer's total and reduction scratch (Vulkan only).
    SplatBuffer buffers[3];
    const char* names[3] = {"splat bins", "splat sample bins", "splat sample values"};
    const VkDeviceSize sizes[3] = {VkDeviceSize(input.binCount) * 4, VkDeviceSize(std::max(count, 1u)) * 4,
                                   VkDeviceSize(std::max(count, 1u)) * 4};
    for (int i = 0; i < 3; ++i) {
        if (onGl)
            buffers[i].shared = std::make_unique<gl::SharedBuffer>(ctx, *gl, sizes[i], VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, names[i]);
        else
            buffers[i].plain = ctx.createBuffer({sizes[i], VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUsage::GpuOnly, names[i], "splat"});
        buffers[i].index = ctx.bindless().addBuffer(buffers[i].vk().buffer);
    }
    vk::Buffer total = ctx.createBuffer({4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUsage::GpuOnly, "splat total", "splat"});
    const uint32_t scratchElements = std::max(reduceScratchElements(input.binCount), 1u);
    vk::Buffer scratch = ctx.createBuffer({VkDeviceSize(scratchElements) * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                           vk::MemoryUsage::GpuOnly, "splat reduce scratch", "splat"});
    const vk::StorageBufferIndex totalIndex = ctx.bindless().addBuffer(total.buffer);
    const vk::StorageBufferIndex scratchIndex = ctx.bindless().addBuffer(scratch.buffer);

    const std::vector<float> zeros(input.binCount, 0.0f);
    vk::uploadBuffer(ctx, buffers[0].vk(), std::span<const float>(zeros));
    if (count) {
        vk::uploadBuffer(ctx, buffers[1].vk(), std::span<const uint32_t>(input.bins));
        vk::uploadBuffer(ctx, buffers[2].vk(), std::span<const float>(input.values));
    }
    std::unique_ptr<gl::ComputeProgram> program;
    std::unique_ptr<gl::HandOff> handOff;
    GLuint glBuffers[3] = {};
    if (onGl) {
        {
            gl::GlContext::Current current(*gl);
            program = std::make_unique<gl::ComputeProgram>(*gl, "gl/splat_add.comp.glsl", readGlSource(glShaderDir));
        }
        for (int i = 0; i < 3; ++i) glBuffers[i] = buffers[i].shared->gl();
        // Handed to GL (gl_sync.hpp): a CPU-side wait for the release, or a semaphore GL waits for.
        handOff = std::make_unique<gl::HandOff>(ctx, *gl, "float splat");
        handOff->submitToGl([&](VkCommandBuffer cmd) {
            for (const SplatBuffer& b : buffers)
                gl::releaseToGl(cmd, ctx, *b.shared, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
        });
    }

    const ComputeKernels kernels{ctx, shaders};
    VkGraphBackend backend(ctx);
    graph::ResourcePool pool(backend);
    graph::RenderGraph graph(pool, {1, 1});
    const graph::FinalUse copyOut{graph::Access::TransferSrc};
    graph::BufferHandle bins = graph.importBuffer(names[0], physical(buffers[0].vk()), {}, copyOut);
    const graph::BufferHandle sampleBins = graph.importBuffer(names[1], physical(buffers[1].vk()), {});
    const graph::BufferHandle sampleValues = graph.importBuffer(names[2], physical(buffers[2].vk()), {});
    graph::BufferHandle totalHandle = graph.importBuffer("splat total", physical(total), {}, copyOut);
    constexpr VkPipelineStageFlags2 kCompute = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;

    graph.addPass(std::string("splat (") + vk::rungName(r) + ")", [&](graph::PassBuilder& b) {
        b.read(sampleBins, graph::Access::StorageRead, kCompute);
        b.read(sampleValues, graph::Access::StorageRead, kCompute);
        bins = b.write(bins, graph::Access::StorageReadWrite, kCompute);
    }, [&](graph::PassContext& pass) {
        if (!onGl) {
            recordSplatAdd(pass.commandBuffer(), kernels, r, {buffers[0].index}, {buffers[1].index},
                           {buffers[2].index}, count, input.binCount);
            return;
        }
        // GL runs while the graph records: its work is done (glFinish) or signalled to Vulkan (semaphore) before the
        // command buffer that reads the bins is submitted; resumeVulkan gives the buffers back ahead of it.
        try {
            gl::GlContext::Current current(*gl);
            handOff->glBegin(glBuffers);
            program->setUint("count", count);
            program->setUint("binCount", input.binCount);
            for (GLuint i = 0; i < 3; ++i) gl->api().glBindBufferBase(GL_SHADER_STORAGE_BUFFER, i, glBuffers[i]);
            if (count) program->dispatch(vk::groupCount(count, gpu::kSplatGroupSize));
            handOff->glEnd(glBuffers);
        } catch (...) {
            handOff->resumeVulkan(pass.commandBuffer(), [](VkCommandBuffer) {});
            throw;
        }
        handOff->resumeVulkan(pass.commandBuffer(), [&](VkCommandBuffer cmd) {
            for (const SplatBuffer& b : buffers)
                gl::acquireFromGl(cmd, ctx, *b.shared, kCompute,
                                  VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
        });
    });
    graph.addPass("sum bins", [&](graph::PassBuilder& b) {
        b.read(bins, graph::Access::StorageRead, kCompute);
        totalHandle = b.write(totalHandle, graph::Access::StorageWrite, kCompute);
    }, [&](graph::PassContext& pass) {
        // The reduction's scratch is private to this pass; recordReduce orders its own dispatches.
        recordReduce(pass.commandBuffer(), kernels, SumElement::Float, {buffers[0].index}, input.binCount,
                     {totalIndex}, {scratchIndex});
    });
    graph.markOutput(bins);
    graph.markOutput(totalHandle);
    ctx.runImmediate([&](VkCommandBuffer cmd) { graph.execute(cmd); });

    SplatResult result;
    result.rung = r;
    result.bins = vk::downloadBuffer<float>(ctx, buffers[0].vk(), input.binCount);
    result.total = vk::downloadBuffer<float>(ctx, total, 1)[0];
    if (onGl) {
        handOff.reset();
        gl::GlContext::Current current(*gl);
        program.reset();
    }
    for (SplatBuffer& b : buffers) {
        ctx.bindless().release(b.index);
        if (b.plain) ctx.destroyDeferred(b.plain);
    }
    ctx.bindless().release(totalIndex);
    ctx.bindless().release(scratchIndex);
    ctx.destroyDeferred(total);
    ctx.destroyDeferred(scratch);
    return result;
}

SplatResult splatOracle(const SplatInput& input) {
    std::vector<double> sums(input.binCount, 0.0);
    for (size_t i = 0; i < input.bins.size(); ++i)
        if (input.bins[i] < input.binCount) sums[input.bins[i]] += input.values[i];
    SplatResult r;
    double total = 0.0;
    for (double s : sums) {
        r.bins.push_back(float(s));
        total += s;
    }
    r.total = float(total);
    return r;
}

}  // namespace idk::render
