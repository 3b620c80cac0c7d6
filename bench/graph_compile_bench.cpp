// graph_compile_bench.cpp: CPU cost of declaring and compiling (ordering, culling, barrier and layout planning,
// transient aliasing) a synthetic 30-pass deferred frame with the render graph (engine/graph/render_graph.hpp),
// over a GPU-free backend that only answers memory-requirement queries. The graph is rebuilt every frame, so
// declare + compile is what a frame pays. No Vulkan device is involved.
#include <string>

#include "bench_support.hpp"
#include "graph/render_graph.hpp"

namespace idk::bench {
namespace {

using graph::Access;
using graph::BufferHandle;
using graph::PassBuilder;
using graph::TextureHandle;

// Answers compile()'s memory queries like a desktop GPU would roughly (4 bytes a texel, 256-byte alignment);
// execute() is never called, so the object-creating functions hand back null objects.
class QueryOnlyBackend : public graph::GraphBackend {
public:
    graph::MemoryRequirements textureRequirements(const graph::TextureInfo& t) override {
        VkDeviceSize size = VkDeviceSize{t.extent.width} * t.extent.height * t.extent.depth * t.layers * 4;
        if (t.mips > 1) size = size * 4 / 3;
        return {(size + 255) / 256 * 256, 256, 0b1};
    }
    graph::MemoryRequirements bufferRequirements(const graph::BufferInfo& b) override {
        return {(b.size + 15) / 16 * 16, 16, b.hostVisible ? 0b10u : 0b1u};
    }
    graph::HeapHandle allocateHeap(const graph::HeapDesc&) override { return {}; }
    graph::PhysicalTexture createTexture(const graph::TextureInfo&, std::string_view,
                                         const graph::MemoryPlacement*) override {
        return {};
    }
    graph::PhysicalBuffer createBuffer(const graph::BufferInfo&, std::string_view,
                                       const graph::MemoryPlacement*) override {
        return {};
    }
    void destroyTexture(const graph::PhysicalTexture&) override {}
    void destroyBuffer(const graph::PhysicalBuffer&) override {}
    void releaseHeap(graph::HeapHandle) override {}
};

constexpr VkPipelineStageFlags2 kCompute = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
constexpr VkPipelineStageFlags2 kFragment = VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT;

graph::TextureDesc relative(VkFormat format, float scale = 1.0f) {
    graph::TextureDesc d;
    d.format = format;
    d.scaleX = d.scaleY = scale;
    return d;
}
graph::TextureDesc absolute(VkFormat format, uint32_t w, uint32_t h, uint32_t depth = 1) {
    graph::TextureDesc d;
    d.format = format;
    d.sizeMode = graph::SizeMode::Absolute;
    d.extent = {w, h, depth};
    return d;
}

constexpr VkFormat kHdr = VK_FORMAT_R16G16B16A16_SFLOAT;
constexpr VkFormat kDepth = VK_FORMAT_D32_SFLOAT;
const std::function<void(graph::PassContext&)> kNoExec = {};

// 30 passes: upload, culling, 4 shadow cascades, a point-shadow cube, depth prepass, G-buffer, Hi-Z, SSAO +
// blur, voxelization + voxel mips, lighting, SSR, volumetric fog, composite, TAA (history), luminance histogram,
// exposure (persistent buffer), 4 bloom downsamples, 3 upsamples, tonemap, and a debug overlay nobody reads
// (culled).
void declareFrame(graph::RenderGraph& g) {
    BufferHandle instances, drawArgs, histogram, exposure;
    TextureHandle cascades[4], cube, depth, albedo, normal, material, velocity, hiz, ao, aoBlur, voxels, hdr, ssr,
        fog, composite, taa, ldr;
    g.addPass("upload instances", [&](PassBuilder& b) {
        instances = b.write(b.create("instances", graph::BufferDesc{1 << 20}), Access::TransferDst);
    }, kNoExec);
    g.addPass("frustum cull", [&](PassBuilder& b) {
        b.read(instances, Access::StorageRead, kCompute);
        drawArgs = b.write(b.create("draw args", graph::BufferDesc{1 << 18}), Access::StorageWrite, kCompute);
    }, kNoExec);
    for (int i = 0; i < 4; ++i) {
        g.addPass("shadow cascade " + std::to_string(i), [&](PassBuilder& b) {
            b.read(drawArgs, Access::IndirectRead);
            cascades[i] = b.write(b.create("cascade " + std::to_string(i), absolute(kDepth, 2048, 2048)),
                                  Access::DepthWrite);
        }, kNoExec);
    }
    g.addPass("point shadow", [&](PassBuilder& b) {
        b.read(drawArgs, Access::IndirectRead);
        graph::TextureDesc d = absolute(kDepth, 512, 512);
        d.layers = 6;
        d.cube = true;
        cube = b.write(b.create("point shadow cube", d), Access::DepthWrite);
    }, kNoExec);
    g.addPass("depth prepass", [&](PassBuilder& b) {
        b.read(drawArgs, Access::IndirectRead);
        depth = b.write(b.create("depth", relative(kDepth)), Access::DepthWrite);
    }, kNoExec);
    g.addPass("gbuffer", [&](PassBuilder& b) {
        b.read(drawArgs, Access::IndirectRead);
        b.read(depth, Access::DepthRead);
        albedo = b.write(b.create("albedo", relative(VK_FORMAT_R8G8B8A8_UNORM)), Access::ColorWrite);
        normal = b.write(b.create("normal", relative(VK_FORMAT_R16G16_SFLOAT)), Access::ColorWrite);
        material = b.write(b.create("material", relative(VK_FORMAT_R8G8B8A8_UNORM)), Access::ColorWrite);
        velocity = b.write(b.create("velocity", relative(VK_FORMAT_R16G16_SFLOAT)), Access::ColorWrite);
    }, kNoExec);
    g.addPass("hi-z", [&](PassBuilder& b) {
        b.read(depth, Access::SampledRead, kCompute);
        graph::TextureDesc d = relative(VK_FORMAT_R32_SFLOAT, 0.5f);
        d.mips = 0;
        hiz = b.write(b.create("hi-z", d), Access::StorageWrite, kCompute);
    }, kNoExec);
    g.addPass("ssao", [&](PassBuilder& b) {
        b.read(hiz, Access::SampledRead, kCompute);
        b.read(normal, Access::SampledRead, kCompute);
        ao = b.write(b.create("ao", relative(VK_FORMAT_R8_UNORM, 0.5f)), Access::StorageWrite, kCompute);
    }, kNoExec);
    g.addPass("ssao blur", [&](PassBuilder& b) {
        b.read(ao, Access::SampledRead, kCompute);
        aoBlur = b.write(b.create("ao blurred", relative(VK_FORMAT_R8_UNORM, 0.5f)), Access::StorageWrite, kCompute);
    }, kNoExec);
    g.addPass("voxelize", [&](PassBuilder& b) {
        b.read(drawArgs, Access::IndirectRead);
        voxels = b.write(b.create("voxels", absolute(VK_FORMAT_R16G16B16A16_SFLOAT, 128, 128, 128)),
                         Access::StorageWrite, kFragment);
    }, kNoExec);
    g.addPass("voxel mips", [&](PassBuilder& b) {
        voxels = b.write(voxels, Access::StorageReadWrite, kCompute);
    }, kNoExec);
    g.addPass("lighting", [&](PassBuilder& b) {
        for (TextureHandle t : {albedo, normal, material, depth, aoBlur, voxels, cube}) {
            b.read(t, Access::SampledRead, kCompute);
        }
        for (TextureHandle c : cascades) b.read(c, Access::SampledRead, kCompute);
        hdr = b.write(b.create("hdr", relative(kHdr)), Access::StorageWrite, kCompute);
    }, kNoExec);
    g.addPass("ssr", [&](PassBuilder& b) {
        for (TextureHandle t : {hdr, hiz, normal}) b.read(t, Access::SampledRead, kCompute);
        ssr = b.write(b.create("ssr", relative(kHdr, 0.5f)), Access::StorageWrite, kCompute);
    }, kNoExec);
    g.addPass("volumetric fog", [&](PassBuilder& b) {
        b.read(cascades[0], Access::SampledRead, kCompute);
        b.read(depth, Access::SampledRead, kCompute);
        fog = b.write(b.create("fog", relative(kHdr, 0.25f)), Access::StorageWrite, kCompute);
    }, kNoExec);
    g.addPass("composite", [&](PassBuilder& b) {
        for (TextureHandle t : {hdr, ssr, fog}) b.read(t, Access::SampledRead, kCompute);
        composite = b.write(b.create("composite", relative(kHdr)), Access::StorageWrite, kCompute);
    }, kNoExec);
    g.addPass("taa", [&](PassBuilder& b) {
        b.read(composite, Access::SampledRead, kCompute);
        b.read(velocity, Access::SampledRead, kCompute);
        b.read(b.history("taa"), Access::SampledRead, kCompute);
        graph::TextureDesc d = relative(kHdr);
        d.persistent = true;
        taa = b.write(b.create("taa", d), Access::StorageWrite, kCompute);
    }, kNoExec);
    g.addPass("luminance histogram", [&](PassBuilder& b) {
        b.read(taa, Access::SampledRead, kCompute);
        histogram = b.write(b.create("histogram", graph::BufferDesc{256 * 4}), Access::StorageWrite, kCompute);
    }, kNoExec);
    g.addPass("exposure", [&](PassBuilder& b) {
        b.read(histogram, Access::StorageRead, kCompute);
        b.read(b.historyBuffer("exposure"), Access::StorageRead, kCompute);
        exposure = b.write(b.create("exposure", graph::BufferDesc{16, true}), Access::StorageWrite, kCompute);
    }, kNoExec);
    TextureHandle bloom[5];
    bloom[0] = taa;
    for (int i = 1; i <= 4; ++i) {
        g.addPass("bloom down " + std::to_string(i), [&](PassBuilder& b) {
            b.read(bloom[i - 1], Access::SampledRead, kCompute);
            bloom[i] = b.write(b.create("bloom " + std::to_string(i), relative(kHdr, 1.0f / float(1 << i))),
                               Access::StorageWrite, kCompute);
        }, kNoExec);
    }
    TextureHandle up = bloom[4];
    for (int i = 3; i >= 1; --i) {
        g.addPass("bloom up " + std::to_string(i), [&](PassBuilder& b) {
            b.read(up, Access::SampledRead, kCompute);
            up = b.write(bloom[i], Access::StorageReadWrite, kCompute);
        }, kNoExec);
    }
    g.addPass("tonemap", [&](PassBuilder& b) {
        b.read(taa, Access::SampledRead, kFragment);
        b.read(up, Access::SampledRead, kFragment);
        b.read(exposure, Access::StorageRead, kFragment);
        ldr = b.write(b.create("ldr", relative(VK_FORMAT_R8G8B8A8_SRGB)), Access::ColorWrite);
    }, kNoExec);
    g.addPass("debug overlay", [&](PassBuilder& b) {   // culled: nothing reads its output
        b.read(hdr, Access::SampledRead, kFragment);
        b.write(b.create("debug", relative(VK_FORMAT_R8G8B8A8_UNORM)), Access::ColorWrite);
    }, kNoExec);
    g.markOutput(ldr);
}

void BM_GraphCompile30Passes(benchmark::State& state) {
    QueryOnlyBackend backend;
    graph::ResourcePool pool(backend);
    size_t run = 0, barriers = 0;
    for (auto _ : state) {
        graph::RenderGraph g(pool, VkExtent2D{1920, 1080});
        declareFrame(g);
        g.compile();
        run = g.executionOrder().size();
        benchmark::DoNotOptimize(run);
    }
    {
        graph::RenderGraph g(pool, VkExtent2D{1920, 1080});
        declareFrame(g);
        g.compile();
        for (const std::string& pass : g.executionOrder()) barriers += g.barriersBefore(pass).size();
        state.counters["transient_MiB"] = double(g.aliasingPlan().totalBytes()) / (1 << 20);
        state.counters["unaliased_MiB"] = double(g.aliasingPlan().unaliasedBytes()) / (1 << 20);
    }
    state.counters["passes_run"] = double(run);
    state.counters["barriers"] = double(barriers);
    setRow(state, {"render graph", "synthetic deferred frame: 30 passes (1 culled), 31 resources + 2 history, 1920x1080",
                   "declare + compile (order, cull, barriers, layouts, aliasing); query-only backend", "-", "",
                   "ours", "cpu"});
}
BENCHMARK(BM_GraphCompile30Passes)->MinTime(0.3)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace idk::bench
