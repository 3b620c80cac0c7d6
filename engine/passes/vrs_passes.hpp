// vrs_passes.hpp: the passes of variable-rate shading (issue 14; frame/vrs_feature.* drives them): the velocity
// field from the temporal motion vectors, the per-tile rate classifier, the software rung's reconstruction and the
// --vrs-debug overlay. Shaders in shaders_glsl/vrs/, shared structs in shaders_glsl/shared/vrs_types.h.
#pragma once
#include <glm/glm.hpp>

#include "graph/render_graph.hpp"
#include "passes/passes.hpp"
#include "shared/vrs_types.h"
#include "vk/pipeline.hpp"

namespace idk::passes {

// Classifier parameters (one workgroup per tile; tileSize 8, 16 or 32).
struct VrsClassifyParams {
    uint32_t tileSize = gpu::kVrsDefaultTileSize;
    bool subgroupReduce = true;  // false: the shared-memory tree (devices without subgroup arithmetic)
    float frameSeconds = 1.0f / 60.0f;
    float speedFactor = gpu::kVrsSpeedFactor;
    float lumVarianceFactor = gpu::kVrsLumVarianceFactor;
};

// Records the classifier outside a graph (tests): `lit` an RGBA16F storage-image index, addresses of the velocity
// (0: none) and of a rate buffer whose header the caller has written.
void recordVrsClassify(VkCommandBuffer cmd, vk::Context& ctx, vk::ShaderLibrary& shaders, const VrsClassifyParams& params,
                       uint32_t lit, uint32_t width, uint32_t height, VkDeviceAddress velocity, VkDeviceAddress rates);

// vrs_classify.cpp: rates for the next frame from the lit image and the velocity; returns the rates' new version.
graph::BufferHandle addVrsClassifyPass(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                       const VrsClassifyParams& params, graph::TextureHandle lit,
                                       graph::BufferHandle velocity, graph::BufferHandle rates);

// vrs_velocity.cpp: vec2 UV-per-frame motion of each pixel: the motion vectors (R32UI packHalf2x16, zero on the
// background) where depth < 1, the camera's reprojection (temporal constants) elsewhere; returns a transient buffer.
graph::BufferHandle addVrsVelocityPass(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                       graph::BufferHandle temporal, graph::TextureHandle motion,
                                       graph::TextureHandle depth);

// vrs_reconstruct.cpp: fills the non-anchor pixels of `target` (software rung); returns its new version.
graph::TextureHandle addVrsReconstructPass(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                           const GBufferOutputs& gbuffer, graph::BufferHandle frame,
                                           graph::BufferHandle rates, graph::TextureHandle target,
                                           bool fillSentinel = false);  // test hook: kVrsSentinel everywhere

// vrs_overlay.cpp: tints `target` by the rates (--vrs-debug); returns its new version.
graph::TextureHandle addVrsOverlayPass(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                       graph::BufferHandle rates, graph::TextureHandle target);

// The hardware rungs (frame/vrs_feature.cpp drives them when the "vrs" ladder chose a native rung).
// vrs_rate_image.cpp: the rates as an R8_UINT image, one texel per tile, in the KHR or NV encoding; returns it in
// the state of its copy (the lighting pass reads it as its shading-rate attachment / image).
// Records the conversion alone (tests): `texels` receives (tiles + 3) / 4 uints, byte i = tile i's texel.
void recordVrsRateTexels(VkCommandBuffer cmd, vk::Context& ctx, vk::ShaderLibrary& shaders, VkDeviceAddress rates,
                         VkDeviceAddress texels, uint32_t tiles, bool nvEncoding);
graph::TextureHandle addVrsRateImagePass(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                         graph::BufferHandle rates, uint32_t tilesX, uint32_t tilesY, bool nvEncoding);

// What vrs_lighting_rate.cpp reads: the compute lighting's inputs plus the rate image and the invocation counter.
struct VrsHardwareLighting {
    GBufferOutputs gbuffer;
    graph::BufferHandle frame, lights;
    graph::TextureHandle environment;
    LightingInputs inputs;            // inputs.vrsRates must be valid (the anchor of each fragment's cell)
    graph::TextureHandle rateImage;   // addVrsRateImagePass
    uint32_t texelSize = 16;          // pixels per rate texel side (= the classifier's tile)
    vk::ShadingRateSource source = vk::ShadingRateSource::KhrAttachment;
    graph::BufferHandle invocations;  // uint, zeroed before: the fragment invocations are added to it
};
// Lighting + sky as one fullscreen fragment pass at the hardware rates into `target`; returns its new version and
// sets `countedInvocations` to the counter's version after the pass.
graph::TextureHandle addVrsLightingRatePass(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                            const VrsHardwareLighting& in, graph::TextureHandle target,
                                            graph::BufferHandle& countedInvocations);

}  // namespace idk::passes
