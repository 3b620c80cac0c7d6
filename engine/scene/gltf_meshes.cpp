// gltf_meshes.cpp: glTF meshes -> Scene::meshes for the loader (the geometry half of IDKEngine's ModelLoader):
// every vertex attribute (POSITION, NORMAL, TANGENT, TEXCOORD_0/1, COLOR_0, JOINTS_0, WEIGHTS_0) from accessors
// or Draco, morph targets, strips/fans triangulated, flat normals when absent, tangents generated from the UVs
// when absent, non-finite values handled as gltf_loader.hpp documents.
#include <cmath>
#include <map>
#include <numeric>
#include <set>

#include "scene/gltf_internal.hpp"
#include "scene/primitive_ops.hpp"

namespace idk::scene::gltf {

namespace {

const char* modeName(int mode) {
    switch (mode) {
        case TINYGLTF_MODE_POINTS: return "POINTS";
        case TINYGLTF_MODE_LINE: return "LINES";
        case TINYGLTF_MODE_LINE_LOOP: return "LINE_LOOP";
        case TINYGLTF_MODE_LINE_STRIP: return "LINE_STRIP";
        case TINYGLTF_MODE_TRIANGLES: return "TRIANGLES";
        case TINYGLTF_MODE_TRIANGLE_STRIP: return "TRIANGLE_STRIP";
        case TINYGLTF_MODE_TRIANGLE_FAN: return "TRIANGLE_FAN";
        default: return "unknown mode";
    }
}

// Turns strips and fans into a triangle list, with the vertex order the glTF spec gives (keeps the winding).
std::vector<uint32_t> triangulate(const std::vector<uint32_t>& v, int mode) {
    std::vector<uint32_t> out;
    if (mode == TINYGLTF_MODE_TRIANGLES) {
        out.assign(v.begin(), v.begin() + std::ptrdiff_t(v.size() - v.size() % 3));
    } else if (v.size() >= 3) {
        out.reserve((v.size() - 2) * 3);
        for (size_t i = 0; i + 2 < v.size(); ++i) {
            if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
                const bool odd = (i % 2) == 1;
                out.insert(out.end(), {v[i], v[odd ? i + 2 : i + 1], v[odd ? i + 1 : i + 2]});
            } else {  // fan
                out.insert(out.end(), {v[i + 1], v[i + 2], v[0]});
            }
        }
    }
    return out;
}

const std::set<std::string> kLoadedAttributes = {"POSITION",   "NORMAL",  "TANGENT",  "TEXCOORD_0",
                                                 "TEXCOORD_1", "COLOR_0", "JOINTS_0", "WEIGHTS_0"};

// Reads one attribute of a primitive: from the Draco data when it holds it, else from the accessor.
class AttributeReader {
public:
    AttributeReader(const Ctx& ctx, const std::map<std::string, int>& attributes, const DracoGeometry* draco,
                    std::string where)
        : ctx_(ctx), attributes_(attributes), draco_(draco), where_(std::move(where)) {}

    bool has(const std::string& name) const { return attributes_.count(name) > 0; }

    // Floats with the attribute's component count checked against `allowed` (bit c set: c components allowed).
    std::vector<float> read(const std::string& name, unsigned allowed, size_t vertexCount, int* components) const {
        const std::string usage = where_ + " " + name;
        std::vector<float> values;
        if (draco_ != nullptr && draco_->attributes.count(name) > 0) {
            const DecodedAttribute& d = draco_->attributes.at(name);
            values = d.values;
            *components = d.components;
        } else {
            values = readAnyFloats(ctx_, attributes_.at(name), usage, components);
        }
        if (*components > 4 || ((allowed >> *components) & 1u) == 0) {
            std::string valid;
            for (int c = 1; c <= 4; ++c)
                if ((allowed >> c) & 1u) valid += (valid.empty() ? "" : " or ") + str(c);
            ctx_.fail(usage + " (" + accessorOf(name) + "): type must have " + valid + " components, not " +
                      str(*components));
        }
        const size_t count = values.size() / size_t(*components);
        if (vertexCount != SIZE_MAX && count != vertexCount)
            ctx_.fail(usage + ": has " + str(count) + " elements, POSITION has " + str(vertexCount));
        return values;
    }

    template <int N>
    std::vector<glm::vec<N, float>> vectors(const std::string& name, size_t vertexCount) const {
        int comps = 0;
        return toVectors<N>(read(name, 1u << N, vertexCount, &comps));
    }

