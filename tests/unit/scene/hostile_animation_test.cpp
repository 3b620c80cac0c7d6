// hostile_animation_test.cpp: bad skins, animations and geometry values: NaN/infinite positions, too many joints,
// joint indices past the skin, sampler and node indices out of range, input/output count mismatches, times not
// increasing, zero-scale nodes, random mutations of animated assets. Each is a LoadError naming the file and the
// cause, or the warning and substitute gltf_loader.hpp documents; never a crash.
#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "scene/animation.hpp"
#include "scene/gltf_loader.hpp"
#include "test_files.hpp"
#include "test_gltf.hpp"

namespace idk::scene {
namespace {

using test::expectLoadError;
using test::GltfFile;
using test::json;
using test::TempDir;

// The base triangle, skinned to joint node 1 (IBM identity) and animated: node 1 moves along +X, x = t for
// keys at 0, 1, 2 s.
GltfFile skinnedTriangle() {
    GltfFile f = test::triangle();
    const size_t joints = f.append(std::vector<uint8_t>{0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0});
    const size_t weights = f.append(std::vector<float>{1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0});
    const size_t ibm = f.append(std::vector<float>{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1});
    const size_t times = f.append(std::vector<float>{0, 1, 2});
    const size_t values = f.append(std::vector<float>{0, 0, 0, 1, 0, 0, 2, 0, 0});
    auto view = [&](size_t at, size_t length) {
        f.doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", at}, {"byteLength", length}});
        return f.doc["bufferViews"].size() - 1;
    };
    f.doc["accessors"].push_back(
        {{"bufferView", view(joints, 12)}, {"componentType", 5121}, {"count", 3}, {"type", "VEC4"}});
    f.doc["accessors"].push_back(
        {{"bufferView", view(weights, 48)}, {"componentType", 5126}, {"count", 3}, {"type", "VEC4"}});
    f.doc["accessors"].push_back(
        {{"bufferView", view(ibm, 64)}, {"componentType", 5126}, {"count", 1}, {"type", "MAT4"}});
    f.doc["accessors"].push_back({{"bufferView", view(times, 12)}, {"componentType", 5126}, {"count", 3},
                                  {"type", "SCALAR"}, {"min", {0}}, {"max", {2}}});
    f.doc["accessors"].push_back(
        {{"bufferView", view(values, 36)}, {"componentType", 5126}, {"count", 3}, {"type", "VEC3"}});
    f.doc["meshes"][0]["primitives"][0]["attributes"]["JOINTS_0"] = 2;
    f.doc["meshes"][0]["primitives"][0]["attributes"]["WEIGHTS_0"] = 3;
    f.doc["nodes"] = json::parse(R"([{"mesh": 0, "skin": 0}, {"name": "joint"}])");
    f.doc["scenes"][0]["nodes"] = {0, 1};
    f.doc["skins"] = json::parse(R"([{"joints": [1], "inverseBindMatrices": 4}])");
    f.doc["animations"] = json::parse(R"([{"samplers": [{"input": 5, "output": 6, "interpolation": "LINEAR"}],
        "channels": [{"sampler": 0, "target": {"node": 1, "path": "translation"}}]}])");
    return f;
}

void setFloat(GltfFile& f, size_t byteOffset, float value) {
    std::memcpy(f.buffer.data() + byteOffset, &value, 4);
}

TEST(HostileAnimation, TheBaseFileAnimates) {
    TempDir dir;
    Scene s = loadGltf(skinnedTriangle().write(dir));
    ASSERT_EQ(s.animations.size(), 1u);
    evaluateAnimations(s, 1.5);
    EXPECT_EQ(s.nodes[1].translation, glm::vec3(1.5f, 0, 0));
    // The vertices follow joint 1 (weight 1).
    const Primitive& p = s.meshes[0].primitives[0];
    EXPECT_EQ(deformedPosition(s, s.instances[0], p, 0), p.positions[0] + glm::vec3(1.5f, 0, 0));
}

TEST(HostileAnimation, NonFinitePositionsDropThePrimitiveWithAWarning) {
    TempDir dir;
    for (const float bad : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
        auto f = test::triangle();
        setFloat(f, 16, bad);  // vertex 1, y
        const Scene s = loadGltf(f.write(dir));
        EXPECT_TRUE(s.meshes[0].primitives.empty());
        EXPECT_TRUE(s.instances.empty());
        EXPECT_TRUE(s.bounds.empty());
        ASSERT_EQ(s.warnings.size(), 1u);
        EXPECT_NE(s.warnings[0].find("mesh 0 primitive 0 POSITION (accessor 0): 1 vertices are NaN or infinite"),
                  std::string::npos)
            << s.warnings[0];
    }
}

