// pt_frame.hpp: the path tracer's per-resolution GPU state (ray queues, path states, hits, shadow rays, sort
// buffers, accumulation sums, output images) and a small helper that imports these owned resources into each
// batch's render graph and carries their synchronization state from one graph to the next. Owned (not graph
// transients) because the sums persist across batches and the conformance tests read the queues back.
#pragma once
#include <map>
#include <string>

#include "graph/render_graph.hpp"
#include "vk/bindless.hpp"
#include "vk/resources.hpp"

namespace idk::vk {
class Context;
}

namespace idk::render {

struct PtFrameResources {
    uint32_t width = 0, height = 0;
    vk::Buffer paths, hits, shadowRays, guides, keys, sortScratch;
    vk::Buffer queue[2], args[2], shadow[2], shadowArgs[2];
    vk::Buffer accumColor, accumAlbedo, accumNormal, accumDepth, accumMoment;
    vk::Image colorImage, albedoImage, normalImage, depthImage, varianceImage, denoisedImage;
    vk::StorageImageIndex colorStorage, albedoStorage, normalStorage, depthStorage, varianceStorage;
    vk::StorageBufferIndex keysIndex, queueIndex[2], scratchIndex;
};

// Creates everything for width x height (sorting buffers only when `sorting`).
PtFrameResources createPtFrame(vk::Context& ctx, uint32_t width, uint32_t height, bool sorting);
void destroyPtFrame(vk::Context& ctx, PtFrameResources& frame);

// Tracks the graph handle of every owned resource used in one graph and each resource's state between graphs.
class PtGraphResources {
public:
    explicit PtGraphResources(graph::RenderGraph& graph, std::map<const void*, graph::ResourceState>& states)
        : graph_(graph), states_(states) {}
    graph::BufferHandle& buffer(const vk::Buffer& buffer);   // imports on first use
    // Imports on first use (final use: transfer source); `storageIndex`: its bindless storage slot, if any.
    graph::TextureHandle& image(const vk::Image& image, uint32_t storageIndex = graph::kNoBindlessIndex);
    void saveStates();                                       // after compile: the states the next graph starts from

private:
    graph::RenderGraph& graph_;
    std::map<const void*, graph::ResourceState>& states_;
    std::map<const void*, graph::BufferHandle> buffers_;
    std::map<const void*, graph::TextureHandle> images_;
};

}  // namespace idk::render
