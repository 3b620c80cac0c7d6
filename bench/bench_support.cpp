// bench_support.cpp: the shared device and the helpers declared in bench_support.hpp.
#include "bench_support.hpp"

#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdlib>
#include <random>
#include <span>
#include <thread>

#include "vk/transfer.hpp"

namespace idk::bench {
namespace {

std::unique_ptr<vk::Context> gContext;
std::unique_ptr<vk::ShaderLibrary> gShaders;
std::string gDeviceError;

std::string versionString(uint32_t v) {
    return std::to_string(VK_API_VERSION_MAJOR(v)) + "." + std::to_string(VK_API_VERSION_MINOR(v)) + "." +
           std::to_string(VK_API_VERSION_PATCH(v));
}

}  // namespace

vk::Context* context() { return gContext.get(); }
vk::ShaderLibrary* shaders() { return gShaders.get(); }
const std::string& deviceError() { return gDeviceError; }

void createDevice() {
    benchmark::AddCustomContext("idk_build_type", IDK_BENCH_BUILD_TYPE);
    benchmark::AddCustomContext("hardware_threads", std::to_string(std::thread::hardware_concurrency()));
    try {
        vk::ContextDesc desc;
        desc.validation = false;   // the layer's checks would dominate small dispatches
        desc.syncValidation = false;
        if (const char* staging = std::getenv("IDK_FORCE_STAGING")) desc.forceStaging = std::string(staging) == "1";
        gContext = std::make_unique<vk::Context>(desc);
        gShaders = std::make_unique<vk::ShaderLibrary>(*gContext);
    } catch (const std::exception& e) {
        gShaders.reset();
        gContext.reset();
        gDeviceError = std::string("no Vulkan device: ") + e.what();
        benchmark::AddCustomContext("device", "none (" + gDeviceError + ")");
        return;
    }
    const vk::DeviceInfo& info = gContext->info();
    const vk::DeviceCapabilities& caps = gContext->capabilities();
    benchmark::AddCustomContext("device", info.name);
    benchmark::AddCustomContext("driver", info.driverName + " " + info.driverInfo);
    benchmark::AddCustomContext("vulkan_api", versionString(info.apiVersion));
    benchmark::AddCustomContext("subgroup_size", std::to_string(caps.minSubgroupSize) + ".." +
                                                     std::to_string(caps.maxSubgroupSize));
    benchmark::AddCustomContext("uploads", gContext->desc().forceStaging || !info.uma ? "staging" : "mapped");
    benchmark::AddCustomContext("validation", "off");
    std::string ladders;
    nlohmann::json table = nlohmann::json::array();
    for (const vk::Ladder& l : gContext->ladders()) {
        if (!ladders.empty()) ladders += "; ";
        ladders += l.feature + ": " + vk::rungName(l.chosen) + " (" + l.chosenMechanism + ")";
        table.push_back({{"id", l.id}, {"feature", l.feature}, {"chosen", vk::rungName(l.chosen)},
                         {"mechanism", l.chosenMechanism}, {"reason", l.reason}});
    }
    benchmark::AddCustomContext("ladders", ladders);
    benchmark::AddCustomContext("ladders_json", table.dump());  // with the reasons `idk info` prints
}

void destroyDevice() {
    if (gContext) gContext->waitIdle();
    gShaders.reset();
    gContext.reset();
}

bool requireDevice(benchmark::State& state) {
    if (gContext) return true;
    state.SkipWithError(gDeviceError.c_str());
    for (auto _ : state) {
    }
    return false;
}

GpuBuffer::GpuBuffer(vk::Context& ctx, uint32_t elements, const std::string& name) : ctx_(ctx) {
    buffer_ = ctx.createBuffer({VkDeviceSize(std::max(elements, 1u)) * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                vk::MemoryUsage::GpuOnly, name, "bench"});
    index_ = ctx.bindless().addBuffer(buffer_.buffer);
}

GpuBuffer::~GpuBuffer() {
    ctx_.bindless().release(index_);
    ctx_.destroyDeferred(buffer_);
}

void GpuBuffer::upload(const void* data, size_t elements) { vk::uploadBuffer(ctx_, buffer_, data, elements * 4); }
void GpuBuffer::download(void* out, size_t elements) { vk::downloadBuffer(ctx_, buffer_, out, elements * 4); }

double timeGpu(vk::Context& ctx, vk::TimestampQueries& queries, const std::function<void(VkCommandBuffer)>& work,
               double* submitWallSeconds) {
    auto start = std::chrono::steady_clock::now();
    ctx.runImmediate([&](VkCommandBuffer cmd) {
        queries.reset(cmd);
        uint32_t scope = queries.begin(cmd, "work");
        work(cmd);
        queries.end(cmd, scope);
    });
    double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (submitWallSeconds) *submitWallSeconds += wall;
    if (!queries.supported()) return wall;   // no timestamps: fall back to the submission's wall time
    return queries.read().at(0).milliseconds * 1e-3;
}

void setRow(benchmark::State& state, const RowInfo& row) {
    std::string label = "group=" + row.group + ";input=" + row.input + ";settings=" + row.settings +
                        ";rung=" + row.rung + ";role=" + row.role + ";time=" + row.time;
    if (!row.peer.empty()) label += ";peer=" + row.peer;
    state.SetLabel(label);
}

std::string rungsThatRan(const std::vector<vk::Ladder>& consulted) {
    std::string text;
    for (const vk::Ladder& l : consulted)
        text += (text.empty() ? "" : ", ") + l.id + "=" + vk::rungName(l.chosen) + " (" + l.chosenMechanism + ")";
    return text.empty() ? "- (no capability ladder consulted)" : text;
}

std::filesystem::path sharedScene(const std::string& name) {
    return std::filesystem::path(IDK_BENCH_SOURCE_DIR) / ".." / "shared" / "scenes" / name / "glTF-Binary" /
           (name + ".glb");
}

std::vector<uint32_t> randomUints(size_t count, uint32_t bound, uint32_t seed) {
    std::mt19937 rng(seed);
    std::vector<uint32_t> v(count);
    for (uint32_t& x : v) x = bound ? uint32_t(rng() % bound) : uint32_t(rng());
    return v;
}

std::vector<float> randomFloats(size_t count, uint32_t seed) {
    std::vector<uint32_t> bits = randomUints(count, 1u << 24, seed);
    std::vector<float> v(count);
    for (size_t i = 0; i < count; ++i) v[i] = 0.5f + float(bits[i]) * 0x1p-24f;
    return v;
}

}  // namespace idk::bench