TEST(HostileAnimation, SkinWithTooManyJoints) {
    TempDir dir;
    auto f = skinnedTriangle();
    for (int i = 0; i < 300; ++i) f.doc["nodes"].push_back(json::object());
    f.doc["skins"][0]["joints"] = json::array();
    for (int i = 0; i < 300; ++i) f.doc["skins"][0]["joints"].push_back(i + 2);
    f.doc["skins"][0].erase("inverseBindMatrices");
    expectLoadError(f.write(dir), "skin 0 has 300 joints; at most 256 (kMaxJoints) are supported");
}

TEST(HostileAnimation, JointIndexPastTheSkin) {
    TempDir dir;
    auto f = skinnedTriangle();
    f.buffer[f.doc["bufferViews"][2]["byteOffset"].get<size_t>() + 4] = 3;  // vertex 1, joint 3 with weight 1
    expectLoadError(f.write(dir), "vertex 1 uses joint 3, but skin 0 of node 0 has 1 joints");
    // The same index with weight 0 is harmless: it becomes joint 0.
    f = skinnedTriangle();
    f.buffer[f.doc["bufferViews"][2]["byteOffset"].get<size_t>() + 5] = 3;  // vertex 1, slot 1 (weight 0)
    const Scene s = loadGltf(f.write(dir));
    EXPECT_EQ(s.meshes[0].primitives[0].joints[1][1], 0u);
}

TEST(HostileAnimation, SkinDataErrors) {
    TempDir dir;
    auto f = skinnedTriangle();
    f.doc["skins"][0]["joints"] = {1, 0};
    expectLoadError(f.write(dir), "skin 0: 1 inverseBindMatrices for 2 joints");
    f = skinnedTriangle();
    f.doc["skins"][0]["joints"] = {7};
    expectLoadError(f.write(dir), "joint node 7 out of range");
    f = skinnedTriangle();
    setFloat(f, f.doc["bufferViews"][4]["byteOffset"].get<size_t>(), std::numeric_limits<float>::quiet_NaN());
    expectLoadError(f.write(dir), "inverseBindMatrices contain NaN");
    f = skinnedTriangle();
    f.doc["nodes"][0]["skin"] = 4;
    expectLoadError(f.write(dir), "skin 4 out of range");
}

TEST(HostileAnimation, SamplerAndTargetIndicesOutOfRange) {
    TempDir dir;
    auto f = skinnedTriangle();
    f.doc["animations"][0]["channels"][0]["sampler"] = 3;
    expectLoadError(f.write(dir), "animation 0 channel 0: sampler 3 out of range (animation has 1 samplers)");
    f = skinnedTriangle();
    f.doc["animations"][0]["channels"][0]["target"]["node"] = 9;
    expectLoadError(f.write(dir), "target node 9 out of range");
    f = skinnedTriangle();
    f.doc["animations"][0]["samplers"][0]["output"] = 40;
    expectLoadError(f.write(dir), "accessor 40 out of range");
}

TEST(HostileAnimation, InputOutputCountMismatch) {
    TempDir dir;
    auto f = skinnedTriangle();
    f.doc["accessors"][6]["count"] = 2;
    expectLoadError(f.write(dir), "input/output count mismatch: 3 keyframes");
    f = skinnedTriangle();
    f.doc["animations"][0]["samplers"][0]["interpolation"] = "CUBICSPLINE";  // needs 9 outputs
    expectLoadError(f.write(dir), "need 9 output elements");
    f = skinnedTriangle();
    f.doc["animations"][0]["channels"][0]["target"]["path"] = "rotation";  // VEC3 output for a rotation
    expectLoadError(f.write(dir), "path rotation needs 4 values per keyframe");
}

TEST(HostileAnimation, TimesNotIncreasing) {
    TempDir dir;
    const size_t times = skinnedTriangle().doc["bufferViews"][5]["byteOffset"].get<size_t>();
    auto f = skinnedTriangle();
    setFloat(f, times + 8, 0.5f);  // 0, 1, 0.5
    expectLoadError(f.write(dir), "input times are not increasing (key 2");
    f = skinnedTriangle();
    setFloat(f, times + 4, std::numeric_limits<float>::quiet_NaN());
    expectLoadError(f.write(dir), "input time 1 is NaN or infinite");
    // Equal consecutive times are accepted: a jump at that time, never a division by zero.
    f = skinnedTriangle();
    setFloat(f, times + 8, 1.0f);  // 0, 1, 1
    Scene s = loadGltf(f.write(dir));
    for (const double t : {0.5, 1.0, 1.5}) {
        evaluateAnimations(s, t);
        EXPECT_TRUE(std::isfinite(s.nodes[1].translation.x)) << t;
    }
    evaluateAnimations(s, 1.0);
    EXPECT_EQ(s.nodes[1].translation.x, 2.0f);  // at the jump, the last key of the same time
}

