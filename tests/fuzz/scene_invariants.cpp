// scene_invariants.cpp: see scene_invariants.hpp.
#include "scene_invariants.hpp"

#include <optional>

namespace idk::fuzz {
namespace {

template <class T>
bool optIn(const std::optional<uint32_t>& index, const std::vector<T>& v) {
    return !index || *index < v.size();
}

std::string primitiveProblem(const scene::Scene& s, const scene::Primitive& p) {
    const size_t n = p.positions.size();
    auto sized = [&](size_t count) { return count == 0 || count == n; };
    if (p.normals.size() != n) return "normals count differs from positions";
    if (!sized(p.uv0.size()) || !sized(p.uv1.size()) || !sized(p.colors.size()) || !sized(p.tangents.size()) ||
        !sized(p.joints.size()) || !sized(p.weights.size()))
        return "a vertex attribute has neither 0 nor positions.size() entries";
    if (p.indices.size() % 3 != 0) return "index count not a multiple of 3";
    for (const uint32_t i : p.indices)
        if (i >= n) return "index " + std::to_string(i) + " >= vertex count " + std::to_string(n);
    if (!optIn(p.material, s.materials)) return "primitive material out of range";
    for (const auto& t : p.targets)
        if (!sized(t.positions.size()) || !sized(t.normals.size()) || !sized(t.tangents.size()))
            return "morph target array size differs from positions";
    return {};
}

std::string materialProblem(const scene::Scene& s, const scene::Material& m) {
    for (const auto* ref : {&m.baseColorTexture, &m.metallicRoughnessTexture, &m.normalTexture, &m.occlusionTexture,
                            &m.emissiveTexture, &m.transmissionTexture, &m.thicknessTexture, &m.specularTexture,
                            &m.specularColorTexture, &m.clearcoatTexture, &m.clearcoatRoughnessTexture,
                            &m.sheenColorTexture, &m.sheenRoughnessTexture, &m.iridescenceTexture,
                            &m.iridescenceThicknessTexture, &m.clearcoatNormalTexture, &m.anisotropyTexture})
        if (*ref && (*ref)->texture >= s.textures.size()) return "material texture index out of range";
    return {};
}

}  // namespace

std::string firstBrokenInvariant(const scene::Scene& s) {
    for (const auto& mesh : s.meshes)
        for (const auto& p : mesh.primitives)
            if (std::string problem = primitiveProblem(s, p); !problem.empty()) return problem;
    for (const auto& m : s.materials)
        if (std::string problem = materialProblem(s, m); !problem.empty()) return problem;
    for (const auto& t : s.textures)
        if (!optIn(t.image, s.images)) return "texture image index out of range";
    for (const auto& node : s.nodes) {
        if (!optIn(node.mesh, s.meshes) || !optIn(node.parent, s.nodes) || !optIn(node.camera, s.cameras) ||
            !optIn(node.light, s.lights) || !optIn(node.skin, s.skins))
            return "node index out of range";
        for (const uint32_t child : node.children)
            if (child >= s.nodes.size()) return "node child out of range";
    }
    for (const uint32_t root : s.rootNodes)
        if (root >= s.nodes.size()) return "root node out of range";
    for (const auto& inst : s.instances)
        if (inst.mesh >= s.meshes.size() || inst.node >= s.nodes.size() || !optIn(inst.skin, s.skins))
            return "instance index out of range";
    for (const auto& skin : s.skins) {
        if (skin.joints.size() > scene::kMaxJoints) return "skin with more than kMaxJoints joints";
        if (skin.inverseBindMatrices.size() != skin.joints.size()) return "inverse bind matrix count != joint count";
        for (const uint32_t j : skin.joints)
            if (j >= s.nodes.size()) return "skin joint out of range";
    }
    for (const auto& a : s.animations) {
        for (const auto& c : a.channels)
            if (c.sampler >= a.samplers.size() || c.node >= s.nodes.size()) return "animation channel out of range";
        for (const auto& sampler : a.samplers)
            for (size_t k = 1; k < sampler.times.size(); ++k)
                if (!(sampler.times[k - 1] <= sampler.times[k])) return "keyframe times decrease or are NaN";
    }
    return {};
}

}  // namespace idk::fuzz
