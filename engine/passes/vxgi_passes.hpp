// vxgi_passes.hpp: the passes of voxel global illumination (engine/frame/vxgi_feature.hpp drives them).
#pragma once
#include <optional>
#include <glm/glm.hpp>

#include <array>
#include <string>
#include <vector>

#include "passes/passes.hpp"
#include "vk/features.hpp"

namespace idk::passes {

class VxgiGlAccumulator;  // vxgi_gl_accumulate.hpp

// The grid's cube in world space: gridMin + [0, size * voxelSize]^3.
struct VoxelGridBox {
    glm::vec3 gridMin{0.0f};
    float voxelSize = 1.0f;
    uint32_t size = 64;
};

// --shadows raytraced: the BVH the voxelization's shadow rays walk (frame/rt_shadow_feature.hpp builds it), and
// how many of the lights of nonzero intensity cast (render::shadowCasters).
struct VoxelShadowRays {
    uint64_t sceneDesc = 0;  // GpuPtSceneDesc
    uint32_t casters = 0;
    uint32_t blasStack = 32, tlasStack = 32;  // the traversal's stack sizes (specialization constants)
    bool hasAlpha = false;                   // alpha-tested or blended materials: opacity tested along the ray
};

// vxgi_voxelize.cpp (vxgi_merge.cpp the clear and the merge): "vxgi_clear" zeroes the write-conflict accumulators
// (transient 3D images of the atomic rung's formats) and the depth keys, "vxgi_voxel_keys" rasterizes the scene three times (one orthographic projection per
// axis; each triangle keeps the fragments of its dominant axis) and raises each voxel's depth key per facing class
// (its front-most surface: shared/vxgi_depth_key.h), "vxgi_voxelize" rasterizes it again and adds the outgoing
// diffuse radiance of every fragment within tolerance of its key to its voxel,
// "vxgi_merge" resolves them into `grid` (RGBA16F, size^3, mip 0) and into level 0 of the six directional volumes
// (`directions`, updated to their new versions), storing only the voxels that changed from or to empty unless
// `fullMerge`, and marks the level-1 cells holding an occupied voxel in `cells` (a transient R32UI mask the level-1
// mip reads: voxelCellMaskDesc). Returns the grid's new version.
struct VoxelizeInputs {
    SceneBuffers scene;
    graph::BufferHandle frame;
    PointShadowOutputs shadows;
    VoxelGridBox box;
    vk::Rung atomics = vk::Rung::Native;  // ladder "vxgi-atomics": Native float add, Fallback r32ui max,
                                          // GlInterop records added by GL ("vxgi_gl_accumulate" before the merge)
    VxgiGlAccumulator* gl = nullptr;      // the GlInterop rung's shared buffers (prepared for box.size)
    // Ladder "conservative-raster": Native VK_EXT_conservative_rasterization, Fallback geometry-shader dilation;
    // none: pixel-centre rasterization (thin voxelization).
    std::optional<vk::Rung> conservative;
    VxgiDirectionIndices directionLevel0{};  // storage indices of the directional volumes' level-0 views
    // The grid and the directional volumes are new (contents undefined): the merge stores every voxel. Otherwise it
    // skips the empty voxels the previous frames left zero (merge.comp.glsl), and reads the grid to know which.
    bool fullMerge = true;
    std::optional<VoxelShadowRays> shadowRays;  // --shadows raytraced (then `shadows` has no table yet)
    // Set: one draw, each triangle projected along its dominant axis by ladder "voxel-single-draw"'s rung: Native
    // a passthrough geometry shader picking a swizzled viewport (vxgi_axis_swizzle.hpp), Fallback a geometry
    // shader re-emitting it (the dilation fallback of "conservative-raster" projects by itself). Unset: three draws.
    std::optional<vk::Rung> singleDraw;
    // The accumulators and keys cover one z-slab of size / slabs voxels; the passes from the clear to the merge run
    // once per slab (frame/vxgi_memory.hpp chooses the count from the memory budget). 1 on the gl-interop rung.
    uint32_t slabs = 1;
    // The merge's touched-voxel lists (persistent buffers of voxelListBytes, vxgi_merge.cpp): `current`, which the
    // accumulating draws fill this frame, and the previous frame's (invalid where there is none: the grid is new).
    // Unset: the merge visits every voxel (the gl-interop rung: its GL side keeps no first-touch mark).
    struct Lists {
        graph::BufferHandle current, previous;
        uint32_t currentIndex = 0, previousIndex = 0;  // their bindless storage-buffer indices
    };
    std::optional<Lists> lists;
};
// The bytes of one touched-voxel list of an n^3 grid: a 16-byte header and 16 n^2 - 4 entries of 4 bytes, 64 n^2
// bytes in all (a multiple of 64 KiB from n = 32: its allocation is its size). The bound holds the voxels of
// surfaces the size of 16 of the grid's cross-sections (a closed room at 64^3, its six walls 2-3 voxels thick, fills
// about 40%): 4 MiB at 256^3, 16 MiB at 512^3. A frame touching more visits every voxel in its merge.
VkDeviceSize voxelListBytes(uint32_t n);
// The write-conflict accumulators "vxgi_clear" creates for a rung of "vxgi-atomics" (transient 3D images of one
// slab of the grid, size x size x size / slabs, all live at once): Native 8 x R32F (r g b, facing xyzw, count),
// Fallback 7 x R32UI, GlInterop none (its shared buffers instead). The memory check (frame/vxgi_memory.hpp) sizes them from this too.
struct VoxelAccumulatorImages {
    VkFormat format = VK_FORMAT_UNDEFINED;
    uint32_t count = 0;
};
VoxelAccumulatorImages voxelAccumulatorImages(vk::Rung atomics);
// The cell mask of a grid of n^3 voxels: R32UI, (n / 2)^3 (one texel per level-1 cell), transient, on every rung.
// (R32UI rather than R8UI: storage images of 8-bit formats need shaderStorageImageExtendedFormats.)
inline constexpr VkFormat kVoxelCellMaskFormat = VK_FORMAT_R32_UINT;
inline uint32_t voxelCellMaskSize(uint32_t n) { return n > 1 ? n / 2 : 1; }
// The front-most rule's depth keys of a slab of n x n x depth voxels (shared/vxgi_depth_key.h,
// include/voxelize_key.glsl): R32UI, n x n x (2 depth) (two words per voxel: facing sign + and -), transient, on
// every rung; 8 bytes per voxel. Its z extent is the only one above n: the slab count keeps it within the device's
// maxImageDimension3D (frame/vxgi_memory.hpp).
inline constexpr VkFormat kVoxelDepthKeyFormat = VK_FORMAT_R32_UINT;
VkExtent3D voxelDepthKeyExtent(uint32_t n, uint32_t depth);

graph::TextureHandle addVoxelizePasses(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                       const VoxelizeInputs& inputs, graph::TextureHandle grid,
                                       VxgiDirectionHandles& directions, graph::TextureHandle& cells,
                                       IndirectDrawLog* log);

// addVoxelizePasses' parts. The rung's kVoxelAtomics* mode (push `mode` of the voxelize and merge shaders).
uint32_t voxelAtomicsMode(vk::Rung atomics);
// One z-slab: voxels [z, z + depth) of the grid; `suffix` names its passes (" slab k" when there are several).
struct VoxelSlab {
    uint32_t index = 0, z = 0, depth = 0;
    std::string suffix;
};
// The transient resources the passes of a slab hand on (their current graph versions): the accumulators
// (`count` images of voxelAccumulatorImages), the depth keys, the cell mask, and on the gl-interop rung the shared
// record and sums buffers instead of images. The first slab's clear creates them, the later slabs' reuse them.
struct VoxelSlabImages {
    graph::TextureHandle images[8];
    graph::TextureHandle cells;
    graph::TextureHandle keys;
    uint32_t count = 0;
    graph::BufferHandle records, sums;
    graph::BufferHandle list;  // this frame's touched-voxel list (VoxelizeInputs::lists)
};
// vxgi_merge.cpp: "vxgi_clear" of `slab` (zeroes `acc`; the first slab creates its images and the cell mask, and
// empties inputs.lists->current), and "vxgi_merge" of `slab` (with lists after "vxgi_merge_args", its indirect
// dispatch; reads `acc`, writes `grid`, `directions` and acc.cells; returns the grid's new version).
void addVoxelClearPass(graph::RenderGraph& graph, const VoxelizeInputs& inputs, const VoxelSlab& slab,
                       VoxelSlabImages& acc);
graph::TextureHandle addVoxelMergePass(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                       const VoxelizeInputs& inputs, const VoxelSlab& slab, VoxelSlabImages& acc,
                                       graph::TextureHandle grid, VxgiDirectionHandles& directions);

// vxgi_cone_trace.cpp: "vxgi_mip L" (one pass per level L >= 1 of the six directional volumes, each from the
// level below; the voxelization's merge wrote level 0), then "vxgi_cone_trace": per G-buffer pixel inside the grid,
// diffuse irradiance from a cosine-weighted cone set and the reflection cone's radiance (transient RGBA16F, render
// resolution). With `halfResolution` the trace runs on half of it (rounded up), "vxgi_upsample"
// (addVxgiUpsamplePass) brings it to render resolution and "vxgi_cone_trace_fixup" traces the pixels the upsample
// found no sample of their surface for.
struct ConeTraceInputs {
    GBufferOutputs gbuffer;
    graph::BufferHandle frame;
    graph::TextureHandle environment;
    graph::TextureHandle grid;           // after the voxelization (level 0 only)
    uint32_t gridStorage = 0, gridSampled = 0;
    // Anisotropic volumes, one per direction (+x -x +y -y +z -z; colour then opacity, VxgiDirectionHandles),
    // levels 0 (the merge's) to log2(size): the frame's handles, their sampled indices, and the storage index of
    // each level's view per image.
    VxgiDirectionHandles directions;
    VxgiDirectionIndices directionSampled{};
    std::vector<VxgiDirectionIndices> directionLevels;
    uint32_t gridSampler = 0;            // bindless sampler: trilinear, clamp to edge
    graph::TextureHandle cells;          // the merge's cell mask (addVoxelizePasses): the level-1 mip skips its zeros
    VoxelGridBox box;
    uint32_t ringCones = 5;
    uint32_t footprintCones = 4;  // narrower cones per diffuse cone (frame::VxgiSettings::footprintCones)
    float stepFactor = 0.5f;
    bool halfResolution = false;
    VxgiDirectionHandles* mipped = nullptr;  // if set: the directional volumes after the mip passes
};
IndirectLightImages addConeTracePasses(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                       const ConeTraceInputs& inputs);

// vxgi_upsample.cpp: "vxgi_upsample": the half-resolution cone trace to render resolution, joint-bilateral on the
// G-buffer's depth and normals (shaders_glsl/vxgi/upsample.comp.glsl), in the cone trace's output layout; diffuse
// alpha -1 marks the pixels left for the fix-up trace.
struct VxgiUpsampleInputs {
    GBufferOutputs gbuffer;
    graph::BufferHandle frame;
    IndirectLightImages traced;  // half resolution (addConeTracePasses with halfResolution)
    VoxelGridBox box;
};
IndirectLightImages addVxgiUpsamplePass(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                        const VxgiUpsampleInputs& inputs);

// vxgi_debug_view.cpp: "vxgi_debug_voxels" (--gi-debug voxels) overwrites `target` (the final HDR colour, RGBA16F
// storage) with the radiance of the first cell of `level` each pixel's camera ray meets with coverage above
// kVxgiDebugCoverage (shared/vxgi_debug_types.h), alpha the distance to the middle of the ray's stretch in it;
// black, alpha 0, where it meets none. Returns its new version.
struct VxgiDebugViewInputs {
    graph::BufferHandle frame;
    graph::TextureHandle target;
    graph::TextureHandle grid;                        // level 0 (read when level == 0)
    VxgiDirectionHandles directions;                  // after the mips (read when level >= 1)
    VxgiDirectionIndices volumeStorage{};             // storage indices of `level`: [0] the grid's for level 0
    uint32_t level = 0;
    VoxelGridBox box;
};
graph::TextureHandle addVxgiDebugViewPass(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                          const VxgiDebugViewInputs& inputs);

}  // namespace idk::passes
