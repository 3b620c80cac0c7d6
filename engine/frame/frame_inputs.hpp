// frame_inputs.hpp: the first step of every PBR frame: the frame constants (camera, lights, environment) in a
// per-slot host-visible buffer, the frame's light list (the scene's plus the caller's extra lights), the GPU
// scene's buffers imported into the graph, and the scene's own per-frame updates (patched materials, the animated
// pose). Fills FrameContext::frameConstants, scene and lights. Ports the start of IDKEngine's RasterPipeline.Render
// (reference 1.5, step 6.6).
#pragma once
#include <vector>

#include "frame/frame_context.hpp"
#include "render/environment.hpp"
#include "render/gpu_scene.hpp"
#include "render/vk_graph_backend.hpp"

namespace idk::frame {

class FrameInputs {
public:
    explicit FrameInputs(vk::Context& ctx) : ctx_(ctx) {}
    ~FrameInputs();
    FrameInputs(const FrameInputs&) = delete;
    FrameInputs& operator=(const FrameInputs&) = delete;

    // Lights that are not part of the scene (the viewer's shot lights), appended to the scene's from the next frame.
    void setExtraLights(std::vector<gpu::GpuLight> lights) { extraLights_ = std::move(lights); }

    void addPasses(FrameContext& f, render::GpuScene& scene, const render::GpuEnvironment& environment);

private:
    const vk::Buffer& lightBuffer(FrameContext& f, render::GpuScene& scene);

    vk::Context& ctx_;
    std::vector<vk::Buffer> frameConstants_;      // one host-visible GpuFrame per frame slot
    vk::Buffer albedoTables_;                     // pathtrace::albedoTableData() (GGX energy compensation), static
    std::vector<gpu::GpuLight> extraLights_;
    std::vector<gpu::GpuLight> combinedLights_;   // scene lights + extra lights of the frame being built
    std::vector<vk::Buffer> lightBuffers_;        // per frame slot, only while there are extra lights
};

// Imports a persistent buffer into the graph (invalid handle for an empty buffer).
graph::BufferHandle importBuffer(graph::RenderGraph& graph, const char* name, const vk::Buffer& buffer,
                                 const graph::ResourceState& state = {});

}  // namespace idk::frame
