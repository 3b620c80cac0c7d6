// compute_primitives.cpp: records the dispatches of the workgroup sum, the reduce-then-scan exclusive scan and the
// LSD radix sort (histogram -> scan of histograms -> stable scatter, per 8-bit digit), with the compute->compute
// barriers between dependent dispatches. These run outside the render graph, hence their own barriers.
#include "render/compute_primitives.hpp"

#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>
#include <vector>

#include "shared/bindings.h"
#include "vk/transfer.hpp"
#include "vk/context.hpp"
#include "vk/shader_library.hpp"

// SYNC: this runs outside the render graph, so every dispatch that reads an earlier dispatch's storage writes
// is preceded by vk::computeToComputeBarrier (engine/vk/transfer.hpp).
namespace idk::render {
namespace {

using vk::ShaderId;

static_assert(gpu::kRadixDigits == gpu::kComputeGroupSize, "radix_histogram gives each invocation one digit counter");
static_assert(gpu::kRadixDigits == (1u << gpu::kRadixBits));
static_assert(sizeof(gpu::SumPush) <= gpu::kPushConstantBytes && sizeof(gpu::RadixPush) <= gpu::kPushConstantBytes);

constexpr std::array<uint32_t, 3> kGroup = {gpu::kComputeGroupSize, 1, 1};
constexpr uint32_t kMaxCount = 1u << 31;


void checkCount(uint32_t count, const char* what) {
    if (count > kMaxCount) throw std::invalid_argument(std::string(what) + ": more than 2^31 elements");
}

// Every kernel addresses its arrays through the global bindless set; binding it once per record* call is enough
// because all pipelines share the one global pipeline layout.
void bindGlobalSet(VkCommandBuffer cmd, const ComputeKernels& k) { k.ctx.bindless().bind(cmd); }

void dispatch(VkCommandBuffer cmd, const ComputeKernels& k, const vk::Pipeline& pipeline, const auto& push,
              uint32_t groups) {
    vk::bindPipeline(cmd, pipeline);
    vk::pushConstants(cmd, k.ctx, push);
    vkCmdDispatch(cmd, groups, 1, 1);
}

const vk::Pipeline& sumPipeline(const ComputeKernels& k, SumElement element, uint32_t items) {
    return k.shaders.compute({ShaderId::compute_workgroup_sum_comp,
                              {{gpu::kSpecMinSubgroupSize, resolvedSlotSubgroupSize(k)},
                               {gpu::kSpecSumElement, static_cast<uint32_t>(element)},
                               {gpu::kSpecSumItemsPerInvocation, items}},
                              sizeof(gpu::SumPush),
                              kGroup});
}

void sumPass(VkCommandBuffer cmd, const ComputeKernels& k, SumElement element, GpuArray input, uint32_t count,
             GpuArray output, uint32_t items, uint32_t groups) {
    gpu::SumPush push{input.buffer.value, input.offset, output.buffer.value, output.offset, count};
    dispatch(cmd, k, sumPipeline(k, element, items), push, groups);
}

void scanAddPass(VkCommandBuffer cmd, const ComputeKernels& k, GpuArray input, GpuArray output, uint32_t count,
                 std::optional<GpuArray> blockOffsets) {
    const vk::Pipeline& pipeline = k.shaders.compute({ShaderId::compute_scan_add_comp,
                                                      {{gpu::kSpecMinSubgroupSize, resolvedSlotSubgroupSize(k)}},
                                                      sizeof(gpu::ScanPush),
                                                      kGroup});
    gpu::ScanPush push{input.buffer.value, input.offset, output.buffer.value, output.offset,
                       blockOffsets ? blockOffsets->buffer.value : 0u, blockOffsets ? blockOffsets->offset : 0u,
                       count, blockOffsets ? gpu::kScanAddBlockOffsets : 0u};
    dispatch(cmd, k, pipeline, push, vk::groupCount(count, kScanTile));
}

}  // namespace

uint32_t resolvedSlotSubgroupSize(const ComputeKernels& kernels) {
    uint32_t deviceMin = std::max(kernels.ctx.capabilities().minSubgroupSize, 1u);
    if (kernels.slotSubgroupSize == 0) return deviceMin;
    if (kernels.slotSubgroupSize > deviceMin) {
        throw std::invalid_argument("compute primitives: slots sized for subgroups of " +
                                    std::to_string(kernels.slotSubgroupSize) + " but the device may run subgroups of " +
                                    std::to_string(deviceMin) + " (shared memory would overflow)");
    }
    return kernels.slotSubgroupSize;
}

// ---- sums -------------------------------------------------------------------------------------------------------

uint32_t workgroupSumCount(uint32_t count, uint32_t itemsPerInvocation) {
    return vk::groupCount(count, gpu::kComputeGroupSize * itemsPerInvocation);
}

void recordWorkgroupSum(VkCommandBuffer cmd, const ComputeKernels& kernels, SumElement element, GpuArray input,
                        uint32_t count, GpuArray output, uint32_t itemsPerInvocation) {
    checkCount(count, "recordWorkgroupSum");
    if (itemsPerInvocation == 0) throw std::invalid_argument("recordWorkgroupSum: itemsPerInvocation is 0");
    if (count == 0) return;
    bindGlobalSet(cmd, kernels);
    sumPass(cmd, kernels, element, input, count, output, itemsPerInvocation,
            workgroupSumCount(count, itemsPerInvocation));
}

uint32_t reduceScratchElements(uint32_t count) {
    // Level i writes its partial sums behind those of level i - 1; the last level writes `result` instead.
    uint32_t total = 0;
    for (uint32_t n = workgroupSumCount(count); n > 1; n = workgroupSumCount(n)) total += n;
    return total;
}

void recordReduce(VkCommandBuffer cmd, const ComputeKernels& kernels, SumElement element, GpuArray input,
                  uint32_t count, GpuArray result, GpuArray scratch) {
    checkCount(count, "recordReduce");
    bindGlobalSet(cmd, kernels);
    GpuArray level = input;
    uint32_t n = count;
    uint32_t used = 0;
    while (workgroupSumCount(n) > 1) {
        uint32_t groups = workgroupSumCount(n);
        GpuArray partials = scratch.at(used);
        sumPass(cmd, kernels, element, level, n, partials, kSumItemsPerInvocation, groups);
        vk::computeToComputeBarrier(cmd);
        used += groups;
        level = partials;
        n = groups;
    }
    // One workgroup left (also for count == 0, which writes 0).
    sumPass(cmd, kernels, element, level, n, result, kSumItemsPerInvocation, 1);
}

// ---- exclusive scan ---------------------------------------------------------------------------------------------

uint32_t exclusiveScanScratchElements(uint32_t count) {
    uint32_t total = 0;
    for (uint32_t n = count; n > kScanTile; n = vk::groupCount(n, kScanTile)) total += vk::groupCount(n, kScanTile);
    return total;
}

namespace {

// Reduce-then-scan: tile sums (workgroup_sum over the same 2048-element tiles), their exclusive scan (recursively,
// in place), then each tile is scanned and offset by its tile's scanned sum. Every pass depends on the previous one.
void scanLevel(VkCommandBuffer cmd, const ComputeKernels& k, GpuArray input, GpuArray output, uint32_t count,
               GpuArray scratch) {
    if (count <= kScanTile) {
        scanAddPass(cmd, k, input, output, count, std::nullopt);
        return;
    }
    uint32_t blocks = vk::groupCount(count, kScanTile);
    GpuArray blockSums = scratch;
    sumPass(cmd, k, SumElement::Uint, input, count, blockSums, gpu::kScanItemsPerInvocation, blocks);
    vk::computeToComputeBarrier(cmd);
    scanLevel(cmd, k, blockSums, blockSums, blocks, scratch.at(blocks));
    vk::computeToComputeBarrier(cmd);
    scanAddPass(cmd, k, input, output, count, blockSums);
}

}  // namespace

void recordExclusiveScan(VkCommandBuffer cmd, const ComputeKernels& kernels, GpuArray input, GpuArray output,
                         uint32_t count, GpuArray scratch) {
    checkCount(count, "recordExclusiveScan");
    if (count == 0) return;
    bindGlobalSet(cmd, kernels);
    scanLevel(cmd, kernels, input, output, count, scratch);
}

// ---- radix sort -------------------------------------------------------------------------------------------------

namespace {

struct SortLayout {
    uint32_t blocks = 0;
    uint32_t histogramCount = 0;
    uint32_t keysTemp = 0;  // element offsets into scratch
    uint32_t valuesTemp = 0;
    uint32_t histograms = 0;
    uint32_t scanScratch = 0;
    uint32_t total = 0;
};

SortLayout sortLayout(uint32_t count, bool withValues) {
    SortLayout l;
    l.blocks = vk::groupCount(count, kSortTile);
    l.histogramCount = l.blocks * gpu::kRadixDigits;  // at most 2^31 / 8
    uint64_t histograms = uint64_t(count) * (withValues ? 2 : 1);
    uint64_t scanScratch = histograms + l.histogramCount;
    uint64_t total = scanScratch + exclusiveScanScratchElements(l.histogramCount);
    if (total > UINT32_MAX) throw std::invalid_argument("radix sort: scratch would exceed 2^32 elements");
    l.keysTemp = 0;
    l.valuesTemp = count;
    l.histograms = uint32_t(histograms);
    l.scanScratch = uint32_t(scanScratch);
    l.total = uint32_t(total);
    return l;
}

}  // namespace

uint32_t radixSortScratchElements(uint32_t count, bool withValues) { return sortLayout(count, withValues).total; }

void recordRadixSort(VkCommandBuffer cmd, const ComputeKernels& kernels, GpuArray keys,
                     std::optional<GpuArray> values, uint32_t count, GpuArray scratch, uint32_t keyBits) {
    checkCount(count, "recordRadixSort");
    if (keyBits == 0 || keyBits > 32) throw std::invalid_argument("recordRadixSort: keyBits must be in 1..32");
    if (count <= 1) return;
    const bool withValues = values.has_value();
    SortLayout layout = sortLayout(count, withValues);
    uint32_t passes = (keyBits + gpu::kRadixBits - 1) / gpu::kRadixBits;
    passes += passes & 1u;  // even: the last pass writes back into keys/values

    uint32_t slots = resolvedSlotSubgroupSize(kernels);
    const vk::Pipeline& histogram = kernels.shaders.compute(
        {ShaderId::compute_radix_histogram_comp, {}, sizeof(gpu::RadixPush), kGroup});
    const vk::Pipeline& scatter = kernels.shaders.compute(
        {ShaderId::compute_radix_scatter_comp,
         {{gpu::kSpecMinSubgroupSize, slots}, {gpu::kSpecSortWithValues, withValues ? 1u : 0u}},
         sizeof(gpu::RadixPush),
         kGroup});

    bindGlobalSet(cmd, kernels);
    GpuArray keysTemp = scratch.at(layout.keysTemp);
    GpuArray valuesTemp = withValues ? scratch.at(layout.valuesTemp) : GpuArray{};
    GpuArray histograms = scratch.at(layout.histograms);
    GpuArray valuesMain = withValues ? *values : GpuArray{};
    for (uint32_t pass = 0; pass < passes; ++pass) {
        bool even = (pass & 1u) == 0;
        GpuArray keysIn = even ? keys : keysTemp, keysOut = even ? keysTemp : keys;
        GpuArray valuesIn = even ? valuesMain : valuesTemp, valuesOut = even ? valuesTemp : valuesMain;
        gpu::RadixPush push{keysIn.buffer.value,    keysIn.offset,    keysOut.buffer.value,    keysOut.offset,
                            valuesIn.buffer.value,  valuesIn.offset,  valuesOut.buffer.value,  valuesOut.offset,
                            histograms.buffer.value, histograms.offset, count, pass * gpu::kRadixBits, layout.blocks};
        if (pass > 0) vk::computeToComputeBarrier(cmd);  // the previous scatter wrote keysIn and read the histograms
        dispatch(cmd, kernels, histogram, push, layout.blocks);
        vk::computeToComputeBarrier(cmd);
        scanLevel(cmd, kernels, histograms, histograms, layout.histogramCount, scratch.at(layout.scanScratch));
        vk::computeToComputeBarrier(cmd);
        dispatch(cmd, kernels, scatter, push, layout.blocks);
    }
}

}  // namespace idk::render
