// culling_feature.hpp: GPU culling of the scene's draws (issue 10) and the G-buffer drawn from it. Per view, a
// compute pass tests every draw's world box and compacts the survivors into the commands that
// vkCmdDrawIndexedIndirectCount draws (passes/cull.cpp). Hiz adds two-phase occlusion culling (niagara's
// approach): the early phase draws what was visible last frame, the Hi-Z pyramid of that depth is built, the late
// phase tests every draw against it, records the result as next frame's visibility and draws what the early phase
// missed. The first frame (no visibility yet) and camera cuts stay exact: whatever the early phase misses, the
// late phase finds, because the early depth is never nearer than the final one. The per-draw records, visibility
// bits, view planes and stats readback exist only while culling is on. Fills FrameContext::gbuffer,
// depthPyramid and cameraDraws. On the mesh-shading ladder's native rung the culled instances are drawn as
// meshlets (render/meshlets.hpp, built at the first culled frame), which the task shader culls again (frustum,
// normal cone, Hi-Z in the late phase) with the two phases per meshlet: one bit per meshlet persists, the early
// phase draws the meshlets visible last frame, the late phase tests the rest; the MDI rung draws whole instances. Ports IDKEngine's GPU culling
// (reference 2.6, 2.7) without its single-phase previous-frame Hi-Z (which could drop newly visible objects).
// The Hi-Z pyramid is reduced by a MAX sampler where the ladder "hiz-reduction" allows it, else in compute.
// --geometry mesh|mdi picks the rung instead of the ladder; meshlets exist only while the mesh path is used.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "frame/frame_context.hpp"
#include "frame/hiz_levels.hpp"
#include "render/gpu_scene.hpp"

namespace idk::frame {

class CullingFeature {
public:
    explicit CullingFeature(vk::Context& ctx) : ctx_(ctx) {}
    ~CullingFeature();
    CullingFeature(const CullingFeature&) = delete;
    CullingFeature& operator=(const CullingFeature&) = delete;

    void setScene();  // a new scene: its records and visibility are rebuilt at the first culled frame
    // The G-buffer of the camera view: every draw (culling off), the frustum's survivors, or the two phases of
    // occlusion culling. Also declares f.depthPyramid (of the final depth; built only if a later pass reads it).
    passes::GBufferOutputs addGBuffer(FrameContext& f, const render::GpuScene& scene);
    // The counters of the last frame that culled, per view (empty when it did not cull); with Hiz the two phases
    // are summed (instancesTested counts each draw once). Valid once that frame's GPU work has finished.
    std::vector<passes::CullingViewStats> lastStats() const;
    // The geometry path the last frame's camera G-buffer took: "mesh" (task + mesh shaders), "mdi"
    // (vkCmdDrawIndexedIndirectCount of the culled instances) or "indirect" (culling off: every instance).
    const char* lastGeometryPath() const noexcept { return lastGeometry_; }
    // The per-draw visibility bits (uint per scene draw: what the last late phase found visible; empty before the
    // first culled frame). Valid once that frame's GPU work has finished (tests and benchmarks read them).
    std::vector<uint32_t> visibilityBits() const;
    // The mesh rung's per-meshlet visibility bits (GpuCullDraw::meshletVisibilityWord addresses each draw's words;
    // what the last late phase's task shaders found visible; empty off the mesh rung). Valid as visibilityBits.
    std::vector<uint32_t> meshletVisibilityBits() const;
    // Conformance (the task shader's oracle needs the pyramid its late phase read): while on, each Hiz frame copies
    // its early phase's Hi-Z pyramid to the host; earlyPyramid() returns the last one (valid as visibilityBits).
    void capturePyramid(bool on) { capturePyramid_ = on; }
    std::vector<float> earlyPyramid() const;

    // Whether the culled G-buffer draws meshlets with mesh shaders under `settings` (--geometry; auto: the
    // "mesh-shading" ladder). --geometry mesh on a device without VK_EXT_mesh_shader draws MDI: callers that take
    // the setting from a user check geometryError first.
    static bool usesMeshShaders(const vk::Context& ctx, const CullingSettings& settings);
    // Why `settings` cannot run as asked on this device (empty when it can): --geometry mesh without
    // VK_EXT_mesh_shader, or --geometry mesh|mdi with culling off (both paths draw culled commands).
    static std::string geometryError(const vk::Context& ctx, const CullingSettings& settings);

private:
    void createResources(const render::GpuScene& scene, uint32_t framesInFlight, bool meshRung);
    void release();
    void capture(FrameContext& f, graph::BufferHandle pyramid);  // capturePyramid: copy it to the host
    vk::Context& ctx_;
    vk::Buffer draws_;                       // GpuCullDraw per scene draw (static)
    vk::Buffer visibility_;                  // uint per scene draw: drawn last frame (Hiz)
    bool meshRung_ = false;                  // meshlets and the mesh-shader G-buffer (ladder "mesh-shading")
    vk::Buffer meshlets_, meshletIndices_;   // render::MeshletData (mesh rung only)
    vk::Buffer meshletVisibility_;           // mesh rung: one bit per meshlet of each draw, drawn last frame (Hiz)
    uint32_t meshletWords_ = 0;              // words in meshletVisibility_
    bool capturePyramid_ = false;
    vk::Buffer capturedPyramid_;             // host-visible copy of the last early pyramid (capturePyramid only)
    uint32_t capturedFloats_ = 0;
    std::vector<vk::Buffer> views_, stats_;  // per frame slot, host-visible: GpuCullView[], GpuCullCounters[]
    uint32_t lastSlot_ = 0;
    uint32_t lastPhases_ = 0;                // counters the last culled frame wrote (0: it did not cull)
    const char* lastGeometry_ = "indirect";
    uint32_t drawCount_ = 0;                 // records in draws_ / visibility_
    std::optional<gpu::GpuCullView> frozen_;  // CullingSettings::freeze: the view culling keeps using
    HizLevels hizLevels_{ctx_};  // the sampler rung of the ladder "hiz-reduction" (empty on the compute rung)
};

}  // namespace idk::frame
