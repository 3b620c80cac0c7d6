// compute_primitives.hpp: reusable GPU compute primitives recorded into a command buffer: workgroup-wide sums and
// full reductions (uint modulo 2^32, float), an exclusive prefix scan of uint (reduce-then-scan), and a stable LSD
// radix sort of 32-bit keys with optional 32-bit values (the path tracer's ray sorting). Kernels live in
// shaders_glsl/compute/, their push blocks in shaders_glsl/shared/compute_push.h.
#pragma once
#include <volk.h>

#include <cstdint>
#include <optional>

#include "shared/compute_push.h"
#include "vk/bindless.hpp"

namespace idk::vk {
class Context;
class ShaderLibrary;
}  // namespace idk::vk

namespace idk::render {

// A run of 32-bit elements in a bindless storage buffer, starting `offset` elements into it.
struct GpuArray {
    vk::StorageBufferIndex buffer;
    uint32_t offset = 0;
    GpuArray at(uint32_t elements) const { return {buffer, offset + elements}; }
};

enum class SumElement : uint32_t { Uint = gpu::kSumElementUint, Float = gpu::kSumElementFloat };

// What the recording functions need from the device. slotSubgroupSize is the subgroup size the kernels' shared
// per-subgroup slots are sized for (256 / size slots); 0 takes the device's minSubgroupSize, the only safe
// choice when the driver may vary the subgroup size. A value above minSubgroupSize is rejected.
struct ComputeKernels {
    vk::Context& ctx;
    vk::ShaderLibrary& shaders;
    uint32_t slotSubgroupSize = 0;
};

inline constexpr uint32_t kSumItemsPerInvocation = 4;
inline constexpr uint32_t kScanTile = gpu::kComputeGroupSize * gpu::kScanItemsPerInvocation;
inline constexpr uint32_t kSortTile = gpu::kComputeGroupSize * gpu::kSortItemsPerInvocation;

// Contract shared by every record* function: the caller has made the inputs visible to compute-shader reads
// (the render graph, or a preceding barrier/submission) and orders later reads of the outputs after
// VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT / SHADER_STORAGE_WRITE. Between their own dispatches the functions place
// compute->compute memory barriers. They bind the pipeline and the bindless set and push their constants.
// Ranges of one call must not overlap unless stated. Counts are limited to 2^31 elements.

// Number of values recordWorkgroupSum writes: one per tile of 256 * itemsPerInvocation elements.
uint32_t workgroupSumCount(uint32_t count, uint32_t itemsPerInvocation = kSumItemsPerInvocation);
// output[g] = sum of input[g * tile, (g + 1) * tile) clamped to count; nothing is recorded for count == 0.
void recordWorkgroupSum(VkCommandBuffer cmd, const ComputeKernels& kernels, SumElement element, GpuArray input,
                        uint32_t count, GpuArray output, uint32_t itemsPerInvocation = kSumItemsPerInvocation);

// Elements of scratch recordReduce needs (0 when one workgroup covers the input).
uint32_t reduceScratchElements(uint32_t count);
// result[0] = sum of input[0, count) (0 for count == 0), by repeated workgroup sums.
void recordReduce(VkCommandBuffer cmd, const ComputeKernels& kernels, SumElement element, GpuArray input,
                  uint32_t count, GpuArray result, GpuArray scratch);

// Elements of scratch recordExclusiveScan needs: the block sums of every level (0 when count <= kScanTile).
uint32_t exclusiveScanScratchElements(uint32_t count);
// output[i] = input[0] + ... + input[i - 1] (uint, modulo 2^32). input and output may be the same range.
void recordExclusiveScan(VkCommandBuffer cmd, const ComputeKernels& kernels, GpuArray input, GpuArray output,
                         uint32_t count, GpuArray scratch);

// Elements of scratch recordRadixSort needs: ping-pong keys (and values), the digit histograms and their scan.
uint32_t radixSortScratchElements(uint32_t count, bool withValues);
// Sorts keys[0, count) ascending in place, stably, moving values[i] with keys[i] when given. Keys must be below
// 2^keyBits (1..32): the sort runs ceil(keyBits / 8) passes of 8 bits, rounded up to an even number so that the
// result ends in keys/values and not in scratch (an extra pass over zero bits is the identity).
void recordRadixSort(VkCommandBuffer cmd, const ComputeKernels& kernels, GpuArray keys,
                     std::optional<GpuArray> values, uint32_t count, GpuArray scratch, uint32_t keyBits = 32);

// The slot sizing the kernels are specialised with (slotSubgroupSize resolved against the device).
uint32_t resolvedSlotSubgroupSize(const ComputeKernels& kernels);

}  // namespace idk::render
