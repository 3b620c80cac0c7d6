// vxgi_gl_accumulate.cpp: the gl-interop rung of "vxgi-atomics" (see the header): the shared record and sums
// buffers, and the pass that hands the records to OpenGL, adds them with GL float atomics and gives the sums back
// to Vulkan within one frame. The GL-side counterpart of IDKEngine's Voxelizer.cs fragment atomics.
#include "passes/vxgi_gl_accumulate.hpp"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

#include "gl/gl_compute.hpp"
#include "gl/gl_sync.hpp"
#include "gl/shared_memory.hpp"
#include "shared/vxgi_types.h"
#include "vk/check.hpp"
#include "vk/context.hpp"
#include "vk/shader_library.hpp"
#include "vk/transfer.hpp"

namespace idk::passes {
namespace {

constexpr VkPipelineStageFlags2 kCs = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
constexpr uint32_t kGroup = 64;         // vxgi_accumulate.comp's local size
constexpr uint32_t kMaxGroupsX = 65535;  // GL's guaranteed GL_MAX_COMPUTE_WORK_GROUP_COUNT per dimension

std::string readGlSource(const std::filesystem::path& dir, const char* file) {
    const std::filesystem::path name = std::filesystem::path("gl") / file;
    const std::filesystem::path path = !dir.empty() && std::filesystem::exists(dir / name)
                                           ? dir / name
                                           : std::filesystem::path(shaders::kShaderSourceDir) / name;
    std::ifstream stream(path);
    if (!stream) throw std::runtime_error(path.string() + ": cannot open the GL voxel accumulation shader");
    std::stringstream text;
    text << stream.rdbuf();
    return text.str();
}

VkDeviceSize recordBytes(uint32_t capacity) {
    return (VkDeviceSize(gpu::kVoxelRecordHeaderWords) + VkDeviceSize(capacity) * gpu::kVoxelRecordWords) * 4;
}

VkDeviceSize sumsBytes(uint32_t n) { return VkDeviceSize(n) * n * n * gpu::kVoxelSumWords * 4; }
uint32_t firstCapacity(uint32_t n) { return 16 * n * n; }  // a few walls across the grid, with depth complexity

// The label the graph opened around the pass closes before the command buffer ends and reopens after it begins
// again, so each submission's labels balance.
void endLabel(VkCommandBuffer cmd) {
    if (vkCmdBeginDebugUtilsLabelEXT && vkCmdEndDebugUtilsLabelEXT) vkCmdEndDebugUtilsLabelEXT(cmd);
}
void beginLabel(VkCommandBuffer cmd, const char* name) {
    if (!vkCmdBeginDebugUtilsLabelEXT || !vkCmdEndDebugUtilsLabelEXT) return;
    VkDebugUtilsLabelEXT label{VK_STRUCTURE_TYPE_DEBUG_UTILS_LABEL_EXT};
    label.pLabelName = name;
    vkCmdBeginDebugUtilsLabelEXT(cmd, &label);
}

}  // namespace

VxgiGlAccumulator::VxgiGlAccumulator(vk::Context& ctx, VxgiGlProgram program, const std::filesystem::path& glShaderDir)
    : ctx_(ctx), kind_(program) {
    const gl::GlContext* gl = ctx.glContext();
    if (!gl) throw std::runtime_error("vxgi-atomics gl-interop: no OpenGL context: " + ctx.capabilities().glInteropNote);
    const bool half = program == VxgiGlProgram::Fp16Vector;
    const char* file = half ? "vxgi_accumulate_fp16.comp.glsl" : "vxgi_accumulate.comp.glsl";
    const std::string source = readGlSource(glShaderDir, file);
    const std::string resolveSource = half ? readGlSource(glShaderDir, "vxgi_resolve_fp16.comp.glsl") : "";
    {
        // The GL driver compiles the sources: one without an extension they require refuses them, naming it.
        gl::GlContext::Current current(*gl);
        program_ = std::make_unique<gl::ComputeProgram>(*gl, std::string("gl/") + file, source);
        if (half)
            resolve_ = std::make_unique<gl::ComputeProgram>(*gl, "gl/vxgi_resolve_fp16.comp.glsl", resolveSource);
    }
    try {
        handOff_ = std::make_unique<gl::HandOff>(ctx, *gl, "vxgi gl accumulate");
        if (handOff_->usesSemaphores()) {
            countCopy_ = ctx.createBuffer({4, VK_BUFFER_USAGE_TRANSFER_DST_BIT, vk::MemoryUsage::Readback,
                                           "vxgi gl record count", "vxgi"});
            if (!countCopy_.mapped()) throw std::runtime_error("vxgi gl-interop: the record count copy is not mapped");
        }
    } catch (...) {
        handOff_.reset();
        if (countCopy_) ctx.destroy(countCopy_);
        gl::GlContext::Current current(*gl);
        program_.reset();
        resolve_.reset();
        throw;
    }
}

VxgiGlAccumulator::~VxgiGlAccumulator() {
    releaseBuffers();
    handOff_.reset();
    if (countCopy_) ctx_.destroyDeferred(countCopy_);
    if (!program_) return;
    try {
        gl::GlContext::Current current(*ctx_.glContext());
        releaseHalfSums();
        program_.reset();
        resolve_.reset();
    } catch (const gl::GlError&) {
        // The context cannot be made current: the deletes are no-ops without one, GL frees the objects with it.
        program_.reset();
        resolve_.reset();
    }
}

void VxgiGlAccumulator::releaseBuffers() {
    // SharedBuffer defers the Vulkan side until the frames using it completed.
    if (records_) ctx_.bindless().release(recordsIndex_);
    if (sums_) ctx_.bindless().release(sumsIndex_);
    records_.reset();
    sums_.reset();
    recordsIndex_ = sumsIndex_ = {};
}

void VxgiGlAccumulator::releaseHalfSums() {
    const gl::Api& api = ctx_.glContext()->api();
    if (halfSums_[0]) api.glDeleteTextures(2, halfSums_);
    if (counts_) api.glDeleteBuffers(1, &counts_);
    halfSums_[0] = halfSums_[1] = counts_ = 0;
}

VkDeviceSize VxgiGlAccumulator::firstFrameBytes(uint32_t n) { return sumsBytes(n) + recordBytes(firstCapacity(n)); }

void VxgiGlAccumulator::prepare(uint32_t n) {
    settleStats();  // the last frame's overflow decides this frame's capacity
    if (wanted_ == 0) wanted_ = firstCapacity(n);
    if (sums_ && gridSize_ == n && capacity_ == wanted_) return;
    const gl::GlContext& gl = *ctx_.glContext();
    // The descriptor's range limit caps the records (the sums of a 512^3 grid, 2.7 GB, would exceed it too: the
    // bindless table then throws DeviceLimitError naming the buffer).
    const VkDeviceSize maxRange = ctx_.info().limits.maxStorageBufferRange;
    const VkDeviceSize maxRecords = (maxRange / 4 - gpu::kVoxelRecordHeaderWords) / gpu::kVoxelRecordWords;
    wanted_ = uint32_t(std::min<VkDeviceSize>(wanted_, maxRecords));
    if (!sums_ || gridSize_ != n) {
        if (sums_) ctx_.bindless().release(sumsIndex_);
        sums_.reset();
        const VkDeviceSize bytes = sumsBytes(n);
        sums_ = std::make_unique<gl::SharedBuffer>(ctx_, gl, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "vxgi gl sums");
        sumsIndex_ = ctx_.bindless().addBuffer(sums_->vk().buffer, bytes, "vxgi gl sums");
        gridSize_ = n;
        if (kind_ == VxgiGlProgram::Fp16Vector) {  // GL-only: Vulkan reads the resolved sums, never these
            gl::GlContext::Current current(gl);
            releaseHalfSums();
            const gl::Api& api = gl.api();
            api.glCreateTextures(GL_TEXTURE_3D, 2, halfSums_);
            for (GLuint t : halfSums_) api.glTextureStorage3D(t, 1, GL_RGBA16F, GLsizei(n), GLsizei(n), GLsizei(n));
            api.glCreateBuffers(1, &counts_);
            api.glNamedBufferStorage(counts_, GLsizeiptr(n) * n * n * 4, nullptr, 0);
            gl.check("vxgi gl-interop: creating the RGBA16F sums");
        }
    }
    if (!records_ || capacity_ != wanted_) {
        if (records_) ctx_.bindless().release(recordsIndex_);
        records_.reset();
        const VkDeviceSize bytes = recordBytes(wanted_);
        records_ = std::make_unique<gl::SharedBuffer>(ctx_, gl, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                                      "vxgi gl records");
        recordsIndex_ = ctx_.bindless().addBuffer(records_->vk().buffer, bytes, "vxgi gl records");
        capacity_ = wanted_;
    }
}

const vk::Buffer& VxgiGlAccumulator::sumsBuffer() const {
    if (!sums_) throw std::logic_error("VxgiGlAccumulator::sumsBuffer: no frame was prepared");
    return sums_->vk();
}

graph::BufferHandle VxgiGlAccumulator::importRecords(graph::RenderGraph& graph) const {
    graph::PhysicalBuffer p{records_->vk().buffer, records_->size(), 0, recordsIndex_.value, 0};
    // Last frame read it in its GL pass (compute stage after the acquire): a WAR wait before this frame's clear.
    graph::ResourceState state;
    state.readStages = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    return graph.importBuffer("vxgi gl records", p, state);
}

graph::BufferHandle VxgiGlAccumulator::importSums(graph::RenderGraph& graph) const {
    graph::PhysicalBuffer p{sums_->vk().buffer, sums_->size(), 0, sumsIndex_.value, 0};
    graph::ResourceState state;  // last frame's merge read it
    state.readStages = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    return graph.importBuffer("vxgi gl sums", p, state);
}

graph::BufferHandle VxgiGlAccumulator::addPass(graph::RenderGraph& graph, graph::BufferHandle records,
                                               graph::BufferHandle sums) {
    auto written = std::make_shared<graph::BufferHandle>();
    graph.addPass(
        "vxgi_gl_accumulate",
        [&](graph::PassBuilder& b) {
            b.read(records, graph::Access::StorageRead, kCs);
            *written = b.write(sums, graph::Access::StorageReadWrite, kCs);
        },
        [this](graph::PassContext& pc) { handOver(pc.commandBuffer()); });
    return *written;
}

const VxgiGlStats& VxgiGlAccumulator::lastStats() const {
    settleStats();
    return stats_;
}

void VxgiGlAccumulator::recordStats(uint32_t appended) const {
    const uint32_t count = std::min(appended, capacity_);
    stats_ = {appended, capacity_, appended - count};
    if (!stats_.dropped) return;
    wanted_ = uint32_t(std::min<uint64_t>(uint64_t(stats_.appended) * 5 / 4 + 1, UINT32_MAX));
    std::fprintf(stderr,
                 "vxgi gl-interop: %u of %u voxel fragments overflowed the record buffer (%u records) and were "
                 "dropped this frame; it grows to %u records from the next frame (a still renders again)\n",
                 stats_.dropped, stats_.appended, stats_.capacity, wanted_);
}

void VxgiGlAccumulator::settleStats() const {
    if (!pendingCount_) return;
    const uint64_t value = std::exchange(pendingCount_, 0);
    ctx_.waitFor(value);  // the hand-off's acquire submission, which copied the count after GL's work
    const vk::MemoryAllocation& a = countCopy_.allocation;
    if (!a.hostCoherent) {
        VkMappedMemoryRange range{VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE};
        range.memory = a.memory;
        range.size = VK_WHOLE_SIZE;
        vk::check(vkInvalidateMappedMemoryRanges(ctx_.device(), 1, &range));
    }
    uint32_t appended = 0;
    std::memcpy(&appended, countCopy_.mapped(), sizeof appended);
    recordStats(appended);
}

void VxgiGlAccumulator::accumulateOnGl() {
    const gl::GlContext& gl = *ctx_.glContext();
    uint32_t dispatched = capacity_;
    if (!handOff_->usesSemaphores()) {
        // The voxelization has completed (CPU-side wait): the count is read here, and only its records dispatched.
        uint32_t appended = 0;
        gl.api().glGetNamedBufferSubData(records_->gl(), 0, sizeof(appended), &appended);
        gl.check("vxgi gl-interop: reading the record count");
        recordStats(appended);
        dispatched = std::min(appended, capacity_);
    }
    // With semaphores the voxelization may still run when this is issued: reading the count here would block this
    // thread until it completed, so GL dispatches for the whole capacity and the shader skips past the count.
    const gl::Api& api = gl.api();
    const uint32_t groups = (dispatched + kGroup - 1) / kGroup;
    program_->setUint("capacity", capacity_);
    api.glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, records_->gl());
    if (kind_ == VxgiGlProgram::Float) {
        program_->setUint("voxelCount", gridSize_ * gridSize_ * gridSize_);
        api.glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, sums_->gl());
        if (groups) program_->dispatch(std::min(groups, kMaxGroupsX), (groups + kMaxGroupsX - 1) / kMaxGroupsX);
        return;
    }
    // Fp16Vector: zero the GL sums, add the records into them, resolve them into the shared sums (every word of
    // it: Vulkan's clear before is overwritten). The dispatches end with a full memory barrier (gl_compute.cpp).
    const GLfloat zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    const GLuint zeroCount = 0;
    for (GLuint t : halfSums_) api.glClearTexImage(t, 0, GL_RGBA, GL_FLOAT, zero);
    api.glClearNamedBufferData(counts_, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zeroCount);
    api.glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
    program_->setUint("gridSize", gridSize_);
    api.glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, counts_);
    for (GLuint i = 0; i < 2; ++i)  // layered: the whole 3D texture
        api.glBindImageTexture(i, halfSums_[i], 0, GL_TRUE, 0, GL_READ_WRITE, GL_RGBA16F);
    if (groups) program_->dispatch(std::min(groups, kMaxGroupsX), (groups + kMaxGroupsX - 1) / kMaxGroupsX);
    resolve_->setUint("gridSize", gridSize_);
    api.glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, sums_->gl());
    const GLuint voxelGroups = (gridSize_ + 3) / 4;  // vxgi_resolve_fp16.comp: 4x4x4
    resolve_->dispatch(voxelGroups, voxelGroups, voxelGroups);
    gl.check("vxgi gl-interop: the fp16 vector adds");
}

