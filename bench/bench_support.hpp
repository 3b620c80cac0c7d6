// bench_support.hpp: what the benchmarks share: one Vulkan device for the whole run (validation off, so the
// layer does not distort timings), a GPU array of 32-bit elements in the bindless table, a timestamp-query
// timer for the GPU work between upload and readback, the paths of the shared scenes, and a helper that
// writes the metadata label the report script (scripts/bench_report.py) turns into a table row.
#pragma once
#include <benchmark/benchmark.h>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "render/compute_primitives.hpp"
#include "vk/context.hpp"
#include "vk/shader_library.hpp"
#include "vk/timestamps.hpp"

namespace idk::bench {

// The process-wide device, created by main() before the benchmarks run and destroyed after them (before
// static destructors: Mesa's exit handlers tear lavapipe down first). Null when no Vulkan device could be
// created; GPU benchmarks then skip with deviceError().
vk::Context* context();
vk::ShaderLibrary* shaders();
const std::string& deviceError();
void createDevice();   // records the device, driver and capability ladders with benchmark::AddCustomContext
void destroyDevice();

// Skips the benchmark (with the reason) and returns false when there is no device.
bool requireDevice(benchmark::State& state);

// A GPU buffer of `elements` 32-bit values registered as a bindless storage buffer.
class GpuBuffer {
public:
    GpuBuffer(vk::Context& ctx, uint32_t elements, const std::string& name);
    ~GpuBuffer();
    GpuBuffer(const GpuBuffer&) = delete;
    GpuBuffer& operator=(const GpuBuffer&) = delete;

    render::GpuArray array(uint32_t offset = 0) const { return {index_, offset}; }
    void upload(const void* data, size_t elements);
    void download(void* out, size_t elements);
    template <class T>
    std::vector<T> download(size_t elements) {
        std::vector<T> out(elements);
        download(out.data(), elements);
        return out;
    }

private:
    vk::Context& ctx_;
    vk::Buffer buffer_;
    vk::StorageBufferIndex index_;
};

// Records `work` into a one-time command buffer between two timestamps, submits, waits, and returns the GPU
// time in seconds (the time between the two timestamps, nothing before or after). When `submitWallSeconds` is
// given, the wall time of recording + submit + wait is added to it (a sanity check on the timestamps).
double timeGpu(vk::Context& ctx, vk::TimestampQueries& queries, const std::function<void(VkCommandBuffer)>& work,
               double* submitWallSeconds = nullptr);

// Row metadata for the report: key=value pairs joined by ';' into the benchmark's label. Keys used by
// scripts/bench_report.py: group, input, settings, rung, peer (the peer benchmark's name), role (ours|peer),
// time (cpu|real|manual: which time the median is taken from).
struct RowInfo {
    std::string group;
    std::string input;
    std::string settings;
    std::string rung = "-";
    std::string peer;             // name of the peer benchmark (without /manual_time etc. suffix); empty: none
    std::string role = "ours";
    std::string time = "manual";
};
void setRow(benchmark::State& state, const RowInfo& row);

// The capability rungs code consulted (vk::Context::consultedLadders), for RowInfo::rung: "id=rung (mechanism)"
// joined by ", ", or "- (no capability ladder consulted)". Clear the context's list before the measured work.
std::string rungsThatRan(const std::vector<vk::Ladder>& consulted);

// <repo>/../shared/scenes/<name>/glTF-Binary/<name>.glb
std::filesystem::path sharedScene(const std::string& name);

// Fixed-seed inputs, so every run (and the peer) sees the same data.
std::vector<uint32_t> randomUints(size_t count, uint32_t bound, uint32_t seed);   // bound 0: full range
std::vector<float> randomFloats(size_t count, uint32_t seed);                     // [0.5, 1.5), 2^-24 grid

}  // namespace idk::bench
