// animation.cpp: keyframe sampling (STEP, LINEAR with quaternion slerp, CUBICSPLINE Hermite), posing the scene at
// a time from its rest pose, and the CPU morph + skin vertex deformation. Ports IDKEngine's CPU animation update
// (which had STEP and LINEAR on TRS only) and the vertex math of its skinning compute shader.
#include "scene/animation.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "scene/scene_graph.hpp"

namespace idk::scene {

namespace {

struct Key {
    size_t k0 = 0, k1 = 0;  // keyframes around t (equal when t is outside the range or exactly clamped)
    float s = 0.0f;         // 0..1 between them
    float td = 0.0f;        // t1 - t0 in seconds
};

Key locate(const std::vector<float>& times, double t) {
    const size_t n = times.size();
    if (n == 0 || !(t > double(times.front()))) return {};  // before the first key, or NaN time
    if (t >= double(times.back())) return {n - 1, n - 1, 0.0f, 0.0f};
    const size_t k1 = size_t(std::upper_bound(times.begin(), times.end(), t,
                                              [](double value, float key) { return value < double(key); }) -
                             times.begin());
    const size_t k0 = k1 - 1;  // times[k0] <= t < times[k1], so times[k1] > times[k0]
    const double t0 = times[k0], t1 = times[k1];
    return {k0, k1, float((t - t0) / (t1 - t0)), float(t1 - t0)};
}

// Where value `which` (0 in-tangent, 1 value, 2 out-tangent for CUBICSPLINE; 0 otherwise) of keyframe k starts.
const float* keyValue(const AnimationSampler& sampler, size_t k, int which) {
    const size_t c = sampler.components;
    if (sampler.interpolation == Interpolation::CubicSpline) return sampler.values.data() + (k * 3 + size_t(which)) * c;
    return sampler.values.data() + k * c;
}

void normalizeQuat(std::vector<float>& q) {
    const float len = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    if (len > 0.0f && std::isfinite(len)) {
        for (float& v : q) v /= len;
    } else {
        q = {0.0f, 0.0f, 0.0f, 1.0f};
    }
}

}  // namespace

std::vector<float> sampleAnimation(const AnimationSampler& sampler, double t, bool isRotation) {
    const size_t c = sampler.components;
    std::vector<float> out(c, 0.0f);
    if (sampler.times.empty() || c == 0) return out;
    const Key key = locate(sampler.times, t);
    const bool cubic = sampler.interpolation == Interpolation::CubicSpline;
    const float* v0 = keyValue(sampler, key.k0, cubic ? 1 : 0);
    if (key.k0 == key.k1 || sampler.interpolation == Interpolation::Step) {
        std::copy(v0, v0 + c, out.begin());
    } else if (!cubic) {
        const float* v1 = keyValue(sampler, key.k1, 0);
        if (isRotation && c == 4) {
            // Keys are unit quaternions by the spec, but files round them (0.383, 0.924): normalize first, or the
            // slerp angle drifts.
            std::vector<float> q0(v0, v0 + 4), q1(v1, v1 + 4);
            normalizeQuat(q0);
            normalizeQuat(q1);
            float d = q0[0] * q1[0] + q0[1] * q1[1] + q0[2] * q1[2] + q0[3] * q1[3];
            if (d < 0.0f) {
                for (float& v : q1) v = -v;
                d = -d;
            }
            float w0 = 1.0f - key.s, w1 = key.s;
            if (d < 0.9995f) {  // slerp; nearly parallel quaternions fall back to nlerp (normalized below)
                const float theta = std::acos(std::min(d, 1.0f));
                const float sinTheta = std::sin(theta);
                w0 = std::sin((1.0f - key.s) * theta) / sinTheta;
                w1 = std::sin(key.s * theta) / sinTheta;
            }
            for (size_t i = 0; i < 4; ++i) out[i] = w0 * q0[i] + w1 * q1[i];
        } else {
            for (size_t i = 0; i < c; ++i) out[i] = v0[i] + key.s * (v1[i] - v0[i]);
        }
    } else {
        const float s = key.s, s2 = s * s, s3 = s2 * s;
        const float h00 = 2.0f * s3 - 3.0f * s2 + 1.0f, h10 = s3 - 2.0f * s2 + s;
        const float h01 = -2.0f * s3 + 3.0f * s2, h11 = s3 - s2;
        const float* b0 = keyValue(sampler, key.k0, 2);  // out-tangent of k0
        const float* v1 = keyValue(sampler, key.k1, 1);
        const float* a1 = keyValue(sampler, key.k1, 0);  // in-tangent of k1
        for (size_t i = 0; i < c; ++i)
            out[i] = h00 * v0[i] + h10 * key.td * b0[i] + h01 * v1[i] + h11 * key.td * a1[i];
    }
    if (isRotation && c == 4) normalizeQuat(out);
    return out;
}

void evaluateAnimations(Scene& scene, double timeSeconds, int animation) {
    if (animation >= 0 && size_t(animation) >= scene.animations.size())
        throw std::out_of_range("evaluateAnimations: animation " + std::to_string(animation) + " of " +
                                std::to_string(scene.animations.size()));
    for (Node& node : scene.nodes) {
        node.translation = node.rest.translation;
        node.rotation = node.rest.rotation;
        node.scale = node.rest.scale;
        node.weights = node.rest.weights;
    }
    for (size_t a = 0; a < scene.animations.size(); ++a) {
        if (animation >= 0 && size_t(animation) != a) continue;
        const Animation& anim = scene.animations[a];
        for (const AnimationChannel& channel : anim.channels) {
            const AnimationSampler& sampler = anim.samplers[channel.sampler];
            Node& node = scene.nodes[channel.node];
            const bool rotation = channel.path == AnimationPath::Rotation;
            const std::vector<float> v = sampleAnimation(sampler, timeSeconds, rotation);
            switch (channel.path) {
                case AnimationPath::Translation: node.translation = glm::vec3(v[0], v[1], v[2]); break;
                case AnimationPath::Rotation: node.rotation = glm::quat(v[3], v[0], v[1], v[2]); break;
                case AnimationPath::Scale: node.scale = glm::vec3(v[0], v[1], v[2]); break;
                case AnimationPath::Weights:
                    std::copy_n(v.begin(), std::min(v.size(), node.weights.size()), node.weights.begin());
                    break;
            }
        }
    }
    updateTransforms(scene);
}

glm::vec3 deformedPosition(const Scene& scene, const Instance& instance, const Primitive& prim, uint32_t vertex) {
    const Node& node = scene.nodes[instance.node];
    glm::vec3 p = prim.positions[vertex];
    for (size_t t = 0; t < prim.targets.size() && t < node.weights.size(); ++t)
        if (!prim.targets[t].positions.empty() && node.weights[t] != 0.0f)
            p += node.weights[t] * prim.targets[t].positions[vertex];
    glm::vec4 q(p, 1.0f);
    if (instance.skin && !prim.joints.empty() && !node.jointMatrices.empty()) {
        glm::mat4 skin(0.0f);
        for (int c = 0; c < 4; ++c) {
            const uint32_t j = prim.joints[vertex][c];
            if (j < node.jointMatrices.size()) skin += prim.weights[vertex][c] * node.jointMatrices[j];
        }
        q = skin * q;
    }
    return glm::vec3(instance.world * q);
}

}  // namespace idk::scene
