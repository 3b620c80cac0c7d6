// animation_test.cpp: evaluateAnimations() and deformedPosition() against values computed by hand in this file:
// the keyframes come from the loader, the math (STEP / LINEAR / slerp / CUBICSPLINE Hermite, skinning, morphing)
// is written out here independently of engine/scene/animation.cpp. InterpolationTest (T, R, S x 3
// interpolations), SimpleSkin joint matrices and skinned vertices, SimpleMorph and AnimatedMorphCube weights and
// morphed positions, Fox (3 clips, finite, deterministic).
#include <cmath>
#include <cstring>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "scene/animation.hpp"
#include "scene/gltf_loader.hpp"
#include "test_files.hpp"

namespace idk::scene {
namespace {

using test::sharedScene;

constexpr float kTolerance = 1e-5f;

// --- the hand reference (glTF 2.0 appendix C, written independently) ---------------------------------------

std::vector<float> keyValue(const AnimationSampler& s, size_t key, size_t part /* 0 in, 1 value, 2 out */) {
    const size_t c = s.components;
    const bool cubic = s.interpolation == Interpolation::CubicSpline;
    const size_t begin = cubic ? (3 * key + part) * c : key * c;
    return std::vector<float>(s.values.begin() + std::ptrdiff_t(begin), s.values.begin() + std::ptrdiff_t(begin + c));
}

std::vector<float> normalized4(std::vector<float> q) {
    const float len = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    for (float& v : q) v /= len;
    return q;
}

std::vector<float> handSample(const AnimationSampler& s, double t, bool rotation) {
    const size_t n = s.times.size(), c = s.components;
    std::vector<float> out;
    if (t <= s.times.front()) {
        out = keyValue(s, 0, 1);
    } else if (t >= s.times.back()) {
        out = keyValue(s, n - 1, 1);
    } else {
        size_t k = 0;
        while (!(s.times[k] <= t && t < s.times[k + 1])) ++k;  // linear scan, unlike the engine's binary search
        const double t0 = s.times[k], t1 = s.times[k + 1];
        const float u = float((t - t0) / (t1 - t0));
        const float dt = float(t1 - t0);
        if (s.interpolation == Interpolation::Step) {
            out = keyValue(s, k, 1);
        } else if (s.interpolation == Interpolation::Linear) {
            const auto a = keyValue(s, k, 1), b = keyValue(s, k + 1, 1);
            out.resize(c);
            if (rotation) {  // glm's slerp takes the short path itself; keys normalized first
                const glm::quat qa = glm::normalize(glm::quat(a[3], a[0], a[1], a[2]));
                const glm::quat qb = glm::normalize(glm::quat(b[3], b[0], b[1], b[2]));
                const glm::quat q = glm::slerp(qa, qb, u);
                out = {q.x, q.y, q.z, q.w};
            } else {
                for (size_t i = 0; i < c; ++i) out[i] = (1.0f - u) * a[i] + u * b[i];
            }
        } else {
            const auto vk = keyValue(s, k, 1), bk = keyValue(s, k, 2), vk1 = keyValue(s, k + 1, 1),
                       ak1 = keyValue(s, k + 1, 0);
            out.resize(c);
            for (size_t i = 0; i < c; ++i)
                out[i] = (2 * u * u * u - 3 * u * u + 1) * vk[i] + (u * u * u - 2 * u * u + u) * dt * bk[i] +
                         (-2 * u * u * u + 3 * u * u) * vk1[i] + (u * u * u - u * u) * dt * ak1[i];
        }
    }
    return rotation ? normalized4(out) : out;
}

void expectNear(const std::vector<float>& actual, std::vector<float> expected, bool rotation, const std::string& what) {
    ASSERT_EQ(actual.size(), expected.size()) << what;
    if (rotation) {  // q and -q are the same rotation
        float d = 0;
        for (size_t i = 0; i < 4; ++i) d += actual[i] * expected[i];
        if (d < 0)
            for (float& v : expected) v = -v;
    }
    for (size_t i = 0; i < actual.size(); ++i)
        EXPECT_NEAR(actual[i], expected[i], kTolerance) << what << " [" << i << "]";
}

const Animation& animationNamed(const Scene& scene, const std::string& name, int* index) {
    for (size_t a = 0; a < scene.animations.size(); ++a)
        if (scene.animations[a].name == name) {
            *index = int(a);
            return scene.animations[a];
        }
    throw std::runtime_error("no animation " + name);
}

// Times before the first key, at each key, inside each interval (1/4, 1/2, 0.9) and after the last key.
std::vector<double> probeTimes(const std::vector<float>& times) {
    std::vector<double> out = {double(times.front()) - 1.0, double(times.front()) - 1e-3};
    for (size_t k = 0; k < times.size(); ++k) {
        out.push_back(times[k]);
        if (k + 1 < times.size())
            for (const double f : {0.25, 0.5, 0.9}) out.push_back(times[k] + f * (double(times[k + 1]) - times[k]));
    }
    out.push_back(double(times.back()) + 0.5);
    out.push_back(100.0);
    return out;
}

TEST(InterpolationTest, AllNineChannelsMatchTheHandComputation) {
    Scene scene = loadGltf(sharedScene("InterpolationTest/glTF-Binary/InterpolationTest.glb"));
    ASSERT_EQ(scene.animations.size(), 9u);
    struct Case {
        const char* name;
        AnimationPath path;
        Interpolation interpolation;
    };
    const Case cases[] = {
        {"Step Translation", AnimationPath::Translation, Interpolation::Step},
        {"Linear Translation", AnimationPath::Translation, Interpolation::Linear},
        {"CubicSpline Translation", AnimationPath::Translation, Interpolation::CubicSpline},
        {"Step Rotation", AnimationPath::Rotation, Interpolation::Step},
        {"Linear Rotation", AnimationPath::Rotation, Interpolation::Linear},
        {"CubicSpline Rotation", AnimationPath::Rotation, Interpolation::CubicSpline},
        {"Step Scale", AnimationPath::Scale, Interpolation::Step},
        {"Linear Scale", AnimationPath::Scale, Interpolation::Linear},
        {"CubicSpline Scale", AnimationPath::Scale, Interpolation::CubicSpline},
    };
    for (const Case& c : cases) {
        int index = -1;
        const Animation& anim = animationNamed(scene, c.name, &index);
        ASSERT_EQ(anim.channels.size(), 1u) << c.name;
        const AnimationChannel ch = anim.channels[0];
        const AnimationSampler sampler = anim.samplers[ch.sampler];
        EXPECT_EQ(ch.path, c.path) << c.name;
        EXPECT_EQ(sampler.interpolation, c.interpolation) << c.name;
        const bool rotation = c.path == AnimationPath::Rotation;
        for (const double t : probeTimes(sampler.times)) {
            evaluateAnimations(scene, t, index);
            const Node& node = scene.nodes[ch.node];
            std::vector<float> actual;
            if (c.path == AnimationPath::Translation)
                actual = {node.translation.x, node.translation.y, node.translation.z};
            if (c.path == AnimationPath::Scale) actual = {node.scale.x, node.scale.y, node.scale.z};
            if (rotation) actual = {node.rotation.x, node.rotation.y, node.rotation.z, node.rotation.w};
            expectNear(actual, handSample(sampler, t, rotation), rotation,
                       std::string(c.name) + " t=" + std::to_string(t));
        }
    }
}

// A few values read off the file's keyframes, so the hand reference itself is pinned to known numbers.
TEST(InterpolationTest, PinnedValues) {
    Scene scene = loadGltf(sharedScene("InterpolationTest/glTF-Binary/InterpolationTest.glb"));
    int linear = -1, step = -1, cubic = -1, rot = -1;
    const Animation& lin = animationNamed(scene, "Linear Translation", &linear);
    animationNamed(scene, "Step Translation", &step);
    animationNamed(scene, "CubicSpline Scale", &cubic);
    animationNamed(scene, "Linear Rotation", &rot);
    const uint32_t node = lin.channels[0].node;
    evaluateAnimations(scene, 0.5 * 0.416667, linear);  // halfway between y = 6.62101 and y = 10
    EXPECT_NEAR(scene.nodes[node].translation.y, (6.62101f + 10.0f) / 2.0f, 1e-4f);
    evaluateAnimations(scene, 0.7, step);  // keys at 0.458333 (y 10) and 0.833333 (y 6)
    EXPECT_NEAR(scene.nodes[scene.animations[size_t(step)].channels[0].node].translation.y, 10.0f, kTolerance);
    evaluateAnimations(scene, 0.416667, cubic);  // exactly key 1: scale 0.5
    EXPECT_NEAR(scene.nodes[scene.animations[size_t(cubic)].channels[0].node].scale.x, 0.5f, 1e-4f);
    // Linear rotation halfway between 0 and 45 degrees about -Z: 22.5 degrees, q = (0, 0, -sin 11.25, cos 11.25).
    evaluateAnimations(scene, 0.5 * 0.416667, rot);
    const glm::quat q = scene.nodes[scene.animations[size_t(rot)].channels[0].node].rotation;
    EXPECT_NEAR(q.z, -std::sin(glm::radians(11.25f)), 1e-4f);
    EXPECT_NEAR(q.w, std::cos(glm::radians(11.25f)), 1e-4f);
    // Animating one clip leaves every other node at its rest pose.
    EXPECT_EQ(scene.nodes[node].translation, scene.nodes[node].rest.translation);
}

// InterpolationTest's cubic keys have equal in- and out-tangents; this sampler does not, so swapping them fails.
TEST(InterpolationTest, CubicSplineUsesOutTangentOfKeyKAndInTangentOfKeyKPlus1) {
    AnimationSampler s;
    s.interpolation = Interpolation::CubicSpline;
    s.components = 1;
    s.times = {1.0f, 3.0f};
    s.values = {/*key 0: in, value, out*/ 7.0f, 0.0f, 2.0f, /*key 1*/ -1.0f, 1.0f, 9.0f};
    // t = 2: s = 0.5, td = 2: 0.5 v0 + 0.125 td b0 + 0.5 v1 - 0.125 td a1 = 0.5 + 0.25 * (2 + 1) = 1.25.
    EXPECT_NEAR(sampleAnimation(s, 2.0, false)[0], 1.25f, kTolerance);
    EXPECT_NEAR(handSample(s, 2.0, false)[0], 1.25f, kTolerance);
    for (const double t : {0.0, 1.0, 1.3, 2.7, 3.0, 4.0})
        EXPECT_NEAR(sampleAnimation(s, t, false)[0], handSample(s, t, false)[0], kTolerance) << t;
    EXPECT_EQ(sampleAnimation(s, 0.5, false)[0], 0.0f);  // before the first key: its value, not its tangent
    EXPECT_EQ(sampleAnimation(s, 5.0, false)[0], 1.0f);
}

// Slerp must take the short arc when the keys' dot product is negative (q and -q are the same rotation).
TEST(InterpolationTest, LinearRotationTakesTheShortArc) {
    AnimationSampler s;
    s.interpolation = Interpolation::Linear;
    s.components = 4;
    const float h = std::sqrt(0.5f);
    s.times = {0.0f, 1.0f};
    s.values = {0, 0, 0, 1, /* 90 degrees about +Z, stored negated */ 0, 0, -h, -h};
    const auto q = sampleAnimation(s, 0.5, true);  // 45 degrees about +Z, up to the overall sign
    const float sign = q[3] < 0 ? -1.0f : 1.0f;
    EXPECT_NEAR(sign * q[2], std::sin(glm::radians(22.5f)), kTolerance);
    EXPECT_NEAR(sign * q[3], std::cos(glm::radians(22.5f)), kTolerance);
    expectNear(q, handSample(s, 0.5, true), true, "short arc");
}

// --- SimpleSkin ---------------------------------------------------------------------------------------------

glm::mat4 rotZ(float radians) {
    return glm::rotate(glm::mat4(1.0f), radians, glm::vec3(0, 0, 1));
}

void expectMatNear(const glm::mat4& a, const glm::mat4& b, float tolerance, const std::string& what) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) EXPECT_NEAR(a[c][r], b[c][r], tolerance) << what << " [" << c << "][" << r << "]";
}

