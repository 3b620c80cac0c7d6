// compute_bench.cpp: the GPU compute primitives (engine/render/compute_primitives.hpp) on 1M elements against
// the C++ standard library on the CPU, measured in the same run: stable radix sort of uint32 keys vs std::sort
// and std::stable_sort, exclusive scan vs std::exclusive_scan, float reduction vs std::accumulate in double.
// GPU times come from timestamp queries around the dispatches only (no upload, no readback); CPU times from
// steady_clock around the algorithm only (no input copy). Both are reported as manual time. Errors are
// counters: "mismatches" (elements that differ from the CPU result) and "rel_error" (float sum vs double);
// "submit_wall_ms" is the wall time of record + submit + wait around the same work, for comparison.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>

#include "bench_support.hpp"

namespace idk::bench {
namespace {

constexpr int64_t kMillion = int64_t(1) << 20;
// Fixed iteration counts per repetition keep the run short on lavapipe (a 1M sort takes ~0.1 s there).
constexpr int64_t kSortIterations = 5;
constexpr int64_t kGpuIterations = 20;

template <class Fn>
double timeCpu(Fn&& fn) {
    auto start = std::chrono::steady_clock::now();
    fn();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::string subgroupRung(const render::ComputeKernels& kernels) {
    const vk::DeviceCapabilities& caps = kernels.ctx.capabilities();
    return std::string(caps.subgroupArithmetic ? "subgroupAdd" : "no subgroup arithmetic") + ", slots for " +
           std::to_string(render::resolvedSlotSubgroupSize(kernels)) + "-wide subgroups";
}

std::string elements(int64_t n) { return n == kMillion ? std::string("1M") : std::to_string(n); }

template <class T>
double countMismatches(const std::vector<T>& got, const std::vector<T>& expected) {
    size_t bad = 0;
    for (size_t i = 0; i < expected.size(); ++i) bad += got[i] != expected[i];
    return double(bad);
}

// ---- Radix sort ----

void BM_GpuRadixSort(benchmark::State& state) {
    if (!requireDevice(state)) return;
    vk::Context& ctx = *context();
    auto n = uint32_t(state.range(0));
    std::vector<uint32_t> keys = randomUints(n, 0, 1);
    std::vector<uint32_t> expected = keys;
    std::sort(expected.begin(), expected.end());

    render::ComputeKernels kernels{ctx, *shaders()};
    GpuBuffer keyBuffer(ctx, n, "bench sort keys");
    GpuBuffer scratch(ctx, render::radixSortScratchElements(n, false), "bench sort scratch");
    vk::TimestampQueries queries(ctx, 1);
    auto record = [&](VkCommandBuffer cmd) {
        render::recordRadixSort(cmd, kernels, keyBuffer.array(), std::nullopt, n, scratch.array());
    };
    keyBuffer.upload(keys.data(), n);
    timeGpu(ctx, queries, record);   // warm-up: pipeline creation
    double wall = 0.0;
    for (auto _ : state) {
        keyBuffer.upload(keys.data(), n);
        state.SetIterationTime(timeGpu(ctx, queries, record, &wall));
    }
    state.counters["mismatches"] = countMismatches(keyBuffer.download<uint32_t>(n), expected);
    state.counters["submit_wall_ms"] = wall * 1e3 / double(state.iterations());
    state.SetItemsProcessed(state.iterations() * n);
    setRow(state, {"compute", elements(n) + " uint32 keys, uniform random",
                   "keys only, 32-bit keys: 4 passes of 8 bits", subgroupRung(kernels),
                   "BM_CpuStdSort/" + std::to_string(n) + ",BM_CpuStdStableSort/" + std::to_string(n)});
}
BENCHMARK(BM_GpuRadixSort)->Arg(kMillion)->UseManualTime()->Iterations(kSortIterations)->Unit(benchmark::kMillisecond);

template <bool Stable>
void cpuSort(benchmark::State& state) {
    auto n = size_t(state.range(0));
    const std::vector<uint32_t> keys = randomUints(n, 0, 1);
    std::vector<uint32_t> work;
    for (auto _ : state) {
        work = keys;
        state.SetIterationTime(timeCpu([&] {
            if constexpr (Stable) {
                std::stable_sort(work.begin(), work.end());
            } else {
                std::sort(work.begin(), work.end());
            }
        }));
        benchmark::DoNotOptimize(work.data());
    }
    state.SetItemsProcessed(state.iterations() * int64_t(n));
    setRow(state, {"compute", elements(int64_t(n)) + " uint32 keys, uniform random",
                   Stable ? "std::stable_sort, 1 thread" : "std::sort, 1 thread", "-", "", "peer"});
}
void BM_CpuStdSort(benchmark::State& state) { cpuSort<false>(state); }
void BM_CpuStdStableSort(benchmark::State& state) { cpuSort<true>(state); }
BENCHMARK(BM_CpuStdSort)->Arg(kMillion)->UseManualTime()->MinTime(0.3)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CpuStdStableSort)->Arg(kMillion)->UseManualTime()->MinTime(0.3)->Unit(benchmark::kMillisecond);

// ---- Exclusive scan ----

void BM_GpuExclusiveScan(benchmark::State& state) {
    if (!requireDevice(state)) return;
    vk::Context& ctx = *context();
    auto n = uint32_t(state.range(0));
    std::vector<uint32_t> input = randomUints(n, 0, 2);   // full range: the sums wrap modulo 2^32 on both sides
    std::vector<uint32_t> expected(n);
    std::exclusive_scan(input.begin(), input.end(), expected.begin(), 0u);

    render::ComputeKernels kernels{ctx, *shaders()};
    GpuBuffer in(ctx, n, "bench scan input");
    GpuBuffer out(ctx, n, "bench scan output");
    GpuBuffer scratch(ctx, render::exclusiveScanScratchElements(n), "bench scan scratch");
    vk::TimestampQueries queries(ctx, 1);
    auto record = [&](VkCommandBuffer cmd) {
        render::recordExclusiveScan(cmd, kernels, in.array(), out.array(), n, scratch.array());
    };
    in.upload(input.data(), n);
    timeGpu(ctx, queries, record);   // warm-up: pipeline creation
    double wall = 0.0;
    for (auto _ : state) state.SetIterationTime(timeGpu(ctx, queries, record, &wall));
    state.counters["mismatches"] = countMismatches(out.download<uint32_t>(n), expected);
    state.counters["submit_wall_ms"] = wall * 1e3 / double(state.iterations());
    state.SetItemsProcessed(state.iterations() * n);
    setRow(state, {"compute", elements(n) + " uint32, uniform random (wraps mod 2^32)",
                   "reduce-then-scan, out of place", subgroupRung(kernels), "BM_CpuExclusiveScan/" + std::to_string(n)});
}
BENCHMARK(BM_GpuExclusiveScan)->Arg(kMillion)->UseManualTime()->Iterations(kGpuIterations)->Unit(benchmark::kMillisecond);

void BM_CpuExclusiveScan(benchmark::State& state) {
    auto n = size_t(state.range(0));
    const std::vector<uint32_t> input = randomUints(n, 0, 2);
    std::vector<uint32_t> output(n);
    for (auto _ : state) {
        state.SetIterationTime(timeCpu([&] { std::exclusive_scan(input.begin(), input.end(), output.begin(), 0u); }));
        benchmark::DoNotOptimize(output.data());
    }
    state.SetItemsProcessed(state.iterations() * int64_t(n));
    setRow(state, {"compute", elements(int64_t(n)) + " uint32, uniform random (wraps mod 2^32)",
                   "std::exclusive_scan, 1 thread", "-", "", "peer"});
}
BENCHMARK(BM_CpuExclusiveScan)->Arg(kMillion)->UseManualTime()->MinTime(0.2)->Unit(benchmark::kMillisecond);

// ---- Float reduction ----

void BM_GpuReduceFloat(benchmark::State& state) {
    if (!requireDevice(state)) return;
    vk::Context& ctx = *context();
    auto n = uint32_t(state.range(0));
    std::vector<float> input = randomFloats(n, 3);
    double exact = std::accumulate(input.begin(), input.end(), 0.0);

    render::ComputeKernels kernels{ctx, *shaders()};
    GpuBuffer in(ctx, n, "bench reduce input");
    GpuBuffer result(ctx, 1, "bench reduce result");
    GpuBuffer scratch(ctx, render::reduceScratchElements(n), "bench reduce scratch");
    vk::TimestampQueries queries(ctx, 1);
    auto record = [&](VkCommandBuffer cmd) {
        render::recordReduce(cmd, kernels, render::SumElement::Float, in.array(), n, result.array(), scratch.array());
    };
    in.upload(input.data(), n);
    timeGpu(ctx, queries, record);   // warm-up: pipeline creation
    double wall = 0.0;
    for (auto _ : state) state.SetIterationTime(timeGpu(ctx, queries, record, &wall));
    float got = result.download<float>(1)[0];
    state.counters["rel_error"] = std::abs(double(got) - exact) / exact;
    state.counters["submit_wall_ms"] = wall * 1e3 / double(state.iterations());
    state.SetItemsProcessed(state.iterations() * n);
    setRow(state, {"compute", elements(n) + " float in [0.5, 1.5)",
                   "workgroup sums (" + std::to_string(render::kSumItemsPerInvocation) +
                       " per invocation), repeated; float accumulation",
                   subgroupRung(kernels), "BM_CpuAccumulateDouble/" + std::to_string(n)});
}
BENCHMARK(BM_GpuReduceFloat)->Arg(kMillion)->UseManualTime()->Iterations(kGpuIterations)->Unit(benchmark::kMillisecond);

void BM_CpuAccumulateDouble(benchmark::State& state) {
    auto n = size_t(state.range(0));
    const std::vector<float> input = randomFloats(n, 3);
    double sum = 0.0;
    for (auto _ : state) {
        state.SetIterationTime(timeCpu([&] { sum = std::accumulate(input.begin(), input.end(), 0.0); }));
        benchmark::DoNotOptimize(sum);
    }
    state.counters["rel_error"] = 0.0;   // it is the reference
    state.SetItemsProcessed(state.iterations() * int64_t(n));
    setRow(state, {"compute", elements(int64_t(n)) + " float in [0.5, 1.5)",
                   "std::accumulate into double, 1 thread (the reference sum)", "-", "", "peer"});
}
BENCHMARK(BM_CpuAccumulateDouble)->Arg(kMillion)->UseManualTime()->MinTime(0.2)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace idk::bench
