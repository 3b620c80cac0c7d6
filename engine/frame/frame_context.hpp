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
#include "passes/culling.hpp"
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
    graph::BufferHandle vrsRates;                  // VRS software rung: last frame's rates (invalid: VRS off)
    passes::CulledDraws cameraDraws;               // GPU culling's compacted camera draws (invalid: culling off)
    // The Hi-Z pyramid of the final G-buffer depth (shared/depth_pyramid.h): a float buffer of levels 0..n-1,
    // level 0 = ceil(width / 2) x ceil(height / 2), each texel the MAXIMUM (farthest) depth of the 2^(k+1)-square
    // of depth pixels it covers; depth 0 near .. 1 far (not reversed), background 1. Built only if a pass reads it.
    graph::BufferHandle depthPyramid;

    // Temporal (temporal_feature.cpp), with --aa taa/upscale: viewProjection above is then jittered by jitterPixels
    // (the offset of this frame's samples from the pixel centres); motionVectors holds R32UI
    // packHalf2x16(current uv - previous uv, unjittered) for geometry pixels (background: reproject by camera).
    // With --vrs on alone: temporalConstants and motionVectors only (no jitter), for the VRS classifier.
    glm::mat4 unjitteredViewProjection{1.0f};
    glm::vec2 jitterPixels{0.0f};
    graph::BufferHandle temporalConstants;         // gpu::GpuTemporalFrame (shared/temporal_types.h)
    graph::TextureHandle motionVectors;
    bool temporalReset = true;                     // no usable history this frame (first frame, reset, resize)
    graph::TextureHandle ambientOcclusion;         // R32F ambient visibility (ssao_feature.cpp); invalid: none
    graph::TextureHandle voxelGrid;                // VXGI: RGBA16F radiance + coverage grid (vxgi_feature.hpp)
    passes::VoxelGridBox voxelBox;                 // its world cube
    passes::IndirectLightImages indirectLight;     // VXGI cone-traced light per pixel (deferred lighting reads it)
    passes::ForwardVxgiInputs vxgiCones;           // VXGI cone parameters + volumes for forward passes (transparency)
    bool temporalStatic = false;                   // nothing moved or changed since last frame (temporal history)
    graph::TextureHandle reflections;              // SSR: RGBA16F reflected radiance + hit weight (ssr_feature.hpp)
};

}  // namespace idk::frame
