// gpu_animation.cpp: packing the deformed vertex copies and skinning jobs of a scene (pure), the per-frame pose
// (instance transforms, joint matrices, morph weights), and the GpuAnimation buffers that feed the pose_upload and
// skinning passes. Ports the GPU half of IDKEngine's ModelManager.Update (mesh-transform batches, skinning input).
#include "render/gpu_animation.hpp"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>

#include "passes/passes.hpp"
#include "render/gpu_scene.hpp"
#include "vk/context.hpp"
#include "vk/transfer.hpp"

namespace idk::render {
namespace {

template <class T>
vk::Buffer uploadStatic(vk::Context& ctx, const std::vector<T>& values, const char* name) {
    if (values.empty()) return {};
    vk::BufferDesc desc;
    desc.size = values.size() * sizeof(T);
    desc.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    desc.name = name;
    desc.category = "animation";
    return vk::createBufferWithData(ctx, desc, values.data(), desc.size);
}

template <class T>
bool sameBytes(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

template <class T>
size_t bytesOf(const std::vector<T>& v) {
    return v.size() * sizeof(T);
}

}  // namespace

int32_t DeformationData::baseVertex(uint32_t node, uint32_t gpuMesh, int32_t restBase) const {
    auto it = copies.find({node, gpuMesh});
    return it == copies.end() ? restBase : it->second;
}

DeformationData packDeformation(const scene::Scene& scene, const std::vector<uint32_t>& firstMesh,
                                GpuSceneData& out) {
    DeformationData d;
    std::vector<bool> seen(scene.nodes.size(), false);
    for (const scene::Instance& inst : scene.instances) {
        if (inst.mesh >= scene.meshes.size() || inst.node >= scene.nodes.size() || seen[inst.node]) continue;
        seen[inst.node] = true;  // GPU instances of one node share its pose, hence one copy
        const scene::Node& node = scene.nodes[inst.node];
        const scene::Mesh& mesh = scene.meshes[inst.mesh];
        const bool skinnedNode = inst.skin && *inst.skin < scene.skins.size();
        const uint32_t jointCount = skinnedNode ? uint32_t(scene.skins[*inst.skin].joints.size()) : 0;
        uint32_t firstJoint = gpu::kDeformNone, firstWeight = gpu::kDeformNone;
        for (uint32_t p = 0; p < mesh.primitives.size(); ++p) {
            const scene::Primitive& prim = mesh.primitives[p];
            const uint32_t gpuMesh = firstMesh[inst.mesh] + p;
            const gpu::GpuMesh& gm = out.meshes[gpuMesh];
            const auto count = uint32_t(prim.positions.size());
            const bool skinned = skinnedNode && prim.joints.size() == count && prim.weights.size() == count;
            const auto targets = uint32_t(std::min(prim.targets.size(), node.weights.size()));
            if (gm.indexCount == 0 || count == 0 || (!skinned && targets == 0)) continue;

            gpu::GpuDeformJob job{};
            job.srcVertex = uint32_t(gm.baseVertex);
            job.dstVertex = uint32_t(out.vertices.size());
            job.vertexCount = count;
            job.firstThread = d.threadCount;
            job.influences = job.firstJoint = job.deltas = job.firstWeight = gpu::kDeformNone;
            if (skinned) {
                if (firstJoint == gpu::kDeformNone) {
                    firstJoint = d.jointCount;
                    d.jointCount += jointCount;
                    d.skinnedNodes.emplace_back(inst.node, jointCount);
                }
                job.influences = uint32_t(d.influences.size());
                job.firstJoint = firstJoint;
                job.jointCount = jointCount;
                for (uint32_t v = 0; v < count; ++v) {
                    const glm::uvec4 j = glm::min(prim.joints[v], glm::uvec4(255u));  // < kMaxJoints = 256
                    d.influences.push_back({j.x | (j.y << 8) | (j.z << 16) | (j.w << 24), prim.weights[v]});
                }
            }
            if (targets > 0) {
                if (firstWeight == gpu::kDeformNone) {
                    firstWeight = d.weightCount;
                    d.weightCount += uint32_t(node.weights.size());
                    d.morphedNodes.emplace_back(inst.node, uint32_t(node.weights.size()));
                }
                uint32_t attributes = 0;
                for (uint32_t t = 0; t < targets; ++t) {
                    attributes |= prim.targets[t].positions.empty() ? 0u : gpu::kMorphPositions;
                    attributes |= prim.targets[t].normals.empty() ? 0u : gpu::kMorphNormals;
                    attributes |= prim.targets[t].tangents.empty() ? 0u : gpu::kMorphTangents;
                }
                job.deltas = uint32_t(d.deltas.size());
                job.targetCount = targets;
                job.morphAttributes = attributes;
                job.firstWeight = firstWeight;
                for (uint32_t t = 0; t < targets; ++t) {
                    const scene::MorphTarget& target = prim.targets[t];
                    // Bit a of kMorph* is array a: positions, normals, tangents (a target lacking one adds zeros).
                    const std::vector<glm::vec3>* arrays[3] = {&target.positions, &target.normals, &target.tangents};
                    for (uint32_t a = 0; a < 3; ++a) {
                        if (!(attributes & (1u << a))) continue;
                        for (uint32_t v = 0; v < count; ++v)
                            d.deltas.push_back(v < arrays[a]->size() ? (*arrays[a])[v] : glm::vec3(0.0f));
                    }
                }
            }
            // The copy starts as the rest pose (the first frame's skinning pass overwrites it).
            for (uint32_t v = 0; v < count; ++v) {
                const uint32_t src = job.srcVertex + v;
                out.vertices.push_back(gpu::GpuVertex(out.vertices[src]));
                if (!out.colors.empty()) out.colors.push_back(glm::vec4(out.colors[src]));
                if (!out.uv1.empty()) out.uv1.push_back(glm::vec2(out.uv1[src]));
            }
            d.copies[{inst.node, gpuMesh}] = int32_t(job.dstVertex);
            d.threadCount += count;
            d.jobs.push_back(job);
            d.sources.push_back({inst.node, inst.mesh, p});
        }
    }
    return d;
}

PoseData packPose(const scene::Scene& scene, const GpuSceneData& data) {
    const DeformationData& d = data.deformation;
    const auto placed = [&](uint32_t node) { return node < scene.nodes.size(); };
    if (std::any_of(data.drawInstance.begin(), data.drawInstance.end(),
                    [&](uint32_t i) { return i >= scene.instances.size(); }) ||
        !std::all_of(d.skinnedNodes.begin(), d.skinnedNodes.end(), [&](auto& n) { return placed(n.first); }) ||
        !std::all_of(d.morphedNodes.begin(), d.morphedNodes.end(), [&](auto& n) { return placed(n.first); }))
        throw std::invalid_argument("packPose: the scene is not the one the GPU scene was packed from");
    PoseData pose;
    pose.instances.reserve(data.instances.size());
    for (size_t i = 0; i < data.instances.size(); ++i)
        pose.instances.push_back(packInstance(scene.instances[data.drawInstance[i]].world, data.instances[i].mesh));
    pose.joints.reserve(d.jointCount);
    for (const auto& [node, count] : d.skinnedNodes) {
        const std::vector<glm::mat4>& joints = scene.nodes[node].jointMatrices;
        for (uint32_t j = 0; j < count; ++j) pose.joints.emplace_back(j < joints.size() ? joints[j] : glm::mat4(0.0f));
    }
    pose.weights.reserve(d.weightCount);
    for (const auto& [node, count] : d.morphedNodes) {
        const std::vector<float>& weights = scene.nodes[node].weights;
        for (uint32_t w = 0; w < count; ++w) pose.weights.push_back(w < weights.size() ? weights[w] : 0.0f);
    }
    return pose;
}

GpuAnimation::GpuAnimation(vk::Context& ctx, const GpuSceneData& data, const scene::Scene& scene)
    : ctx_(ctx), data_(data), pose_(packPose(scene, data)) {
    jobs_ = uploadStatic(ctx, data.deformation.jobs, "skinning jobs");
    influences_ = uploadStatic(ctx, data.deformation.influences, "skin influences");
    deltas_ = uploadStatic(ctx, data.deformation.deltas, "morph deltas");
    deformDirty_ = !data.deformation.jobs.empty();
}

GpuAnimation::~GpuAnimation() {
    for (vk::Buffer* b : {&jobs_, &influences_, &deltas_})
        if (*b) ctx_.destroyDeferred(*b);
    for (vk::Buffer& b : poseSlots_)
        if (b) ctx_.destroyDeferred(b);
}

const DeformationData& GpuAnimation::deformation() const noexcept { return data_.deformation; }

void GpuAnimation::setPose(const scene::Scene& scene) {
    PoseData pose = packPose(scene, data_);
    instancesDirty_ = instancesDirty_ || !sameBytes(pose.instances, pose_.instances);
    deformDirty_ = deformDirty_ || !sameBytes(pose.joints, pose_.joints) || !sameBytes(pose.weights, pose_.weights);
    pose_ = std::move(pose);
}

void GpuAnimation::addPasses(graph::RenderGraph& graph, vk::ShaderLibrary& shaders, uint32_t slot, uint32_t slots,
                             passes::SceneBuffers& sb) {
    const bool upload = instancesDirty_ && sb.instances.valid() && !pose_.instances.empty();
    const bool deform = deformDirty_ && sb.vertices.valid() && !data_.deformation.jobs.empty();
    instancesDirty_ = deformDirty_ = false;
    if (!upload && !deform) return;

    // This slot's buffer: FrameRing::begin() has waited until the GPU finished the slot's previous frame.
    poseSlots_.resize(std::max<size_t>(poseSlots_.size(), slots));
    vk::Buffer& buffer = poseSlots_[slot];
    const size_t instanceBytes = bytesOf(pose_.instances), jointBytes = bytesOf(pose_.joints);
    const size_t total = instanceBytes + jointBytes + bytesOf(pose_.weights);
    if (!buffer) {
        vk::BufferDesc desc;
        desc.size = total;
        desc.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
        desc.memory = vk::MemoryUsage::Upload;
        desc.name = "animation pose " + std::to_string(slot);
        desc.category = "animation";
        buffer = ctx_.createBuffer(desc);
    }
    // Host-visible: memcpys, made visible to the GPU by the frame's queue submission.
    vk::uploadBuffer(ctx_, buffer, pose_.instances.data(), instanceBytes, 0);
    if (jointBytes) vk::uploadBuffer(ctx_, buffer, pose_.joints.data(), jointBytes, instanceBytes);
    if (!pose_.weights.empty())
        vk::uploadBuffer(ctx_, buffer, pose_.weights.data(), bytesOf(pose_.weights), instanceBytes + jointBytes);
    passes::AnimationFrame frame;
    frame.pose = &buffer;
    frame.instanceBytes = upload ? instanceBytes : 0;
    frame.jointsOffset = jointBytes ? instanceBytes : passes::AnimationFrame::kAbsent;
    frame.weightsOffset = pose_.weights.empty() ? passes::AnimationFrame::kAbsent : instanceBytes + jointBytes;
    frame.deform = deform;
    frame.jobs = &jobs_;
    frame.influences = &influences_;
    frame.deltas = &deltas_;
    frame.jobCount = uint32_t(data_.deformation.jobs.size());
    frame.threadCount = data_.deformation.threadCount;
    passes::addAnimationPasses(graph, ctx_, shaders, frame, sb);
}

}  // namespace idk::render
