// vxgi_voxelize.cpp: voxelization of the scene's direct diffuse light into a 3D grid: clear the accumulators, draw
// the scene once per projection axis into an attachment-less N x N render pass whose fragments raise their voxel's
// depth key ("vxgi_voxel_keys": the front-most rule, shared/vxgi_depth_key.h), draw it again so that the fragments
// in front write their voxel with image atomics (radiance and facing), and merge the accumulators into the RGBA16F
// grid and the directional volumes' level 0 (the clear and the merge are in vxgi_merge.cpp). Ports IDKEngine's
// Voxelizer.cs (its 3-draw fallback; the rung of write conflicts follows the "vxgi-atomics" ladder). On its
// gl-interop rung the fragments append records instead, "vxgi_gl_accumulate" (vxgi_gl_accumulate.cpp) adds them
// with GL float atomics into a shared sums buffer, and the merge averages those.
// Rasterisation follows the "conservative-raster" ladder unless --gi-raster centre: VK_EXT_conservative_rasterization
// (overestimate) where the device has it, else voxelize.geom's triangle dilation, so thin walls never leak.
// --gi-voxel-draws single follows "voxel-single-draw": VK_NV_geometry_shader_passthrough + VK_NV_viewport_swizzle
// (voxelize_passthrough.geom, vxgi_axis_swizzle.hpp) where the device has them, else voxelize_axis.geom.
// With S z-slabs (frame/vxgi_memory.hpp: a grid whose accumulators do not fit the memory budget) the accumulators
// and keys cover N x N x N/S voxels and clear, keys, voxelize and merge run once per slab.
// The draws go through passes/indirect_draw.hpp: lavapipe applied the point-shadow faces' culled count to plain
// indirect draws, and the voxelization then drew only the first (last face's count) scene draws.
#include "passes/vxgi_passes.hpp"

#include <algorithm>
#include <memory>
#include <stdexcept>
#include <string>

#include "passes/indirect_draw.hpp"
#include "passes/rendering.hpp"
#include "passes/vxgi_axis_swizzle.hpp"
#include "passes/vxgi_gl_accumulate.hpp"
#include "shared/pt_wavefront.h"
#include "shared/vxgi_types.h"