TEST(SimpleSkin, JointMatricesAndSkinnedVertices) {
    Scene scene = loadGltf(sharedScene("SimpleSkin/glTF/SimpleSkin.gltf"));
    ASSERT_EQ(scene.skins.size(), 1u);
    ASSERT_EQ(scene.skins[0].joints, (std::vector<uint32_t>{1, 2}));
    ASSERT_EQ(scene.instances.size(), 1u);
    const Instance instance = scene.instances[0];
    ASSERT_EQ(instance.skin, 0u);
    // Joint 1 sits at y = 1 in the bind pose; its inverse bind matrix moves it back to the origin.
    const glm::mat4 up = glm::translate(glm::mat4(1.0f), glm::vec3(0, 1, 0));
    const glm::mat4 down = glm::translate(glm::mat4(1.0f), glm::vec3(0, -1, 0));
    expectMatNear(scene.skins[0].inverseBindMatrices[1], down, 0.0f, "inverse bind 1");

    // The rotation keys (0, 0, 0.383, 0.924) at t = 0.5 and (0, 0, 0.707, 0.707) at t = 1 are 45 and 90 degrees.
    const float angle45 = 2.0f * std::atan2(0.383f, 0.924f), angle90 = 2.0f * std::atan2(0.707f, 0.707f);
    struct Probe {
        double t;
        float angle;  // joint 1's rotation about +Z, by hand
    };
    for (const Probe probe : {Probe{0.0, 0.0f}, Probe{0.75, 0.5f * (angle45 + angle90)}, Probe{1.0, angle90},
                              Probe{1.25, angle90}, Probe{99.0, 0.0f}}) {
        const std::string what = "t=" + std::to_string(probe.t);
        evaluateAnimations(scene, probe.t);
        const Node& meshNode = scene.nodes[instance.node];
        ASSERT_EQ(meshNode.jointMatrices.size(), 2u);
        // inverse(world(mesh node) = I) * world(joint) * inverse bind: joint 0 is the identity throughout,
        // joint 1 = T(0,1,0) * Rz(angle) * T(0,-1,0): a rotation about the point (0, 1).
        const glm::mat4 expected1 = up * rotZ(probe.angle) * down;
        expectMatNear(meshNode.jointMatrices[0], glm::mat4(1.0f), kTolerance, what + " joint 0");
        expectMatNear(meshNode.jointMatrices[1], expected1, kTolerance, what + " joint 1");
        // Skinned vertices: sum of weight * joint matrix * position, with the matrices above.
        const Primitive& prim = scene.meshes[instance.mesh].primitives[0];
        for (uint32_t v = 0; v < prim.positions.size(); ++v) {
            const glm::vec4 p(prim.positions[v], 1.0f);
            glm::vec4 hand(0.0f);
            for (int c = 0; c < 4; ++c) {
                const glm::mat4 jm = prim.joints[v][c] == 0 ? glm::mat4(1.0f) : expected1;
                hand += prim.weights[v][c] * (jm * p);
            }
            const glm::vec3 got = deformedPosition(scene, scene.instances[0], prim, v);
            for (int i = 0; i < 3; ++i) EXPECT_NEAR(got[i], hand[i], kTolerance) << what << " vertex " << v;
        }
        if (probe.t == 1.0) {  // the top corners (y = 2, all weight on joint 1) turn 90 degrees about (0, 1)
            for (uint32_t v = 0; v < prim.positions.size(); ++v)
                if (prim.positions[v] == glm::vec3(0.5f, 2.0f, 0.0f)) {
                    const glm::vec3 got = deformedPosition(scene, scene.instances[0], prim, v);
                    EXPECT_NEAR(got.x, -1.0f, 1e-3f);
                    EXPECT_NEAR(got.y, 1.5f, 1e-3f);
                }
        }
    }
}

