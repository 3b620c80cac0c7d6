// temporal_passes.hpp: the passes of the temporal feature (frame/temporal_feature.hpp): motion vectors, the
// history copies of animated scene buffers, the TAA resolve and its output copy.
#pragma once
#include "graph/render_graph.hpp"
#include "passes/passes.hpp"
#include "vk/shader_library.hpp"

namespace idk::passes {

// motion_vectors.cpp: the G-buffer's indirect draws again, writing R32UI packHalf2x16(current uv - previous uv)
// wherever the G-buffer kept a surface (0 elsewhere). prevVertices/prevInstances: last frame's copies, or the
// current buffers when nothing in the scene moves.
struct MotionVectorInputs {
    SceneBuffers scene;
    graph::BufferHandle prevVertices, prevInstances;
    graph::BufferHandle temporal;  // GpuTemporalFrame
    graph::TextureHandle depth;    // GBufferOutputs::depth
};
graph::TextureHandle addMotionVectorPass(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                         const MotionVectorInputs& in, IndirectDrawLog* log);
// Copies `source` into a new version of the persistent buffer `persistentName` (next frame's history).
void addBufferHistoryPass(graph::RenderGraph& graph, const char* passName, const char* persistentName,
                          graph::BufferHandle source, VkDeviceSize bytes);

// taa.cpp: the resolve (history: persistent "taa color", "taa depth", "taa motion") and the copy of the resolved
// colour into `hdr`; returns hdr's new version.
struct TaaInputs {
    graph::BufferHandle temporal;  // GpuTemporalFrame
    graph::TextureHandle color, depth, motion;
    bool reset = false;            // ignore the history this frame
    bool frameStatic = false;      // nothing moved or changed since last frame: keep the history whole
    float maxWeight = 16.0f, clipGamma = 1.25f;
    bool clampHistory = true;
};
graph::TextureHandle addTaaPasses(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                  const TaaInputs& in);

}  // namespace idk::passes

namespace idk::passes {

// upscale.cpp: the temporal upscaler's reconstruction of the render-size lit image `color` at the output size
// (persistent "upscale color", weight in alpha), then its copy into `target` (output size; the frame's output in
// Hdr mode, else a transient the tonemap reads); returns target's new version. `opaque`: the lit image before
// transparency (invalid: the scene has none), from which the resolve derives its reactive term.
struct UpscaleInputs {
    graph::BufferHandle temporal;  // GpuTemporalFrame (render size, jitter)
    graph::TextureHandle color, depth, motion, opaque, target;
    VkExtent2D outputExtent{};
    bool reset = false, frameStatic = false;
    float maxWeight = 16.0f, clipGamma = 1.25f, sigma = 0.5f;
};
graph::TextureHandle addUpscalePasses(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                      const UpscaleInputs& in);

}  // namespace idk::passes
