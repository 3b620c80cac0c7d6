// frame_context.hpp: everything a feature may read or extend while the PBR frame's render graph is built. The
// frame recipe (frame_recipe.cpp) passes one FrameContext through every feature in order; a feature reads what
// earlier ones produced (scene buffers, G-buffer, shadows, ...) and fills the fields it produces. A new feature
// adds fields here instead of parameters to every call. Handles stay invalid until their producer has run (and
// when that feature is off): readers check valid().
#pragma once
#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

#include "graph/render_graph.hpp"
#include "passes/passes.hpp"
#include "passes/vxgi_passes.hpp"
#include "render/render_settings.hpp"
#include "scene/camera.hpp"
#include "shared/scene_types.h"
#include "vk/context.hpp"
#include "vk/shader_library.hpp"

namespace idk::frame {

struct FrameContext {
    // The device and the graph being built.
    vk::Context& ctx;
    vk::ShaderLibrary& shaders;
    graph::RenderGraph& graph;
    passes::IndirectDrawLog& log;
    const render::RenderSettings& settings;

    // This frame: camera, size, frame slot (which per-slot host-visible buffers are free to write).
    scene::CameraView camera;
    uint32_t width = 0, height = 0;
    uint32_t slot = 0, framesInFlight = 1;
    glm::mat4 viewProjection{1.0f};

    // Inputs (frame_inputs.cpp, environment_feature.cpp): every later feature may read them.
    graph::BufferHandle frameConstants;            // gpu::GpuFrame of this frame
    passes::SceneBuffers scene;                    // the GPU scene's buffers, after this frame's updates
    const std::vector<gpu::GpuLight>* lights = nullptr;  // the frame's lights (scene + extra), CPU copy
    graph::TextureHandle environment;              // the equirectangular environment (sampled)

    // Products, in frame order.
    passes::PointShadowOutputs pointShadows;       // invalid table: no point shadows this frame
    passes::GBufferOutputs gbuffer;
    graph::TextureHandle hdr;                      // the lit HDR image (RGBA16F), updated by each pass that adds light
    graph::TextureHandle output;                   // the frame's target (imported); the recipe's last write
    graph::TextureHandle voxelGrid;                // VXGI: RGBA16F radiance + coverage grid (vxgi_feature.hpp)
    passes::VoxelGridBox voxelBox;                 // its world cube
    passes::IndirectLightImages indirectLight;     // VXGI cone-traced light per pixel (deferred lighting reads it)
};

}  // namespace idk::frame
