// skinning_test.cpp: the skinning pass vs the CPU reference scene::deformedPosition (SimpleSkin, Fox, AnimatedMorph-
// Cube, SimpleMorph; several times and clips): placed by the draw's model matrix, |gpu - cpu| <= 1e-4 * max(1, |cpu|)
// (absolute below unit length, relative above: Fox is in cm); normals/tangents vs a CPU port of the shader math
// within 1e-3. Also: draws use the deformed copies, pose_upload moves rigid nodes (InterpolationTest), an unchanged
// pose is not re-skinned. Tests engine/passes/skinning.cpp (IDKEngine: Skinning/compute.glsl).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "render/gpu_scene.hpp"
#include "render/renderer.hpp"
#include "scene/animation.hpp"
#include "scene/gltf_loader.hpp"
#include "support/gpu_fixture.hpp"
#include "vk/transfer.hpp"

namespace idk::test {
namespace {

struct Pose {
    double time;
    int animation;  // -1: all
};

struct Case {
    const char* name;
    const char* path;  // under ../shared/scenes
    std::vector<Pose> poses;
    bool skinned, morphed;
};

const Case kCases[] = {
    {"SimpleSkin", "SimpleSkin/glTF/SimpleSkin.gltf", {{0.0, -1}, {1.7, -1}, {3.25, -1}, {4.6, -1}}, true, false},
    {"Fox", "Fox/glTF-Binary/Fox.glb", {{1.25, 0}, {0.4, 1}, {0.6, 2}, {2.9, -1}}, true, false},
    {"AnimatedMorphCube", "AnimatedMorphCube/glTF-Binary/AnimatedMorphCube.glb", {{0.8, -1}, {2.0, -1}, {3.3, -1}},
     false, true},
    {"SimpleMorph", "SimpleMorph/glTF/SimpleMorph.gltf", {{0.5, -1}, {1.5, -1}, {3.2, -1}}, false, true},
};

void PrintTo(const Case& c, std::ostream* os) { *os << c.name; }

scene::Scene load(const std::string& path) { return scene::loadGltf(std::string(IDK_SHARED_DIR) + "/scenes/" + path); }

glm::vec3 normalizedOr(glm::vec3 v, glm::vec3 fallback) {
    float len = glm::length(v);
    return len > 0.0f ? v / len : fallback;
}

// The shader's normal and tangent math on the CPU (object space): morph deltas, then the skin matrix's cofactor
// (normals) or the matrix itself (tangents), renormalised.
std::pair<glm::vec3, glm::vec3> cpuNormalTangent(const scene::Node& node, const scene::Primitive& prim, uint32_t v) {
    glm::vec3 n = prim.normals[v], t = prim.tangents.empty() ? glm::vec3(0.0f) : glm::vec3(prim.tangents[v]);
    for (size_t k = 0; k < prim.targets.size() && k < node.weights.size(); ++k) {
        if (!prim.targets[k].normals.empty()) n += node.weights[k] * prim.targets[k].normals[v];
        if (!prim.targets[k].tangents.empty()) t += node.weights[k] * prim.targets[k].tangents[v];
    }
    if (node.skin && !prim.joints.empty()) {
        glm::mat3 m(0.0f);
        for (int c = 0; c < 4; ++c)
            if (prim.joints[v][c] < node.jointMatrices.size())
                m += prim.weights[v][c] * glm::mat3(node.jointMatrices[prim.joints[v][c]]);
        glm::mat3 cof(glm::cross(m[1], m[2]), glm::cross(m[2], m[0]), glm::cross(m[0], m[1]));
        n = cof * n * (glm::determinant(m) < 0.0f ? -1.0f : 1.0f);
        t = m * t;
    }
    return {normalizedOr(n, prim.normals[v]), prim.tangents.empty() ? t : normalizedOr(t, glm::vec3(prim.tangents[v]))};
}

class SkinningTest : public GpuTest, public ::testing::WithParamInterface<Case> {};

TEST_P(SkinningTest, GpuDeformedVerticesMatchTheCpuReference) {
    const Case& c = GetParam();
    scene::Scene scene = load(c.path);
    render::RenderSettings settings;
    settings.environmentIntensity = 0.0f;  // the frame only carries the skinning pass here
    render::Renderer renderer(ctx(), shaders(), settings);
    renderer.setScene(scene);
    render::GpuScene& gpu = *renderer.gpuScene();
    ASSERT_NE(gpu.animation(), nullptr);
    const render::GpuSceneData& data = gpu.data();
    const render::DeformationData& d = data.deformation;
    ASSERT_FALSE(d.jobs.empty());
    EXPECT_EQ(!d.influences.empty(), c.skinned);
    EXPECT_EQ(!d.deltas.empty(), c.morphed);

    // Every draw of a deformed (node, primitive) uses its copy.
    for (size_t i = 0; i < data.draws.size(); ++i) {
        const scene::Instance& inst = scene.instances[data.drawInstance[i]];
        const int32_t rest = data.meshes[data.instances[i].mesh].baseVertex;
        EXPECT_EQ(data.draws[i].vertexOffset, d.baseVertex(inst.node, data.instances[i].mesh, rest));
    }

    scene::CameraView camera = scene::defaultCamera(scene);
    for (const Pose& pose : c.poses) {
        scene::evaluateAnimations(scene, pose.time, pose.animation);
        renderer.setPose(scene);
        render::FrameResult frame = renderer.renderOffscreen(camera, 8, 8);
        EXPECT_NE(std::find(frame.passesRun.begin(), frame.passesRun.end(), "skinning"), frame.passesRun.end());
        std::vector<gpu::GpuVertex> vertices =
            vk::downloadBuffer<gpu::GpuVertex>(ctx(), gpu.vertices(), data.vertices.size());

        double worstPosition = 0.0, worstNormal = 0.0, moved = 0.0;
        for (size_t j = 0; j < d.jobs.size(); ++j) {
            const gpu::GpuDeformJob& job = d.jobs[j];
            const render::DeformationData::Source& src = d.sources[j];
            const scene::Primitive& prim = scene.meshes[src.mesh].primitives[src.primitive];
            const auto inst = std::find_if(scene.instances.begin(), scene.instances.end(),
                                           [&](const scene::Instance& i) { return i.node == src.node; });
            ASSERT_NE(inst, scene.instances.end());
            for (uint32_t v = 0; v < job.vertexCount; ++v) {
                const gpu::GpuVertex& g = vertices[job.dstVertex + v];
                glm::vec3 expected = scene::deformedPosition(scene, *inst, prim, v);
                glm::vec3 actual = glm::vec3(inst->world * glm::vec4(g.position, 1.0f));
                double err = glm::length(actual - expected) / std::max(1.0f, glm::length(expected));
                worstPosition = std::max(worstPosition, err);
                moved = std::max(moved, double(glm::length(g.position - prim.positions[v])));
                auto [n, t] = cpuNormalTangent(scene.nodes[src.node], prim, v);
                worstNormal = std::max(worstNormal, double(glm::length(g.normal - n)));
                if (!prim.tangents.empty())
                    worstNormal = std::max(worstNormal, double(glm::length(glm::vec3(g.tangent) - t)));
            }
        }
        std::printf("%s t=%.2f anim %d: worst position error %.2e (relative), normal/tangent %.2e\n", c.name,
                    pose.time, pose.animation, worstPosition, worstNormal);
        EXPECT_LE(worstPosition, 1e-4) << c.name << " at t = " << pose.time << " (animation " << pose.animation << ")";
        EXPECT_LE(worstNormal, 1e-3) << c.name << " at t = " << pose.time;
        if (pose.time > 0.5) {
            EXPECT_GT(moved, 1e-3) << c.name << ": the pose at t = " << pose.time << " is the rest pose";
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Assets, SkinningTest, ::testing::ValuesIn(kCases),
                         [](const ::testing::TestParamInfo<Case>& info) { return std::string(info.param.name); });

class AnimationPassesTest : public GpuTest {};

TEST_F(AnimationPassesTest, UnchangedPoseIsNotSkinnedAgainAndRigidAnimationMovesInstances) {
    scene::Scene fox = load("Fox/glTF-Binary/Fox.glb");
    render::Renderer renderer(ctx(), shaders());
    renderer.setScene(fox);
    scene::CameraView camera = scene::defaultCamera(fox);
    auto has = [](const render::FrameResult& f, const char* pass) {
        return std::find(f.passesRun.begin(), f.passesRun.end(), pass) != f.passesRun.end();
    };
    render::FrameResult first = renderer.renderOffscreen(camera, 8, 8);
    EXPECT_TRUE(has(first, "skinning"));
    EXPECT_FALSE(has(first, "pose_upload")) << "Fox's mesh node does not move";
    EXPECT_FALSE(has(renderer.renderOffscreen(camera, 8, 8), "skinning")) << "same pose: nothing to redo";
    scene::evaluateAnimations(fox, 0.5, 2);
    renderer.setPose(fox);
    EXPECT_TRUE(has(renderer.renderOffscreen(camera, 8, 8), "skinning"));

    // InterpolationTest: rigid TRS animation only: pose_upload, no skinning, instance transforms follow the nodes.
    scene::Scene interp = load("InterpolationTest/glTF-Binary/InterpolationTest.glb");
    render::Renderer rigid(ctx(), shaders());
    rigid.setScene(interp);
    ASSERT_NE(rigid.gpuScene()->animation(), nullptr);
    EXPECT_TRUE(rigid.gpuScene()->data().deformation.jobs.empty());
    scene::evaluateAnimations(interp, 0.7);
    rigid.setPose(interp);
    render::FrameResult frame = rigid.renderOffscreen(scene::defaultCamera(interp), 8, 8);
    EXPECT_TRUE(has(frame, "pose_upload"));
    EXPECT_FALSE(has(frame, "skinning"));
    const render::GpuSceneData& data = rigid.gpuScene()->data();
    std::vector<gpu::GpuInstance> instances =
        vk::downloadBuffer<gpu::GpuInstance>(ctx(), rigid.gpuScene()->instances(), data.instances.size());
    bool anyMoved = false;
    for (size_t i = 0; i < instances.size(); ++i) {
        const glm::mat4& world = interp.instances[data.drawInstance[i]].world;
        EXPECT_EQ(instances[i].model, world) << "draw " << i;
        anyMoved = anyMoved || instances[i].model != data.instances[i].model;
    }
    EXPECT_TRUE(anyMoved) << "t = 0.7 should move some InterpolationTest node";
}

}  // namespace
}  // namespace idk::test