    // Which accessor a non-Draco attribute comes from (for messages).
    std::string accessorOf(const std::string& name) const {
        if (draco_ != nullptr && draco_->attributes.count(name) > 0) return "Draco data";
        return "accessor " + str(attributes_.at(name));
    }

private:
    const Ctx& ctx_;
    const std::map<std::string, int>& attributes_;
    const DracoGeometry* draco_;
    std::string where_;
};

// Replaces non-finite components with 0; returns how many there were.
template <class V>
size_t zeroNonFinite(std::vector<V>& values) {
    size_t bad = 0;
    for (auto& v : values)
        for (int c = 0; c < V::length(); ++c)
            if (!std::isfinite(v[c])) {
                v[c] = 0.0f;
                ++bad;
            }
    return bad;
}

// The UV set tangents are generated from: the one the material's normal map samples, if present.
uint32_t tangentUvSet(const Ctx& ctx, const Primitive& prim) {
    uint32_t set = 0;
    if (prim.material && *prim.material < ctx.scene.materials.size()) {
        const auto& normal = ctx.scene.materials[*prim.material].normalTexture;
        if (normal && normal->texCoord == 1) set = 1;
    }
    if (set == 1 && prim.uv1.empty()) set = 0;
    if (set == 0 && prim.uv0.empty() && !prim.uv1.empty()) set = 1;
    return set;
}

// Reads one primitive; false when it is skipped (a warning says why).
bool readPrimitive(const Ctx& ctx, const tinygltf::Primitive& sp, const std::string& where, Primitive& prim,
                   std::set<std::string>& ignored) {
    const std::optional<DracoGeometry> draco = decodeDraco(ctx, sp, where);
    const AttributeReader in(ctx, sp.attributes, draco ? &*draco : nullptr, where);
    if (!in.has("POSITION")) {
        ctx.warn(where + " has no POSITION attribute; skipped");
        return false;
    }
    prim.positions = in.vectors<3>("POSITION", SIZE_MAX);
    const size_t n = prim.positions.size();
    size_t nonFinite = 0;
    for (const auto& p : prim.positions) nonFinite += !std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z);
    if (nonFinite > 0) {
        ctx.warn(where + " POSITION (" + in.accessorOf("POSITION") + "): " + str(nonFinite) +
                 " vertices are NaN or infinite; primitive skipped");
        return false;
    }
    if (in.has("NORMAL")) prim.normals = in.vectors<3>("NORMAL", n);
    if (in.has("TANGENT")) prim.tangents = in.vectors<4>("TANGENT", n);
    if (in.has("TEXCOORD_0")) prim.uv0 = in.vectors<2>("TEXCOORD_0", n);
    if (in.has("TEXCOORD_1")) prim.uv1 = in.vectors<2>("TEXCOORD_1", n);
    if (in.has("COLOR_0")) {
        int comps = 0;
        const auto flat = in.read("COLOR_0", (1u << 3) | (1u << 4), n, &comps);
        prim.colors.resize(n);
        for (size_t i = 0; i < n; ++i)
            prim.colors[i] = glm::vec4(flat[i * size_t(comps)], flat[i * size_t(comps) + 1],
                                       flat[i * size_t(comps) + 2], comps == 4 ? flat[i * 4 + 3] : 1.0f);
    }
    if (in.has("JOINTS_0")) {
        if (!draco) {
            const auto& acc = accessorAt(ctx, sp.attributes.at("JOINTS_0"), where + " JOINTS_0");
            if (acc.normalized || (acc.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
                                   acc.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT))
                ctx.fail(where + " JOINTS_0: must be unnormalized UNSIGNED_BYTE or UNSIGNED_SHORT");
        }
        const auto joints = in.vectors<4>("JOINTS_0", n);
        prim.joints.resize(n);
        for (size_t i = 0; i < n; ++i)
            for (int c = 0; c < 4; ++c) {
                const float j = joints[i][c];
                if (!(j >= 0.0f && j <= 65535.0f)) ctx.fail(where + " JOINTS_0: invalid joint index");
                prim.joints[i][c] = uint32_t(j);
            }
    }
    if (in.has("WEIGHTS_0")) prim.weights = in.vectors<4>("WEIGHTS_0", n);
    if (prim.joints.empty() != prim.weights.empty()) {
        ctx.warn(where + ": JOINTS_0 without WEIGHTS_0 (or the reverse); skinning data ignored");
        prim.joints.clear();
        prim.weights.clear();
    }
    for (const auto& [name, accessor] : sp.attributes)
        if (kLoadedAttributes.count(name) == 0) ignored.insert(name);