void VxgiGlAccumulator::handOver(VkCommandBuffer cmd) {
    // Vulkan's side: the graph's barrier before this pass made the fragments' records and the clear of the sums
    // visible to compute; the release to VK_QUEUE_FAMILY_EXTERNAL follows it (shared_memory.hpp).
    gl::releaseToGl(cmd, ctx_, *records_, kCs, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
    gl::releaseToGl(cmd, ctx_, *sums_, kCs, VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    endLabel(cmd);
    vk::check(vkEndCommandBuffer(cmd));
    handOff_->submitToGl(cmd);  // CPU-wait mode: the voxelization has completed when it returns

    // Begin the same command buffer again (an implicit reset: its pool has RESET_COMMAND_BUFFER_BIT) and take the
    // buffers back; also when GL throws, so the caller can still end and submit it.
    auto beginAgain = [&] {
        VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
        begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
        vk::check(vkBeginCommandBuffer(cmd, &begin));
        beginLabel(cmd, "vxgi_gl_accumulate");
    };
    const bool copyCount = handOff_->usesSemaphores();
    auto acquire = [&](VkCommandBuffer c) {
        constexpr VkPipelineStageFlags2 kCsCopy = kCs | VK_PIPELINE_STAGE_2_COPY_BIT;
        gl::acquireFromGl(c, ctx_, *records_, kCsCopy, VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_TRANSFER_READ_BIT);
        gl::acquireFromGl(c, ctx_, *sums_, kCs, VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
        if (!copyCount) return;
        // Semaphore mode: the count, for lastStats, copied after GL's work and made visible to the host.
        const VkBufferCopy region{0, 0, 4};
        vkCmdCopyBuffer(c, records_->vk().buffer, countCopy_.buffer, 1, &region);
        vk::memoryBarrier(c, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT,
                          VK_ACCESS_2_HOST_READ_BIT);
    };
    const GLuint buffers[2] = {records_->gl(), sums_->gl()};
    try {
        gl::GlContext::Current current(*ctx_.glContext());
        handOff_->glBegin(buffers);
        accumulateOnGl();
        handOff_->glEnd(buffers);  // glFinish, or the signal to Vulkan and a flush
    } catch (...) {
        beginAgain();
        handOff_->resumeVulkan(cmd, acquire);
        throw;
    }
    beginAgain();
    const uint64_t value = handOff_->resumeVulkan(cmd, acquire);
    if (copyCount) pendingCount_ = value;
}

}  // namespace idk::passes