// --- morph targets ------------------------------------------------------------------------------------------

TEST(SimpleMorph, WeightsAndMorphedPositions) {
    Scene scene = loadGltf(sharedScene("SimpleMorph/glTF/SimpleMorph.gltf"));
    ASSERT_EQ(scene.meshes[0].weights, (std::vector<float>{0.5f, 0.5f}));  // the mesh's default weights
    const Primitive& prim = scene.meshes[0].primitives[0];
    ASSERT_EQ(prim.targets.size(), 2u);
    // Keys (t: w0, w1) = (0: 0,0) (1: 0,1) (2: 1,1) (3: 1,0) (4: 0,0), by hand at these times:
    struct Probe {
        double t;
        float w0, w1;
    };
    for (const Probe p : {Probe{-1, 0, 0}, Probe{0.5, 0, 0.5f}, Probe{1.5, 0.5f, 1}, Probe{2.25, 1, 0.75f},
                          Probe{3.75, 0.25f, 0}, Probe{9, 0, 0}}) {
        evaluateAnimations(scene, p.t);
        const Node& node = scene.nodes[0];
        ASSERT_EQ(node.weights.size(), 2u);
        EXPECT_NEAR(node.weights[0], p.w0, kTolerance) << p.t;
        EXPECT_NEAR(node.weights[1], p.w1, kTolerance) << p.t;
        for (uint32_t v = 0; v < prim.positions.size(); ++v) {
            const glm::vec3 hand =
                prim.positions[v] + p.w0 * prim.targets[0].positions[v] + p.w1 * prim.targets[1].positions[v];
            const glm::vec3 got = deformedPosition(scene, scene.instances[0], prim, v);
            for (int i = 0; i < 3; ++i) EXPECT_NEAR(got[i], hand[i], kTolerance) << p.t << " vertex " << v;
        }
    }
    // Pinned: at t = 2 both weights are 1, so the apex (0.5, 0.5) moves up by both targets' deltas.
    evaluateAnimations(scene, 2.0);
    for (uint32_t v = 0; v < prim.positions.size(); ++v)
        if (prim.positions[v] == glm::vec3(0.5f, 0.5f, 0.0f)) {
            const glm::vec3 got = deformedPosition(scene, scene.instances[0], prim, v);
            EXPECT_NEAR(got.y, 0.5f + prim.targets[0].positions[v].y + prim.targets[1].positions[v].y, kTolerance);
            EXPECT_GT(got.y, 0.5f);
        }
}