TEST(HostileAnimation, ZeroScaleNodesAreDegenerateNotFatal) {
    TempDir dir;
    auto f = skinnedTriangle();
    f.doc["nodes"][0]["scale"] = {0, 0, 0};
    f.doc["nodes"][1]["scale"] = {0, 0, 0};
    Scene s = loadGltf(f.write(dir));
    evaluateAnimations(s, 1.0);
    for (const auto& m : s.nodes[0].jointMatrices) EXPECT_EQ(m, glm::mat4(0.0f));
    const glm::vec3 p = deformedPosition(s, s.instances[0], s.meshes[0].primitives[0], 1);
    EXPECT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
    EXPECT_FALSE(s.bounds.empty());
}

TEST(HostileAnimation, WeightsOnANodeWithoutTargetsAreSkipped) {
    TempDir dir;
    auto f = skinnedTriangle();
    f.doc["animations"][0]["channels"][0]["target"]["path"] = "weights";
    const Scene s = loadGltf(f.write(dir));
    EXPECT_TRUE(s.animations[0].channels.empty());
    ASSERT_EQ(s.warnings.size(), 1u);
    EXPECT_NE(s.warnings[0].find("no morph targets"), std::string::npos);
}

TEST(HostileAnimation, AnimatedNodeWithAMatrixIsDecomposed) {
    TempDir dir;
    auto f = skinnedTriangle();
    f.doc["nodes"][1]["matrix"] = {2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 0, 5, 6, 7, 1};
    Scene s = loadGltf(f.write(dir));
    EXPECT_FALSE(s.nodes[1].matrix.has_value());
    EXPECT_EQ(s.nodes[1].rest.scale, glm::vec3(2.0f));
    EXPECT_EQ(s.nodes[1].rest.translation, glm::vec3(5, 6, 7));
    ASSERT_EQ(s.warnings.size(), 1u);
    EXPECT_NE(s.warnings[0].find("decomposed"), std::string::npos);
    evaluateAnimations(s, 1.0);
    EXPECT_EQ(s.nodes[1].translation, glm::vec3(1, 0, 0));
    EXPECT_EQ(s.nodes[1].scale, glm::vec3(2.0f));  // not animated: the decomposed rest value
}

// Random byte mutations of animated, skinned and morphed GLBs: a Scene (which must then evaluate) or a LoadError.
TEST(HostileAnimation, RandomMutationsNeverCrash) {
    std::mt19937 rng(777);
    int loaded = 0, rejected = 0;
    for (const char* file : {"InterpolationTest/glTF-Binary/InterpolationTest.glb",
                             "AnimatedMorphCube/glTF-Binary/AnimatedMorphCube.glb", "Fox/glTF-Binary/Fox.glb"}) {
        const auto original = test::readBytes(test::sharedScene(file));
        uint32_t jsonLength = 0;
        std::memcpy(&jsonLength, original.data() + 12, 4);
        for (int iteration = 0; iteration < 150; ++iteration) {
            auto bytes = original;
            const int edits = 1 + int(rng() % 3);
            for (int e = 0; e < edits; ++e) {
                // Half the edits in the JSON (structure), half anywhere (keyframes, indices, matrices).
                const size_t at = iteration % 2 == 0 ? 20 + rng() % jsonLength : rng() % bytes.size();
                bytes[at] = iteration % 4 == 0 ? uint8_t('0' + rng() % 10) : uint8_t(rng());
            }
            try {
                Scene s = loadGltfFromMemory(bytes, "mutated.glb");
                for (const double t : {-1.0, 0.3, 1.0, 50.0}) evaluateAnimations(s, t);
                ++loaded;
            } catch (const LoadError&) {
                ++rejected;
            }
        }
    }
    EXPECT_EQ(loaded + rejected, 450);
    EXPECT_GT(loaded, 0);
    EXPECT_GT(rejected, 0);
}

}  // namespace
}  // namespace idk::scene