namespace idk::passes {
namespace {

vk::ShaderId fragmentShader(uint32_t mode, bool dilated) {
    if (mode == gpu::kVoxelAtomicsFloatAdd)
        return dilated ? vk::ShaderId::vxgi_voxelize_float_dilated_frag : vk::ShaderId::vxgi_voxelize_float_frag;
    if (mode == gpu::kVoxelAtomicsUintMax)
        return dilated ? vk::ShaderId::vxgi_voxelize_uint_dilated_frag : vk::ShaderId::vxgi_voxelize_uint_frag;
    return dilated ? vk::ShaderId::vxgi_voxelize_record_dilated_frag : vk::ShaderId::vxgi_voxelize_record_frag;
}

// What both voxelization draws share: the scene, the raster rungs and the push block's scene part.
struct VoxelDraws {
    SceneBuffers scene;
    graph::BufferHandle frame, table;
    VoxelGridBox box;
    std::optional<vk::Rung> conservative, singleDraw;
    std::optional<VoxelShadowRays> rays;
};

// Records the scene's draws into the attachment-less N x N rendering (one per projection axis, or one whose
// geometry shader picks each triangle's axis) with fragment shader `plain` (`dilated` behind the dilation
// fallback) and `push` completed with the scene's addresses (and with `lit` the shadows') and `slab`'s z range
// (kVoxelSlab*: the fragments outside it are dropped). Both passes rasterise alike, so a fragment of the key pass is
// the same fragment in the accumulating pass.
void recordVoxelDraws(graph::PassContext& pc, vk::Context& ctx, vk::ShaderLibrary& shaders, const VoxelDraws& d,
                      vk::ShaderId plain, vk::ShaderId dilated, gpu::VoxelizePush push, bool lit,
                      IndirectDrawLog* log, const VoxelSlab& slab) {
    const SceneBuffers& s = d.scene;
    const uint32_t n = d.box.size;
    VkCommandBuffer cmd = pc.commandBuffer();
    // No attachments: the fragments' only output is their atomics (the render area sets the raster grid).
    beginRendering(cmd, {n, n}, {});
    vk::GraphicsPipelineDesc desc;
    desc.vertex = vk::ShaderId::vxgi_voxelize_vert;
    desc.fragment = plain;
    if (d.conservative == vk::Rung::Native) {
        desc.conservative = true;
    } else if (d.conservative == vk::Rung::Fallback) {
        desc.geometry = vk::ShaderId::vxgi_voxelize_geom;
        desc.fragment = dilated;
    }
    const bool swizzled = d.singleDraw == vk::Rung::Native && !desc.geometry;
    if (swizzled) {  // the passthrough shader picks the viewport, the viewport's swizzle projects
        desc.geometry = vk::ShaderId::vxgi_voxelize_passthrough_geom;
        const std::array<VkViewportSwizzleNV, 3> swizzles = voxelAxisSwizzles();
        desc.viewportSwizzles.assign(swizzles.begin(), swizzles.end());
    } else if (d.singleDraw && !desc.geometry) {
        desc.geometry = vk::ShaderId::vxgi_voxelize_axis_geom;
    }
    desc.depthTest = false;
    desc.depthWrite = false;
    desc.cull = VK_CULL_MODE_NONE;  // both faces: a wall seen from behind in the projection still fills
    desc.pushBytes = sizeof(gpu::VoxelizePush);
    if (d.rays)
        desc.spec = {{gpu::kSpecPtHasAlpha, d.rays->hasAlpha ? 1u : 0u},
                     {gpu::kSpecPtStackSize, std::max(d.rays->blasStack, 1u)},
                     {gpu::kSpecPtTlasStackSize, std::max(d.rays->tlasStack, 1u)}};
    vk::bindPipeline(cmd, shaders.graphics(desc));
    if (swizzled) {  // three viewports [-N, N)^2 (one per axis), the grid's N x N square kept by the scissor
        const VkViewport viewport = voxelSwizzleViewport(n);
        const std::array<VkViewport, 3> viewports{viewport, viewport, viewport};
        const VkRect2D square{{0, 0}, {n, n}};
        const std::array<VkRect2D, 3> scissors{square, square, square};
        vkCmdSetViewport(cmd, 0, 3, viewports.data());
        vkCmdSetScissor(cmd, 0, 3, scissors.data());
    }
    ctx.bindless().bind(cmd);
    push.frame = pc.buffer(d.frame).address;
    setSceneAddresses(push, pc, s);
    push.pointShadows = lit && d.table.valid() ? pc.buffer(d.table).address : 0;
    if (lit && d.rays && d.rays->casters > 0) {  // the BVH and its scene are static buffers, read by address
        push.pointShadows = d.rays->sceneDesc;
        push.rayShadows = d.rays->casters;
    }
    push.gridMin = d.box.gridMin;
    push.voxelSize = d.box.voxelSize;
    push.gridSize = n;
    vkCmdBindIndexBuffer(cmd, pc.vkBuffer(s.indices), 0, VK_INDEX_TYPE_UINT32);
    // Three draws, one per projection axis (IDKEngine's measured-fastest fallback), or one whose geometry
    // shader picks each triangle's axis: by re-emitting it projected, or (native rung) by passing it
    // through to the viewport whose swizzle projects it.
    const uint32_t draws = d.singleDraw ? 1 : 3;
    for (uint32_t axis = 0; axis < draws; ++axis) {
        push.axis = (swizzled ? gpu::kVoxelAxisSwizzled : (d.singleDraw ? gpu::kVoxelAxisDominant : axis)) |
                    (slab.z << gpu::kVoxelSlabZShift) | (slab.depth << gpu::kVoxelSlabDepthShift);
        vk::pushConstants(cmd, ctx, push);
        // A slab's draws along x and y see it as a band of rows (x: v = z) or columns (y: u = z): the scissor keeps
        // the band and a pixel either side (a cull only, the fragment shader's slab test decides; a scissor changes
        // no fragment's interpolants). The geometry shaders (dilation, single draw) also drop whole triangles
        // outside the slab (voxelize_projection.glsl voxelTriangleInSlab); the vertex-only path (native
        // conservative raster, centre raster) rasterises the z-projected triangles of every slab in each.
        if (!d.singleDraw) {
            const uint32_t lo = slab.z > 0 ? slab.z - 1 : 0, hi = std::min(slab.z + slab.depth + 1, n);
            VkRect2D band{{0, 0}, {n, n}};  // the z draw: the whole square
            if (axis == 0) band = {{0, int32_t(lo)}, {n, hi - lo}};
            else if (axis == 1) band = {{int32_t(lo), 0}, {hi - lo, n}};
            vkCmdSetScissor(cmd, 0, 1, &band);
        }
        drawAllIndexedIndirect(cmd, pc.vkBuffer(s.drawCommands), s.drawCount);  // see indirect_draw.hpp
        if (log) log->record(pc.passName(), s.drawCount);
    }
    vkCmdEndRendering(cmd);
}

// The scene reads of a voxelization draw (the key pass needs no lights: it evaluates no lighting).
void readScene(graph::PassBuilder& b, const VoxelDraws& d, bool lights, const PointShadowOutputs& shadows) {
    constexpr VkPipelineStageFlags2 kVs = VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT;
    constexpr VkPipelineStageFlags2 kFs = VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT;
    const SceneBuffers& s = d.scene;
    // (voxelize.geom reads only its inputs: no buffer access, so no geometry-stage dependency.)
    b.read(d.frame, graph::Access::StorageRead, lights ? kVs | kFs : kVs);
    if (lights && s.lights.valid()) b.read(s.lights, graph::Access::StorageRead, kFs);
    if (lights && d.table.valid()) {
        b.read(d.table, graph::Access::StorageRead, kFs);
        for (graph::TextureHandle cube : shadows.cubes) b.read(cube, graph::Access::SampledRead, kFs);
    }
    if (s.drawCount == 0) return;
    readSceneMeshes(b, s);
    b.read(s.drawCommands, graph::Access::IndirectRead);
}

}  // namespace

uint32_t voxelAtomicsMode(vk::Rung rung) {
    if (rung == vk::Rung::Native) return gpu::kVoxelAtomicsFloatAdd;
    if (rung == vk::Rung::Fallback) return gpu::kVoxelAtomicsUintMax;
    return gpu::kVoxelAtomicsGlRecords;
}

VkExtent3D voxelDepthKeyExtent(uint32_t n, uint32_t depth) { return {n, n, 2 * depth}; }

VoxelAccumulatorImages voxelAccumulatorImages(vk::Rung atomics) {
    const uint32_t mode = voxelAtomicsMode(atomics);
    if (mode == gpu::kVoxelAtomicsGlRecords) return {};
    // r, g, b, the facing's x, y, z, w, and the float-add rung's count (kVoxelAccum*)
    if (mode == gpu::kVoxelAtomicsFloatAdd) return {VK_FORMAT_R32_SFLOAT, 8};
    return {VK_FORMAT_R32_UINT, 7};
}

graph::TextureHandle addVoxelizePasses(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                       const VoxelizeInputs& in, graph::TextureHandle grid,
                                       VxgiDirectionHandles& directions, graph::TextureHandle& cells,
                                       IndirectDrawLog* log) {
    const uint32_t mode = voxelAtomicsMode(in.atomics);
    const uint32_t n = in.box.size;
    const uint32_t slabs = std::max(in.slabs, 1u);
    VxgiGlAccumulator* gl = in.gl;
    if (mode == gpu::kVoxelAtomicsGlRecords && !gl)
        throw std::logic_error("addVoxelizePasses: the gl-interop rung needs VoxelizeInputs::gl");
    if (n % slabs != 0 || (gl && slabs != 1))
        throw std::logic_error("addVoxelizePasses: " + std::to_string(slabs) + " slabs for a grid of " +
                               std::to_string(n) + (gl ? " on the gl-interop rung" : ""));
    const uint32_t depth = n / slabs;
    // The slabs repeat clear, keys, voxelize and merge as graph passes of their own (a suffix " slab k" when
    // there are several), each slab's reusing the first's transient images: the graph sees each rewrite as a new
    // version and plans the barriers between one slab's merge reading them and the next slab's clear (write after
    // read), as it does for any resource written twice in a frame; the merges write the grid, the directions and
    // the cell mask in turn, so they run in slab order. One pass looping over the slabs would have to record the
    // barriers between them itself, which passes never do.
    VoxelSlabImages acc;
    if (in.lists) {
        if (n > 1024) throw std::logic_error("addVoxelizePasses: the touched-voxel lists pack 10 bits per axis");
        acc.list = in.lists->current;
    }
    const uint32_t listBits = in.lists ? (in.lists->currentIndex + 1) << gpu::kVoxelListShift : 0;
    if (gl) {
        acc.records = gl->importRecords(graph);
        acc.sums = gl->importSums(graph);
    }
    const VoxelDraws draws{in.scene, in.frame, in.shadows.table, in.box, in.conservative, in.singleDraw, in.shadowRays};
    const PointShadowOutputs shadows = in.shadows;
    graph::TextureHandle written = grid;
    for (uint32_t slab = 0; slab < slabs; ++slab) {
        const std::string suffix = slabs > 1 ? " slab " + std::to_string(slab) : std::string();
        const VoxelSlab slabInfo{slab, slab * depth, depth, suffix};
        addVoxelClearPass(graph, in, slabInfo, acc);

        constexpr VkPipelineStageFlags2 kFs = VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT;
        // The key pass rasterises the scene a second time, with a fragment shader that evaluates no light (the
        // alpha test only) and does one compare-and-swap. On a GPU that is a depth-prepass-like cost (vertex and
        // raster work again, cheap fragments, atomics in L2), and the accumulating draw then skips the shadow
        // lookups of hidden fragments; lavapipe runs vertex, geometry and fragment work on the same CPU cores, so
        // the second raster costs it about as much as the scene's vertex and setup work (pass_ms.vxgi_voxel_keys).
        // With several slabs every slab draws the whole scene and keeps the fragments of its z range; the scissor
        // and the geometry shaders' cull (recordVoxelDraws) spare most of the other slabs' raster work, so on
        // lavapipe the Cornell box's clear + keys + voxelize + merge took about the same time in 2 slabs as in 1
        // (64^3: 33-36 against 41-45 ms; 128^3: 176-209 against 203-235 ms; 256^3: 917-1017 against 909-974 ms).
        auto keyed = std::make_shared<VoxelSlabImages>();
        graph.addPass(
            "vxgi_voxel_keys" + suffix,
            [&](graph::PassBuilder& b) {
                acc.keys = b.write(acc.keys, graph::Access::StorageReadWrite, kFs);
                readScene(b, draws, false, shadows);
                *keyed = acc;
            },
            [&ctx, &shaders, draws, keyed, log, slabInfo](graph::PassContext& pc) {
                if (draws.scene.drawCount == 0) return;
                gpu::VoxelizePush push{};
                push.depthKeys = pc.texture(keyed->keys).storageIndex;
                recordVoxelDraws(pc, ctx, shaders, draws, vk::ShaderId::vxgi_voxelize_key_frag,
                                 vk::ShaderId::vxgi_voxelize_key_dilated_frag, push, false, log, slabInfo);
            });
        auto voxelized = std::make_shared<VoxelSlabImages>();
        graph.addPass(
            "vxgi_voxelize" + suffix,
            [&](graph::PassBuilder& b) {
                for (uint32_t i = 0; i < acc.count; ++i)
                    acc.images[i] = b.write(acc.images[i], graph::Access::StorageReadWrite, kFs);
                if (acc.records.valid()) acc.records = b.write(acc.records, graph::Access::StorageReadWrite, kFs);
                if (acc.list.valid()) acc.list = b.write(acc.list, graph::Access::StorageReadWrite, kFs);
                b.read(acc.keys, graph::Access::StorageRead, kFs);
                readScene(b, draws, true, shadows);
                *voxelized = acc;
            },
            [&ctx, &shaders, draws, voxelized, mode, log, gl, slabInfo, listBits](graph::PassContext& pc) {
                if (draws.scene.drawCount == 0) return;
                gpu::VoxelizePush push{};
                for (uint32_t i = 0; i < voxelized->count; ++i)
                    push.accum[i] = pc.texture(voxelized->images[i]).storageIndex;
                if (gl) {
                    push.accum[0] = gl->recordsIndex();
                    push.accum[1] = gl->capacity();
                }
                push.depthKeys = pc.texture(voxelized->keys).storageIndex | listBits;  // both below 2^16
                recordVoxelDraws(pc, ctx, shaders, draws, fragmentShader(mode, false), fragmentShader(mode, true),
                                 push, true, log, slabInfo);
            });

        if (gl) acc.sums = gl->addPass(graph, acc.records, acc.sums);

        written = addVoxelMergePass(graph, ctx, shaders, in, slabInfo, acc, written, directions);
    }
    cells = acc.cells;
    return written;
}

}  // namespace idk::passes