TEST(AnimatedMorphCube, WeightsFollowTheKeyframes) {
    Scene scene = loadGltf(sharedScene("AnimatedMorphCube/glTF-Binary/AnimatedMorphCube.glb"));
    ASSERT_EQ(scene.animations.size(), 1u);
    const AnimationSampler& sampler = scene.animations[0].samplers[0];
    ASSERT_EQ(sampler.components, 2u);
    const Primitive& prim = scene.meshes[0].primitives[0];
    ASSERT_EQ(prim.targets.size(), 2u);
    for (const double t : {0.0, 0.05, 0.5, 1.234, 2.0, 3.3, 4.2, 7.0}) {
        evaluateAnimations(scene, t);
        const auto hand = handSample(sampler, t, false);
        const Node& node = scene.nodes[scene.animations[0].channels[0].node];
        EXPECT_NEAR(node.weights[0], hand[0], kTolerance) << t;
        EXPECT_NEAR(node.weights[1], hand[1], kTolerance) << t;
        const Instance& instance = scene.instances[0];
        for (uint32_t v = 0; v < prim.positions.size(); v += 5) {
            const glm::vec3 local =
                prim.positions[v] + hand[0] * prim.targets[0].positions[v] + hand[1] * prim.targets[1].positions[v];
            const glm::vec3 expected(instance.world * glm::vec4(local, 1.0f));
            const glm::vec3 got = deformedPosition(scene, instance, prim, v);
            for (int i = 0; i < 3; ++i) EXPECT_NEAR(got[i], expected[i], 1e-3f) << t;  // world units x100
        }
    }
}