    for (size_t t = 0; t < sp.targets.size(); ++t) {
        const AttributeReader target(ctx, sp.targets[t], nullptr, where + " target " + str(t));
        MorphTarget mt;
        if (target.has("POSITION")) mt.positions = target.vectors<3>("POSITION", n);
        if (target.has("NORMAL")) mt.normals = target.vectors<3>("NORMAL", n);
        if (target.has("TANGENT")) mt.tangents = target.vectors<3>("TANGENT", n);
        if (zeroNonFinite(mt.positions) + zeroNonFinite(mt.normals) + zeroNonFinite(mt.tangents) > 0)
            ctx.warn(where + " target " + str(t) + ": NaN or infinite deltas replaced by 0");
        prim.targets.push_back(std::move(mt));
    }
    const size_t badAttributes = zeroNonFinite(prim.normals) + zeroNonFinite(prim.tangents) + zeroNonFinite(prim.uv0) +
                                 zeroNonFinite(prim.uv1) + zeroNonFinite(prim.colors) + zeroNonFinite(prim.weights);
    if (badAttributes > 0)
        ctx.warn(where + ": " + str(badAttributes) + " NaN or infinite attribute components replaced by 0");

    std::vector<uint32_t> raw;
    if (draco) {
        raw = draco->indices;  // always a triangle list
    } else if (sp.indices >= 0) {
        raw = readIndices(ctx, sp.indices, where + " indices");
    } else {
        raw.resize(n);
        std::iota(raw.begin(), raw.end(), 0u);
    }
    for (const uint32_t i : raw)
        if (i >= n) ctx.fail(where + ": index " + std::to_string(i) + " out of range (" + str(n) + " vertices)");
    const int mode = draco ? TINYGLTF_MODE_TRIANGLES : sp.mode;
    if (mode == TINYGLTF_MODE_TRIANGLES && raw.size() % 3 != 0)
        ctx.warn(where + ": " + str(raw.size()) + " indices is not a multiple of 3; the rest is ignored");
    prim.indices = triangulate(raw, mode);
    if (sp.material >= 0) {
        if (size_t(sp.material) >= ctx.model.materials.size())
            ctx.fail(where + ": material " + std::to_string(sp.material) + " out of range (file has " +
                     str(ctx.model.materials.size()) + ")");
        prim.material = uint32_t(sp.material);
    }
    loadVariantMappings(ctx, sp.extensions, prim, where);
    if (prim.indices.empty()) {
        ctx.warn(where + " has no triangles; skipped");
        return false;
    }
    if (prim.normals.empty()) makeFlatNormals(prim);
    if (prim.tangents.empty()) {
        generateTangents(prim, tangentUvSet(ctx, prim));
    } else {
        for (auto& t : prim.tangents) t.w = t.w < 0.0f ? -1.0f : 1.0f;  // the spec's +-1, robust to quantization
    }
    return true;
}

}  // namespace

void loadMeshes(const Ctx& ctx) {
    std::map<std::string, int> skippedModes;
    std::set<std::string> ignored;
    for (size_t m = 0; m < ctx.model.meshes.size(); ++m) {
        const auto& src = ctx.model.meshes[m];
        Mesh mesh;
        mesh.name = src.name;
        std::optional<size_t> targetCount;
        if (!src.weights.empty()) targetCount = src.weights.size();
        for (size_t p = 0; p < src.primitives.size(); ++p) {
            const auto& sp = src.primitives[p];
            const std::string where = "mesh " + str(m) + " primitive " + str(p);
            if (sp.mode != TINYGLTF_MODE_TRIANGLES && sp.mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
                sp.mode != TINYGLTF_MODE_TRIANGLE_FAN) {
                skippedModes[modeName(sp.mode)]++;
                continue;
            }
            if (targetCount && sp.targets.size() != *targetCount)
                ctx.fail(where + ": " + str(sp.targets.size()) + " morph targets, but the mesh has " +
                         str(*targetCount) + (src.weights.empty() ? " in another primitive" : " weights"));
            targetCount = sp.targets.size();
            Primitive prim;
            if (readPrimitive(ctx, sp, where, prim, ignored)) mesh.primitives.push_back(std::move(prim));
        }
        mesh.weights.assign(targetCount.value_or(0), 0.0f);
        for (size_t i = 0; i < src.weights.size(); ++i) mesh.weights[i] = float(src.weights[i]);
        ctx.scene.meshes.push_back(std::move(mesh));
    }
    if (!skippedModes.empty()) {
        std::string list;
        for (const auto& [name, count] : skippedModes)
            list += (list.empty() ? "" : ", ") + name + " x" + std::to_string(count);
        ctx.warn("skipped primitives that are not triangles (" + list +
                 "); only triangle lists, strips and fans are loaded");
    }
    if (!ignored.empty()) {
        std::string list;
        for (const auto& name : ignored) list += (list.empty() ? "" : ", ") + name;
        ctx.warn("ignored vertex attributes: " + list);
    }
}

}  // namespace idk::scene::gltf
