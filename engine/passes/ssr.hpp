// ssr.hpp: the screen-space reflection passes (ssr.cpp): the closest-depth Hi-Z pyramid, the Hi-Z ray march, and
// the copy of the lit image that the next frame's march samples.
#pragma once
#include <glm/glm.hpp>

#include <cstdint>

#include "graph/render_graph.hpp"
#include "passes/passes.hpp"
#include "vk/shader_library.hpp"

namespace idk::passes {

// "ssr_hiz": the MINIMUM (closest) depth pyramid of `depth` (shared/depth_pyramid.h layout; the culling pyramid
// is the maximum one). A float buffer.
graph::BufferHandle addSsrPyramidPass(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                      graph::TextureHandle depth, glm::uvec2 size);
// Outside a graph (conformance tests): passes::recordDepthPyramid with HizReduction::Closest (passes/culling.hpp).

struct SsrInputs {
    GBufferOutputs gbuffer;
    graph::BufferHandle frame;          // GpuFrame of this frame
    graph::BufferHandle pyramid;        // addSsrPyramidPass
    glm::mat4 previousViewProjection{1.0f};
    bool havePrevious = false;          // false: no lit image of a previous frame (every ray misses)
    uint32_t maxSteps = 64;
    float thickness = 0.1f;
};

// "ssr_trace": RGBA16F per pixel, rgb = radiance reflected into it from last frame's lit image ("ssr lit image"
// history), a = hit weight (0: miss, the lighting keeps its environment / VXGI specular term).
graph::TextureHandle addSsrTracePass(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                     const SsrInputs& in);

// "ssr_keep": copies this frame's lit image `hdr` (RGBA16F) into the persistent "ssr lit image" for the next frame.
void addSsrKeepPass(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders, graph::TextureHandle hdr);

}  // namespace idk::passes
