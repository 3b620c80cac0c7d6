// vxgi_gl_accumulate.hpp: the gl-interop rung of the "vxgi-atomics" ladder. The voxelization's fragments append
// records (voxel, premultiplied rgba) to a buffer shared with OpenGL; the "vxgi_gl_accumulate" pass hands it to GL,
// whose compute program (shaders_glsl/gl/vxgi_accumulate.comp.glsl) adds the records into a shared sums buffer with
// GL_NV_shader_atomic_float, and gives the sums back to Vulkan, whose merge pass (vxgi_voxelize.cpp) averages them
// into the RGBA16F grid in the same render graph.
//
// The hand-over (gl/gl_sync.hpp): the pass ends the graph's command buffer and submits it, GL runs, then the pass
// begins the same command buffer again and the rest of the frame is recorded into it. So the graph's command buffer
// must come from a pool created with VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT (vk::FrameRing's and
// Context::runImmediate's are). With CPU-side waits (llvmpipe: no GL_EXT_semaphore_fd; or IDK_GL_SYNC=cpu) the
// submission is waited for, GL reads the record count, dispatches for it and ends with glFinish. With semaphores
// no thread waits: GL waits for Vulkan's signal on its own queue, dispatches for the whole capacity (the shader
// reads the count from the record header), signals Vulkan, and the frame's stats come from a copy of the header
// made after GL's work, read when they are asked for (lastStats, the next prepare: it waits for the last frame's
// hand-off to complete, since that frame's count decides the capacity of this one).
//
// Overflow: the record buffer holds `capacity` records (first frame: 16 n^2 for an n^3 grid). The fragment counter
// counts past it, the host reads it at the hand-over: records past the capacity are dropped from that frame (GL
// adds those that fit), the drop is reported (stderr and lastStats()) and the buffer grows to hold 1.25x the count
// from the next frame on; Renderer::renderStill then renders the frame again (the grid fits the scene, not the
// camera, so the count repeats and fits). Measured at 64^3: DamagedHelmet 74029 fragments, ToyCar 190362.
//
// Two GL programs add the records ("vxgi-gl-accumulate" ladder): Float, gl/vxgi_accumulate.comp, eight
// GL_NV_shader_atomic_float adds and a count per record straight into the shared sums; Fp16Vector (where the GL
// context has GL_NV_shader_atomic_fp16_vector), gl/vxgi_accumulate_fp16.comp, two f16vec4 image atomics per record
// into GL-owned RGBA16F 3D images ((r, g, b, coverage) and the facing) and a uint count, then
// gl/vxgi_resolve_fp16.comp writes them into the shared sums in the same layout, so the merge is the same. On a
// GPU the vector atomics are 3 instead of 9 atomic operations per fragment on the hot voxels, at half precision (11
// significant bits; the grid is RGBA16F anyway).
#pragma once
#include <cstdint>
#include <filesystem>
#include <memory>

#include "graph/render_graph.hpp"
#include "vk/bindless.hpp"
#include "vk/resources.hpp"

namespace idk::gl {
class ComputeProgram;
class HandOff;
class SharedBuffer;
}  // namespace idk::gl
namespace idk::vk {
class Context;
}

namespace idk::passes {

struct VxgiGlStats {
    uint32_t appended = 0;  // fragments the last frame's voxelization produced
    uint32_t capacity = 0;  // records its buffer held
    uint32_t dropped = 0;   // appended - capacity when it overflowed, else 0
};

enum class VxgiGlProgram : uint8_t { Float, Fp16Vector };

class VxgiGlAccumulator {
public:
    // Throws std::runtime_error when ctx has no GL context (the rung is unavailable), gl::GlError when the GL driver
    // refuses a program (Fp16Vector without GL_NV_shader_atomic_fp16_vector: the driver's log names it).
    // glShaderDir/gl/<program>.comp.glsl, when present, replaces the build's GL source.
    explicit VxgiGlAccumulator(vk::Context& ctx, VxgiGlProgram program = VxgiGlProgram::Float,
                               const std::filesystem::path& glShaderDir = {});
    VxgiGlProgram program() const noexcept { return kind_; }
    ~VxgiGlAccumulator();
    VxgiGlAccumulator(const VxgiGlAccumulator&) = delete;
    VxgiGlAccumulator& operator=(const VxgiGlAccumulator&) = delete;

    // Before a frame's passes: sizes the sums for an n^3 grid and the records for the current capacity.
    void prepare(uint32_t gridSize);
    // The shared buffers' bytes for an n^3 grid's first frame (sums, and records at the first capacity); the memory
    // check (frame/vxgi_memory.hpp) uses it.
    static VkDeviceSize firstFrameBytes(uint32_t gridSize);
    // With semaphores this waits for the last frame's hand-off to complete (it has by the time a frame is read).
    const VxgiGlStats& lastStats() const;
    uint32_t capacity() const noexcept { return capacity_; }
    // Test hook: the record capacity of the next prepare() (an overflow test starts small).
    void setCapacity(uint32_t records) { wanted_ = records; }

    // This frame's imports of the two shared buffers (after prepare).
    graph::BufferHandle importRecords(graph::RenderGraph& graph) const;
    graph::BufferHandle importSums(graph::RenderGraph& graph) const;
    uint32_t recordsIndex() const noexcept { return recordsIndex_.value; }
    uint32_t sumsIndex() const noexcept { return sumsIndex_.value; }
    // The sums of the last frame (kVoxelSumWords floats per voxel, Vulkan-owned after the frame): tests read the
    // per-voxel fragment counts from it.
    const vk::Buffer& sumsBuffer() const;

    // "vxgi_gl_accumulate": reads `records` (written by the voxelization), writes `sums` (cleared before); returns
    // the sums' new version, which the merge reads. Records the frame's stats when it runs.
    graph::BufferHandle addPass(graph::RenderGraph& graph, graph::BufferHandle records, graph::BufferHandle sums);

private:
    void handOver(VkCommandBuffer cmd);  // submit, run GL, begin again (gl::HandOff)
    void accumulateOnGl();               // the GL dispatch over this frame's records
    void recordStats(uint32_t appended) const;  // stats_, and the capacity of the next frame when it overflowed
    void settleStats() const;            // semaphore mode: reads the header copy of the last hand-off
    void releaseBuffers();
    void releaseHalfSums();              // Fp16Vector: the GL images and counts (inside a current GL context)
    vk::Context& ctx_;
    VxgiGlProgram kind_;
    std::unique_ptr<gl::ComputeProgram> program_;
    std::unique_ptr<gl::ComputeProgram> resolve_;  // Fp16Vector: images + counts -> the shared sums
    uint32_t halfSums_[2] = {0, 0};      // Fp16Vector: GL RGBA16F 3D textures (radiance + coverage, facing)
    uint32_t counts_ = 0;                // Fp16Vector: GL buffer, a uint count per voxel
    std::unique_ptr<gl::SharedBuffer> records_, sums_;
    vk::StorageBufferIndex recordsIndex_, sumsIndex_;
    std::unique_ptr<gl::HandOff> handOff_;
    vk::Buffer countCopy_;              // semaphore mode: the record count after GL's work (host-readable)
    uint32_t gridSize_ = 0, capacity_ = 0;
    mutable uint32_t wanted_ = 0;
    mutable uint64_t pendingCount_ = 0;  // timeline value after which countCopy_ holds the last frame's count
    mutable VxgiGlStats stats_;
};

}  // namespace idk::passes
