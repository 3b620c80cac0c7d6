// passes.hpp: every pass is a free function in its own file that declares its resources to the render graph
// and records its work; this header lists them with their settings and outputs.
#pragma once
#include <glm/glm.hpp>

#include "graph/render_graph.hpp"
#include "render/lambert_scene.hpp"
#include "vk/shader_library.hpp"

namespace idk::passes {

// lambert.cpp: the foundation's minimal rasterizer (Lambert diffuse + emission + point lights).
struct LambertSettings {
    glm::mat4 viewProjection{1.0f};
    glm::vec3 ambient{0.03f};
    glm::vec4 clearColor{0.0f, 0.0f, 0.0f, 1.0f};
    VkFormat colorFormat = VK_FORMAT_R16G16B16A16_SFLOAT;  // the target's format (pipelines are built per format)
};
struct LambertOutputs {
    graph::TextureHandle color;  // the written version of the target
    graph::TextureHandle depth;  // transient D32
};
LambertOutputs addLambertPass(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                              const render::GpuLambertScene& scene, graph::TextureHandle target,
                              const LambertSettings& settings);

}  // namespace idk::passes
