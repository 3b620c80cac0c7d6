// gbuffer.cpp: rasterizes every (instance, primitive) of the GPU scene with ONE vkCmdDrawIndexedIndirect
// (gl_DrawID selects instance and material) into albedo, normal, material and emissive targets plus depth, and
// for scenes with KHR_materials_specular/_clearcoat/_sheen textures or KHR_materials_anisotropy a layers target
// with their texels and the anisotropy direction (plus a spill target for materials whose texels exceed its bits).
// Ports IDKEngine's RasterPipeline G-buffer step (GBuffer/VertexPath/vertex.glsl + GBuffer/fragment.glsl).
// Deviation: IDKEngine draws twice (single-sided with culling, then double-sided); here one draw with culling
// off and back faces of single-sided materials rejected in the fragment shader. With GPU culling (passes/cull.cpp)
// it draws the compacted commands with vkCmdDrawIndexedIndirectCount instead.
#include "passes/indirect_draw.hpp"
#include "passes/passes.hpp"
#include "passes/culling.hpp"
#include "passes/rendering.hpp"

#include <memory>
#include <stdexcept>
#include <vector>

#include "shared/deferred_types.h"

namespace idk::passes {

void IndirectDrawLog::record(std::string_view pass, uint32_t drawCount) {
    for (Entry& e : entries) {
        if (e.pass == pass) {
            ++e.calls;
            e.draws += drawCount;
            return;
        }
    }
    entries.push_back({std::string(pass), 1, drawCount});
}

namespace {

// Storage-image formats of the core set (readers use imageLoad; see shared/deferred_types.h for why).
constexpr VkFormat kAlbedoFormat = VK_FORMAT_R8G8B8A8_UNORM;  // sRGB-encoded by the shader
constexpr VkFormat kNormalFormat = VK_FORMAT_R32_UINT;        // octahedral, packSnorm2x16
constexpr VkFormat kMaterialFormat = VK_FORMAT_R8G8B8A8_UNORM;
constexpr VkFormat kEmissiveFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
constexpr VkFormat kDepthCopyFormat = VK_FORMAT_R32_SFLOAT;  // gl_FragCoord.z of the kept fragment
constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;      // attachment only, not stored
constexpr VkFormat kIdFormat = VK_FORMAT_R32G32_UINT;        // surface IDs (optional): draw, triangle
// Extension texels (optional): packUnorm4x8 words of include/gbuffer_fragment.glsl.
constexpr VkFormat kLayersFormat = VK_FORMAT_R32G32B32A32_UINT;
// Texels the layers target has no bits for (include/gbuffer_layer_bits.glsl): 48 bits used of 64.
constexpr VkFormat kLayerSpillFormat = VK_FORMAT_R32G32_UINT;

VkRenderingAttachmentInfo colorAttachment(VkImageView view) {
    VkRenderingAttachmentInfo a{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    a.imageView = view;
    a.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    a.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;  // zero: background pixels are told apart by depth == 1
    a.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    return a;
}

graph::TextureHandle target(graph::PassBuilder& b, const char* name, VkFormat format, graph::Access access) {
    graph::TextureDesc desc;
    desc.format = format;
    return b.write(b.create(name, desc), access);
}

}  // namespace

GBufferOutputs addGBufferPass(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                              const SceneBuffers& scene, graph::BufferHandle frame, IndirectDrawLog* log,
                              const CulledDraws* culled, const GBufferOutputs* drawOver, graph::TextureHandle ids) {
    if (ids.valid() && (culled || drawOver))
        throw std::logic_error("addGBufferPass: the surface-ID buffer is drawn on the unculled vertex path only");
    if (ids.valid() && !ctx.capabilities().geometryShader)
        throw std::runtime_error("surface-ID buffer: the device lacks the geometryShader feature (gl_PrimitiveID)");
    auto out = std::make_shared<GBufferOutputs>();
    const SceneBuffers s = scene;
    const CulledDraws c = culled ? *culled : CulledDraws{};
    const bool load = drawOver != nullptr;
    const GBufferOutputs over = load ? *drawOver : GBufferOutputs{};
    graph.addPass(
        load ? "gbuffer_late" : "gbuffer",
        [&](graph::PassBuilder& b) {
            // The geometry stages: vertex, or task + mesh on the mesh rung.
            const VkPipelineStageFlags2 kVs = c.meshTasks ? kTaskMeshStages : VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT;
            if (load) {
                out->albedo = b.write(over.albedo, graph::Access::ColorReadWrite);
                out->normal = b.write(over.normal, graph::Access::ColorReadWrite);
                out->material = b.write(over.material, graph::Access::ColorReadWrite);
                out->emissive = b.write(over.emissive, graph::Access::ColorReadWrite);
                out->depth = b.write(over.depth, graph::Access::ColorReadWrite);
                out->depthAttachment = b.write(over.depthAttachment, graph::Access::DepthWrite);
                if (over.layers.valid()) out->layers = b.write(over.layers, graph::Access::ColorReadWrite);
                if (over.layerSpill.valid())
                    out->layerSpill = b.write(over.layerSpill, graph::Access::ColorReadWrite);
            } else {
                out->albedo = target(b, "gbuffer albedo", kAlbedoFormat, graph::Access::ColorWrite);
                out->normal = target(b, "gbuffer normal", kNormalFormat, graph::Access::ColorWrite);
                out->material = target(b, "gbuffer material", kMaterialFormat, graph::Access::ColorWrite);
                out->emissive = target(b, "gbuffer emissive", kEmissiveFormat, graph::Access::ColorWrite);
                out->depth = target(b, "gbuffer depth", kDepthCopyFormat, graph::Access::ColorWrite);
                out->depthAttachment = target(b, "gbuffer depth attachment", kDepthFormat, graph::Access::DepthWrite);
                if (ids.valid()) out->ids = b.write(ids, graph::Access::ColorWrite);
                if (s.layerTexels) out->layers = target(b, "gbuffer layers", kLayersFormat, graph::Access::ColorWrite);
                if (s.layerTexels && s.layerSpill)
                    out->layerSpill = target(b, "gbuffer layer spill", kLayerSpillFormat, graph::Access::ColorWrite);
            }
            b.read(frame, graph::Access::StorageRead, kVs);
            if (s.drawCount == 0) return;
            readSceneMeshes(b, s, kVs);
            if (c.commands.valid()) {
                b.read(c.commands, graph::Access::IndirectRead);
                b.read(c.counters, graph::Access::IndirectRead);
                if (c.meshTasks) declareMeshDraws(b, c);
            } else {
                b.read(s.drawCommands, graph::Access::IndirectRead);
            }
        },
        [&ctx, &shaders, s, c, load, frame, out, log](graph::PassContext& pc) {
            VkCommandBuffer cmd = pc.commandBuffer();
            VkExtent2D extent = pc.outputExtent();
            const bool writeIds = out->ids.valid();
            const bool writeLayers = out->layers.valid();
            const bool writeSpill = out->layerSpill.valid();

            std::vector<VkRenderingAttachmentInfo> colors = {
                colorAttachment(pc.view(out->albedo)), colorAttachment(pc.view(out->normal)),
                colorAttachment(pc.view(out->material)), colorAttachment(pc.view(out->emissive)),
                colorAttachment(pc.view(out->depth))};
            colors[4].clearValue.color = {{1.0f, 0.0f, 0.0f, 0.0f}};  // background depth
            // Location 5: the layer texels; location 6: their spill; location 7: the surface IDs. A slot below a used
            // one is an attachment without a view (its writes are discarded, as Vulkan defines for VK_NULL_HANDLE).
            // The IDs come last so that a frame without them has no such gap (the shader writes every slot below).
            if (writeLayers || writeSpill || writeIds)
                colors.push_back(writeLayers ? colorAttachment(pc.view(out->layers)) : colorAttachment(VK_NULL_HANDLE));
            if (writeSpill || writeIds)
                colors.push_back(writeSpill ? colorAttachment(pc.view(out->layerSpill))
                                            : colorAttachment(VK_NULL_HANDLE));
            if (writeIds) {
                colors.push_back(colorAttachment(pc.view(out->ids)));
                colors[7].clearValue.color.uint32[0] = colors[7].clearValue.color.uint32[1] = UINT32_MAX;
            }
            if (load)
                for (VkRenderingAttachmentInfo& a : colors) a.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
            VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
            depth.imageView = pc.view(out->depthAttachment);
            depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
            depth.loadOp = load ? VK_ATTACHMENT_LOAD_OP_LOAD : VK_ATTACHMENT_LOAD_OP_CLEAR;
            // Readers use the R32F copy; only a later pass drawing over this one needs the attachment kept.
            depth.storeOp = c.keepDepth ? VK_ATTACHMENT_STORE_OP_STORE : VK_ATTACHMENT_STORE_OP_DONT_CARE;
            depth.clearValue.depthStencil = {1.0f, 0};
            beginRendering(cmd, extent, colors, &depth);
            if (s.drawCount > 0) {
                vk::GraphicsPipelineDesc desc;
                desc.vertex = c.commands.valid() ? vk::ShaderId::gbuffer_gbuffer_culled_vert
                                                 : vk::ShaderId::gbuffer_gbuffer_vert;
                desc.fragment = writeIds ? vk::ShaderId::gbuffer_gbuffer_ids_frag : vk::ShaderId::gbuffer_gbuffer_frag;
                desc.colorFormats = {kAlbedoFormat, kNormalFormat, kMaterialFormat, kEmissiveFormat, kDepthCopyFormat};
                if (writeLayers || writeSpill || writeIds)
                    desc.colorFormats.push_back(writeLayers ? kLayersFormat : VK_FORMAT_UNDEFINED);
                if (writeSpill || writeIds)
                    desc.colorFormats.push_back(writeSpill ? kLayerSpillFormat : VK_FORMAT_UNDEFINED);
                if (writeIds) desc.colorFormats.push_back(kIdFormat);
                desc.depthFormat = kDepthFormat;
                desc.depthCompare = VK_COMPARE_OP_LESS;  // scene::camera convention: depth 0 near, 1 far
                desc.cull = VK_CULL_MODE_NONE;           // facing is decided per material in the fragment shader
                desc.pushBytes = sizeof(gpu::GBufferPush);
                if (c.meshTasks) useMeshShaders(desc);
                const vk::Pipeline& pipeline = shaders.graphics(desc);

                vk::bindPipeline(cmd, pipeline);
                ctx.bindless().bind(cmd);
                gpu::GBufferPush push{pc.buffer(frame).address,
                                      pc.buffer(s.vertices).address,
                                      pc.buffer(s.instances).address,
                                      pc.buffer(s.meshes).address,
                                      pc.buffer(s.materials).address,
                                      s.colors.valid() ? pc.buffer(s.colors).address : 0,
                                      s.uv1.valid() ? pc.buffer(s.uv1).address : 0};
                vk::pushConstants(cmd, ctx, push);
                vkCmdBindIndexBuffer(cmd, pc.vkBuffer(s.indices), 0, VK_INDEX_TYPE_UINT32);
                if (c.meshTasks) {
                    recordMeshDraws(pc, ctx, c, push);
                    if (log) log->record(pc.passName(), c.maxDraws);
                } else if (c.commands.valid()) {
                    vkCmdDrawIndexedIndirectCount(cmd, pc.vkBuffer(c.commands), 0, pc.vkBuffer(c.counters), 0,
                                                  c.maxDraws, sizeof(VkDrawIndexedIndirectCommand));
                    if (log) log->record(pc.passName(), c.maxDraws);  // the most it may draw; the GPU count is a stat
                } else {
                    drawAllIndexedIndirect(cmd, pc.vkBuffer(s.drawCommands), s.drawCount);  // indirect_draw.hpp
                    if (log) log->record(pc.passName(), s.drawCount);
                }
            }
            vkCmdEndRendering(cmd);
        });
    return *out;
}

}  // namespace idk::passes
