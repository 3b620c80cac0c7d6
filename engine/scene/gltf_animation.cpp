// gltf_animation.cpp: glTF animations -> Scene::animations for the loader (the animation part of IDKEngine's
// ModelLoader, which rejected CUBICSPLINE and morph weights): samplers with validated keyframe times and
// input/output counts, channels on translation/rotation/scale/weights; animated nodes given as a matrix are
// decomposed into the TRS the channels write.
#include <algorithm>
#include <cmath>

#include "scene/gltf_internal.hpp"

namespace idk::scene::gltf {

namespace {

AnimationSampler loadSampler(const Ctx& ctx, const tinygltf::AnimationSampler& src, const std::string& where) {
    AnimationSampler sampler;
    if (src.interpolation == "STEP")
        sampler.interpolation = Interpolation::Step;
    else if (src.interpolation == "CUBICSPLINE")
        sampler.interpolation = Interpolation::CubicSpline;
    else if (src.interpolation != "LINEAR" && !src.interpolation.empty())
        ctx.warn(where + ": unknown interpolation '" + src.interpolation + "', using LINEAR");

    sampler.times = readFloats(ctx, src.input, 1, where + " input");
    if (sampler.times.empty()) ctx.fail(where + ": input has no keyframes");
    for (size_t k = 0; k < sampler.times.size(); ++k) {
        if (!std::isfinite(sampler.times[k]))
            ctx.fail(where + ": input time " + str(k) + " is NaN or infinite");
        if (k > 0 && sampler.times[k] < sampler.times[k - 1])
            ctx.fail(where + ": input times are not increasing (key " + str(k) + " at " +
                     std::to_string(sampler.times[k]) + " s follows " + std::to_string(sampler.times[k - 1]) + " s)");
    }
    int comps = 0;
    sampler.values = readAnyFloats(ctx, src.output, where + " output", &comps);
    if (comps != 1 && comps != 3 && comps != 4)
        ctx.fail(where + ": output must be SCALAR, VEC3 or VEC4, not " + str(comps) + " components");
    if (!std::all_of(sampler.values.begin(), sampler.values.end(), [](float v) { return std::isfinite(v); }))
        ctx.fail(where + ": output contains NaN or infinite values");
    const size_t keys = sampler.times.size();
    const size_t perKey = sampler.interpolation == Interpolation::CubicSpline ? 3 : 1;
    const size_t elements = sampler.values.size() / size_t(comps);
    // Morph weights are SCALAR with one element per target per keyframe; everything else one element per key.
    const bool countOk = comps == 1 ? elements % (keys * perKey) == 0 && elements > 0 : elements == keys * perKey;
    if (!countOk)
        ctx.fail(where + ": input/output count mismatch: " + str(keys) + " keyframes (input accessor " +
                 str(src.input) + ") need " + (comps == 1 ? "a multiple of " : "") + str(keys * perKey) +
                 " output elements, output accessor " + str(src.output) + " has " + str(elements));
    sampler.components = uint32_t(comps == 1 ? elements / (keys * perKey) : size_t(comps));
    return sampler;
}

// A node animated through TRS must not keep a matrix (the spec forbids the combination): decompose it.
void decomposeMatrix(const Ctx& ctx, Node& node, size_t index) {
    if (!node.matrix) return;
    const glm::mat4 m = *node.matrix;
    glm::vec3 scale(glm::length(glm::vec3(m[0])), glm::length(glm::vec3(m[1])), glm::length(glm::vec3(m[2])));
    if (glm::determinant(glm::mat3(m)) < 0.0f) scale.x = -scale.x;
    glm::mat3 rotation(1.0f);
    for (int c = 0; c < 3; ++c)
        if (scale[c] != 0.0f && std::isfinite(scale[c])) rotation[c] = glm::vec3(m[c]) / scale[c];
    node.translation = glm::vec3(m[3]);
    node.rotation = glm::normalize(glm::quat_cast(rotation));
    node.scale = scale;
    node.rest.translation = node.translation;
    node.rest.rotation = node.rotation;
    node.rest.scale = node.scale;
    node.matrix.reset();
    ctx.warn("node " + str(index) + " is animated but has a matrix; decomposed into translation/rotation/scale");
}

}  // namespace

void loadAnimations(const Ctx& ctx) {
    for (size_t a = 0; a < ctx.model.animations.size(); ++a) {
        const auto& src = ctx.model.animations[a];
        const std::string where = "animation " + str(a);
        Animation anim;
        anim.name = src.name;
        for (size_t s = 0; s < src.samplers.size(); ++s)
            anim.samplers.push_back(loadSampler(ctx, src.samplers[s], where + " sampler " + str(s)));
        std::vector<bool> samplerUsed(anim.samplers.size(), false);
        for (size_t c = 0; c < src.channels.size(); ++c) {
            const auto& ch = src.channels[c];
            const std::string w = where + " channel " + str(c);
            if (ch.sampler < 0 || size_t(ch.sampler) >= anim.samplers.size())
                ctx.fail(w + ": sampler " + std::to_string(ch.sampler) + " out of range (animation has " +
                         str(anim.samplers.size()) + " samplers)");
            if (ch.target_node < 0) continue;  // the spec: a channel without a target node is ignored
            if (size_t(ch.target_node) >= ctx.scene.nodes.size())
                ctx.fail(w + ": target node " + std::to_string(ch.target_node) + " out of range (file has " +
                         str(ctx.scene.nodes.size()) + " nodes)");
            AnimationChannel channel;
            channel.sampler = uint32_t(ch.sampler);
            channel.node = uint32_t(ch.target_node);
            Node& node = ctx.scene.nodes[channel.node];
            size_t needed = 0;
            if (ch.target_path == "translation" || ch.target_path == "scale") {
                channel.path = ch.target_path == "scale" ? AnimationPath::Scale : AnimationPath::Translation;
                needed = 3;
            } else if (ch.target_path == "rotation") {
                channel.path = AnimationPath::Rotation;
                needed = 4;
            } else if (ch.target_path == "weights") {
                channel.path = AnimationPath::Weights;
                needed = node.weights.size();
                if (needed == 0) {
                    ctx.warn(w + ": weights on node " + str(size_t(channel.node)) +
                             ", which has no morph targets; channel skipped");
                    continue;
                }
            } else {
                ctx.warn(w + ": unsupported path '" + ch.target_path + "'; channel skipped");
                continue;
            }
            const AnimationSampler& sampler = anim.samplers[channel.sampler];
            if (sampler.components != needed)
                ctx.fail(w + ": path " + ch.target_path + " needs " + str(needed) + " values per keyframe, sampler " +
                         str(size_t(channel.sampler)) + " has " + str(size_t(sampler.components)));
            if (channel.path != AnimationPath::Weights) decomposeMatrix(ctx, node, channel.node);
            samplerUsed[channel.sampler] = true;
            anim.channels.push_back(channel);
        }
        bool first = true;
        for (size_t s = 0; s < anim.samplers.size(); ++s) {
            if (!samplerUsed[s]) continue;
            anim.start = first ? anim.samplers[s].times.front() : std::min(anim.start, anim.samplers[s].times.front());
            anim.end = first ? anim.samplers[s].times.back() : std::max(anim.end, anim.samplers[s].times.back());
            first = false;
        }
        ctx.scene.animations.push_back(std::move(anim));
    }
}

}  // namespace idk::scene::gltf
