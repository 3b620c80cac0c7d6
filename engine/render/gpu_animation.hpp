// gpu_animation.hpp: GPU animation data. Every skinned or morphed (node, primitive) gets a deformed copy of its
// vertices in the merged vertex buffer (its draws use it) plus static inputs (joint influences, morph deltas, jobs);
// each frame's pose goes to a per-frame-in-flight host-visible buffer for the pose_upload and skinning passes.
// Ports IDKEngine's ModelManager.Update GPU work (reference 1.5 step 5); nothing exists for a scene without skins,
// morphs or animations.
#pragma once
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "graph/render_graph.hpp"
#include "scene/scene.hpp"
#include "shared/scene_types.h"
#include "shared/skinning_types.h"
#include "vk/resources.hpp"

namespace idk::vk {
class Context;
class ShaderLibrary;
}  // namespace idk::vk
namespace idk::passes {
struct SceneBuffers;
}

namespace idk::render {

struct GpuSceneData;

// What packDeformation() adds to the packed scene (pure CPU data).
struct DeformationData {
    struct Source {
        uint32_t node = 0;       // Scene::nodes index (its joint matrices and morph weights drive the job)
        uint32_t mesh = 0;       // Scene::meshes index
        uint32_t primitive = 0;  // index in that mesh
    };
    std::vector<gpu::GpuDeformJob> jobs;  // sorted by firstThread (= packing order)
    std::vector<Source> sources;          // per job
    std::vector<gpu::GpuSkinInfluence> influences;
    std::vector<glm::vec3> deltas;                             // [job][target][attribute][vertex]
    std::vector<std::pair<uint32_t, uint32_t>> skinnedNodes;   // (node, joint count) in pose joint order
    std::vector<std::pair<uint32_t, uint32_t>> morphedNodes;   // (node, weight count) in pose weight order
    std::map<std::pair<uint32_t, uint32_t>, int32_t> copies;   // (node, GpuMesh index) -> deformed baseVertex
    uint32_t jointCount = 0;                                   // joint matrices in a pose
    uint32_t weightCount = 0;                                  // morph weights in a pose
    uint32_t threadCount = 0;                                  // deformed vertices (one invocation each)

    // The baseVertex a draw of GpuMesh `gpuMesh` placed by `node` uses: its deformed copy, else `restBase`.
    int32_t baseVertex(uint32_t node, uint32_t gpuMesh, int32_t restBase) const;
};

// Appends a deformed copy of every skinned (instance skin + JOINTS_0) or morphed (targets + node weights)
// (node, primitive) with draws to out.vertices and the optional colour/uv1 streams (copies start as the rest
// pose), and returns the jobs. Several instances of one node share one copy. `firstMesh[m]`: the GpuMesh of
// mesh m's primitive 0. Called by packGpuScene before the instances are packed.
DeformationData packDeformation(const scene::Scene& scene, const std::vector<uint32_t>& firstMesh,
                                GpuSceneData& out);

// One frame's pose: per-draw instances (transforms), joint matrices (mat4x3, in skinnedNodes order) and morph
// weights (in morphedNodes order) of the scene as it is posed now.
struct PoseData {
    std::vector<gpu::GpuInstance> instances;
    std::vector<glm::mat4x3> joints;
    std::vector<float> weights;
};
// Throws std::invalid_argument for a scene that cannot be the one `data` was packed from (indices out of range).
PoseData packPose(const scene::Scene& scene, const GpuSceneData& data);

class GpuAnimation {
public:
    // Uploads the static skinning inputs (memory category "animation") and takes the scene's current pose.
    // `data` (the GpuScene's packed arrays) must outlive this object.
    GpuAnimation(vk::Context& ctx, const GpuSceneData& data, const scene::Scene& scene);
    ~GpuAnimation();
    GpuAnimation(const GpuAnimation&) = delete;
    GpuAnimation& operator=(const GpuAnimation&) = delete;

    // Takes the scene's current pose (after scene::evaluateAnimations); it reaches the GPU in the next frame.
    // Only what changed is redone: pose_upload when a transform moved, skinning when joints or weights did.
    void setPose(const scene::Scene& scene);

    // In frame slot `slot` (of `slots` in flight): writes the pending pose into the slot's host-visible buffer
    // and adds pose_upload (-> sb.instances) and skinning (-> sb.vertices) when needed, replacing those handles
    // with their new versions. Call before any pass that reads vertices or instances.
    void addPasses(graph::RenderGraph& graph, vk::ShaderLibrary& shaders, uint32_t slot, uint32_t slots,
                   passes::SceneBuffers& sb);

    const DeformationData& deformation() const noexcept;

private:
    vk::Context& ctx_;
    const GpuSceneData& data_;
    vk::Buffer jobs_, influences_, deltas_;
    std::vector<vk::Buffer> poseSlots_;  // [instances | joints | weights], one per frame in flight
    PoseData pose_;
    bool instancesDirty_ = false, deformDirty_ = true;  // the first frame deforms (the copies hold the rest pose)
};

}  // namespace idk::render