// --- Fox ----------------------------------------------------------------------------------------------------

bool finite(const glm::mat4& m) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(m[c][r])) return false;
    return true;
}

TEST(Fox, ThreeClipsFiniteAndDeterministic) {
    Scene scene = loadGltf(sharedScene("Fox/glTF-Binary/Fox.glb"));
    ASSERT_EQ(scene.animations.size(), 3u);
    EXPECT_EQ(scene.animations[0].name, "Survey");
    EXPECT_EQ(scene.animations[1].name, "Walk");
    EXPECT_EQ(scene.animations[2].name, "Run");
    ASSERT_EQ(scene.instances.size(), 1u);
    const uint32_t foxNode = scene.instances[0].node;
    ASSERT_EQ(scene.skins[0].joints.size(), 24u);
    for (int a = 0; a < 3; ++a) {
        const Animation& anim = scene.animations[size_t(a)];
        EXPECT_GT(anim.end, anim.start);
        std::vector<glm::mat4> previous;
        for (const double f : {-0.5, 0.0, 0.3, 0.5, 0.77, 1.0, 2.0}) {
            const double t = anim.start + f * (double(anim.end) - anim.start);
            evaluateAnimations(scene, t, a);
            const std::vector<glm::mat4> joints = scene.nodes[foxNode].jointMatrices;
            ASSERT_EQ(joints.size(), 24u);
            for (const auto& m : joints) EXPECT_TRUE(finite(m)) << anim.name << " t=" << t;
            for (const auto& n : scene.nodes) EXPECT_TRUE(finite(n.world)) << anim.name << " t=" << t;
            // Deterministic: another time in between, then the same time again, gives the same bits.
            evaluateAnimations(scene, t + 0.123, a);
            evaluateAnimations(scene, t, -1);
            evaluateAnimations(scene, t, a);
            EXPECT_EQ(std::memcmp(joints.data(), scene.nodes[foxNode].jointMatrices.data(), joints.size() * 64), 0)
                << anim.name << " t=" << t;
            if (f == 0.5) previous = joints;
            if (f == 0.77) {
                EXPECT_NE(std::memcmp(previous.data(), joints.data(), joints.size() * 64), 0);  // it moves
            }
        }
    }
    // Skinned vertices stay near the rest bounds (a walking fox does not explode).
    evaluateAnimations(scene, 0.4, 1);
    const Aabb& rest = scene.bounds;
    const float size = glm::length(rest.max - rest.min);
    for (const Primitive& prim : scene.meshes[scene.instances[0].mesh].primitives)
        for (uint32_t v = 0; v < prim.positions.size(); v += 7) {
            const glm::vec3 p = deformedPosition(scene, scene.instances[0], prim, v);
            EXPECT_LT(glm::length(p - rest.centre()), size);
        }
    EXPECT_THROW(evaluateAnimations(scene, 0.0, 3), std::out_of_range);
}

}  // namespace
}  // namespace idk::scene
