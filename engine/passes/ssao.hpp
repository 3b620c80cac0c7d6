// ssao.hpp: the screen-space ambient occlusion pass (ssao.cpp).
#pragma once
#include <cstdint>

#include "graph/render_graph.hpp"
#include "passes/passes.hpp"
#include "vk/shader_library.hpp"

namespace idk::passes {

struct SsaoParams {
    float radius = 0.2f;
    uint32_t samples = 16;
    uint32_t frameIndex = 0;
};

// R32F visibility of the ambient light per G-buffer pixel (1 = unoccluded; background 1).
graph::TextureHandle addSsaoPass(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                 const GBufferOutputs& gbuffer, graph::BufferHandle frame, const SsaoParams& params);

}  // namespace idk::passes
