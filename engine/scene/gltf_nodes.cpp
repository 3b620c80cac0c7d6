// gltf_nodes.cpp: the node half of the loader (IDKEngine's ModelLoader): hierarchy and TRS/matrix,
// EXT_mesh_gpu_instancing (per-instance TRS), morph weights, skins (joints, inverse bind matrices, kMaxJoints)
// with joint-index validation of skinned meshes, and placing one glTF scene: instances, cameras,
// KHR_lights_punctual lights, world matrices and the rest-pose bounds.
#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "scene/animation.hpp"
#include "scene/gltf_internal.hpp"
#include "scene/scene_graph.hpp"

namespace idk::scene::gltf {

namespace {

bool allFinite(const std::vector<float>& v) {
    return std::all_of(v.begin(), v.end(), [](float f) { return std::isfinite(f); });
}

// EXT_mesh_gpu_instancing: one local T * R * S matrix per instance.
std::vector<glm::mat4> instanceMatrices(const Ctx& ctx, const tinygltf::Value& ext, const std::string& where) {
    if (!ext.IsObject() || !ext.Has("attributes") || !ext.Get("attributes").IsObject())
        ctx.fail(where + ": attributes are required");
    const auto& attributes = ext.Get("attributes");
    std::vector<float> t, r, s;
    size_t count = SIZE_MAX;
    auto read = [&](const char* name, int components, std::vector<float>& out) {
        const auto index = indexOr(ctx, attributes, name, where);
        if (!index) return;
        out = readFloats(ctx, int(std::min<uint32_t>(*index, uint32_t(INT32_MAX))), components,
                         where + " " + name);
        if (!allFinite(out)) ctx.fail(where + " " + name + ": NaN or infinite values");
        const size_t n = out.size() / size_t(components);
        if (count != SIZE_MAX && n != count)
            ctx.fail(where + " " + name + ": " + str(n) + " instances, other attributes have " + str(count));
        count = n;
    };
    read("TRANSLATION", 3, t);
    read("ROTATION", 4, r);
    read("SCALE", 3, s);
    if (count == SIZE_MAX) ctx.fail(where + ": no TRANSLATION, ROTATION or SCALE attribute");
    std::vector<glm::mat4> out(count);
    for (size_t i = 0; i < count; ++i) {
        glm::mat4 m(1.0f);
        if (!t.empty()) m = glm::translate(m, glm::vec3(t[i * 3], t[i * 3 + 1], t[i * 3 + 2]));
        if (!r.empty()) {
            glm::quat q(r[i * 4 + 3], r[i * 4], r[i * 4 + 1], r[i * 4 + 2]);
            const float len = glm::length(q);
            m = m * glm::mat4_cast(len > 0.0f ? q / len : glm::quat(1.0f, 0.0f, 0.0f, 0.0f));
        }
        if (!s.empty()) m = glm::scale(m, glm::vec3(s[i * 3], s[i * 3 + 1], s[i * 3 + 2]));
        out[i] = m;
    }
    return out;
}

Camera makeCamera(const Ctx& ctx, const tinygltf::Camera& src, size_t index) {
    Camera cam;
    cam.name = src.name;
    const std::string where = "camera " + str(index);
    if (src.type == "orthographic") {
        const auto& o = src.orthographic;
        cam.type = CameraType::Orthographic;
        cam.xmag = float(o.xmag);
        cam.ymag = float(o.ymag);
        cam.znear = float(o.znear);
        cam.zfar = float(o.zfar);
        if (!(cam.xmag != 0.0f && cam.ymag != 0.0f && cam.znear >= 0.0f && cam.zfar > cam.znear)) {
            ctx.warn(where + ": invalid orthographic parameters; using xmag = ymag = 1, znear 0.01, zfar 100");
            cam.xmag = cam.ymag = 1.0f;
            cam.znear = 0.01f;
            cam.zfar = 100.0f;
        }
    } else {
        const auto& p = src.perspective;
        cam.yfov = float(p.yfov);
        cam.aspectRatio = float(p.aspectRatio);
        cam.znear = float(p.znear);
        cam.zfar = float(p.zfar);
        const float pi = 3.14159265f;
        if (!(cam.yfov > 0.0f && cam.yfov < pi && cam.znear > 0.0f && cam.aspectRatio >= 0.0f &&
              (cam.zfar == 0.0f || cam.zfar > cam.znear))) {
            ctx.warn(where + ": invalid perspective parameters; using yfov 45 degrees, znear 0.1, infinite far");
            cam.yfov = glm::radians(45.0f);
            cam.aspectRatio = 0.0f;
            cam.znear = 0.1f;
            cam.zfar = 0.0f;
        }
    }
    return cam;
}

bool makeLight(const Ctx& ctx, const tinygltf::Light& src, size_t index, Light& light) {
    light.name = src.name;
    if (src.type == "directional")
        light.type = LightType::Directional;
    else if (src.type == "point")
        light.type = LightType::Point;
    else if (src.type == "spot")
        light.type = LightType::Spot;
    else {
        ctx.warn("light " + str(index) + ": unknown type '" + src.type + "'; skipped");
        return false;
    }
    light.color = factor<3>(src.color, glm::vec3(1.0f));
    light.intensity = float(src.intensity);
    light.range = float(src.range);
    light.innerConeAngle = float(src.spot.innerConeAngle);
    light.outerConeAngle = float(src.spot.outerConeAngle);
    return true;
}


std::optional<size_t> nodeLightIndex(const Ctx& ctx, const tinygltf::Node& src, size_t nodeIndex) {
    const auto it = src.extensions.find("KHR_lights_punctual");
    if (it == src.extensions.end() || !it->second.IsObject() || !it->second.Has("light")) return std::nullopt;
    const auto& v = it->second.Get("light");
    const double d = v.IsNumber() ? v.GetNumberAsDouble() : -1.0;
    if (!(d >= 0.0 && d < double(ctx.model.lights.size())))
        ctx.fail("node " + str(nodeIndex) + ": KHR_lights_punctual light index out of range (file has " +
                 str(ctx.model.lights.size()) + " lights)");
    return size_t(d);
}

}  // namespace

void loadNodes(const Ctx& ctx) {
    const auto& model = ctx.model;
    auto& nodes = ctx.scene.nodes;
    nodes.resize(model.nodes.size());
    for (size_t i = 0; i < model.nodes.size(); ++i) {
        const auto& src = model.nodes[i];
        const std::string where = "node " + str(i);
        Node& node = nodes[i];
        node.name = src.name;
        if (!src.matrix.empty()) {
            if (src.matrix.size() != 16) ctx.fail(where + ": matrix must have 16 numbers");
            glm::mat4 m;
            for (int k = 0; k < 16; ++k) glm::value_ptr(m)[k] = float(src.matrix[size_t(k)]);  // column-major
            node.matrix = m;
        }
        if (!src.translation.empty()) {
            if (src.translation.size() != 3) ctx.fail(where + ": translation must have 3 numbers");
            node.translation = factor<3>(src.translation, glm::vec3(0.0f));
        }
        if (!src.rotation.empty()) {
            if (src.rotation.size() != 4) ctx.fail(where + ": rotation must have 4 numbers");
            const auto& r = src.rotation;  // glTF order x, y, z, w
            node.rotation = glm::quat(float(r[3]), float(r[0]), float(r[1]), float(r[2]));
        }
        if (!src.scale.empty()) {
            if (src.scale.size() != 3) ctx.fail(where + ": scale must have 3 numbers");
            node.scale = factor<3>(src.scale, glm::vec3(1.0f));
        }
        if (src.mesh >= 0) {
            if (size_t(src.mesh) >= model.meshes.size())
                ctx.fail(where + ": mesh " + std::to_string(src.mesh) + " out of range (file has " +
                         str(model.meshes.size()) + ")");
            node.mesh = uint32_t(src.mesh);
            const auto& meshWeights = ctx.scene.meshes[*node.mesh].weights;
            node.weights = meshWeights;
            if (!src.weights.empty()) {
                if (src.weights.size() == meshWeights.size())
                    for (size_t w = 0; w < src.weights.size(); ++w) node.weights[w] = float(src.weights[w]);
                else
                    ctx.warn(where + ": " + str(src.weights.size()) + " morph weights for " + str(meshWeights.size()) +
                             " targets; using the mesh's");
            }
        }
        if (src.skin >= 0) {
            if (size_t(src.skin) >= model.skins.size())
                ctx.fail(where + ": skin " + std::to_string(src.skin) + " out of range (file has " +
                         str(model.skins.size()) + ")");
            if (node.mesh) node.skin = uint32_t(src.skin);
        }
        if (src.camera >= 0 && size_t(src.camera) >= model.cameras.size())
            ctx.fail(where + ": camera " + std::to_string(src.camera) + " out of range (file has " +
                     str(model.cameras.size()) + ")");
        for (const int child : src.children) {
            if (child < 0 || size_t(child) >= model.nodes.size())
                ctx.fail(where + ": child " + std::to_string(child) + " out of range (file has " +
                         str(model.nodes.size()) + ")");
            if (nodes[size_t(child)].parent || size_t(child) == i)
                ctx.fail(where + ": node " + std::to_string(child) +
                         " has more than one parent (the hierarchy must be a tree)");
            nodes[size_t(child)].parent = uint32_t(i);
            node.children.push_back(uint32_t(child));
        }
        if (const auto* ext = extension(src.extensions, "EXT_mesh_gpu_instancing")) {
            if (node.mesh)
                node.instanceMatrices = instanceMatrices(ctx, *ext, where + " EXT_mesh_gpu_instancing");
            else
                ctx.warn(where + ": EXT_mesh_gpu_instancing on a node without a mesh; ignored");
        }
        node.rest = {node.translation, node.rotation, node.scale, node.weights};
    }
}

void loadSkins(const Ctx& ctx) {
    const auto& model = ctx.model;
    for (size_t s = 0; s < model.skins.size(); ++s) {
        const auto& src = model.skins[s];
        const std::string where = "skin " + str(s);
        if (src.joints.size() > kMaxJoints)
            ctx.fail(where + " has " + str(src.joints.size()) + " joints; at most " + str(size_t(kMaxJoints)) +
                     " (kMaxJoints) are supported");
        if (src.joints.empty()) ctx.fail(where + " has no joints");
        Skin skin;
        skin.name = src.name;
        for (const int j : src.joints) {
            if (j < 0 || size_t(j) >= model.nodes.size())
                ctx.fail(where + ": joint node " + std::to_string(j) + " out of range (file has " +
                         str(model.nodes.size()) + ")");
            skin.joints.push_back(uint32_t(j));
        }
        if (src.skeleton >= 0) {
            if (size_t(src.skeleton) >= model.nodes.size())
                ctx.fail(where + ": skeleton node " + std::to_string(src.skeleton) + " out of range");
            skin.skeleton = uint32_t(src.skeleton);
        }
        skin.inverseBindMatrices.assign(skin.joints.size(), glm::mat4(1.0f));
        if (src.inverseBindMatrices >= 0) {
            const auto m = readFloats(ctx, src.inverseBindMatrices, 16, where + " inverseBindMatrices");
            if (m.size() / 16 < skin.joints.size())
                ctx.fail(where + ": " + str(m.size() / 16) + " inverseBindMatrices for " + str(skin.joints.size()) +
                         " joints");
            if (!allFinite(m)) ctx.fail(where + ": inverseBindMatrices contain NaN or infinite values");
            for (size_t j = 0; j < skin.joints.size(); ++j)
                skin.inverseBindMatrices[j] = glm::make_mat4(m.data() + j * 16);
        }
        ctx.scene.skins.push_back(std::move(skin));
    }
    // Every joint index a skinned node's vertices use must name a joint of its skin; indices with weight 0 are
    // harmless and set to 0, any other out-of-range index is an error (the GPU would read past the palette).
    for (size_t n = 0; n < ctx.scene.nodes.size(); ++n) {
        const Node& node = ctx.scene.nodes[n];
        if (!node.skin) continue;
        const size_t jointCount = ctx.scene.skins[*node.skin].joints.size();
        auto& mesh = ctx.scene.meshes[*node.mesh];
        for (size_t p = 0; p < mesh.primitives.size(); ++p) {
            Primitive& prim = mesh.primitives[p];
            for (size_t v = 0; v < prim.joints.size(); ++v)
                for (int c = 0; c < 4; ++c) {
                    if (prim.joints[v][c] < jointCount) continue;
                    if (prim.weights[v][c] != 0.0f)
                        ctx.fail("mesh " + str(size_t(*node.mesh)) + " JOINTS_0: vertex " + str(v) + " uses joint " +
                                 str(size_t(prim.joints[v][c])) + ", but skin " + str(size_t(*node.skin)) +
                                 " of node " + str(n) + " has " + str(jointCount) + " joints");
                    prim.joints[v][c] = 0;
                }
        }
    }
}

void placeScene(const Ctx& ctx) {
    const auto& model = ctx.model;
    auto& scene = ctx.scene;
    if (model.defaultScene >= 0 && size_t(model.defaultScene) >= model.scenes.size())
        ctx.fail("default scene " + std::to_string(model.defaultScene) + " out of range (file has " +
                 str(model.scenes.size()) + " scenes)");
    if (ctx.options.scene && *ctx.options.scene >= std::max<size_t>(model.scenes.size(), 1))
        ctx.fail("scene " + str(size_t(*ctx.options.scene)) + " requested, the file has " + str(model.scenes.size()) +
                 " scenes");
    if (!updateNodeWorlds(scene.nodes)) ctx.fail("the node hierarchy contains a cycle");
    for (const auto& s : model.scenes) scene.sceneNames.push_back(s.name);
    scene.sceneIndex = ctx.options.scene.value_or(uint32_t(std::max(model.defaultScene, 0)));
    if (!model.scenes.empty()) {
        for (const int root : model.scenes[scene.sceneIndex].nodes) {
            if (root < 0 || size_t(root) >= scene.nodes.size())
                ctx.fail("scene root node " + std::to_string(root) + " out of range (file has " +
                         str(scene.nodes.size()) + ")");
            if (scene.nodes[size_t(root)].parent)
                ctx.fail("scene root node " + std::to_string(root) + " is a child of another node");
            if (std::find(scene.rootNodes.begin(), scene.rootNodes.end(), uint32_t(root)) == scene.rootNodes.end())
                scene.rootNodes.push_back(uint32_t(root));
        }
    } else {
        for (uint32_t i = 0; i < scene.nodes.size(); ++i)
            if (!scene.nodes[i].parent) scene.rootNodes.push_back(i);
    }

    std::vector<uint32_t> stack;
    for (const uint32_t root : scene.rootNodes) {
        stack.assign(1, root);
        while (!stack.empty()) {
            const uint32_t n = stack.back();
            stack.pop_back();
            Node& node = scene.nodes[n];
            for (auto it = node.children.rbegin(); it != node.children.rend(); ++it) stack.push_back(*it);
            const auto& src = model.nodes[n];
            if (node.mesh && !scene.meshes[*node.mesh].primitives.empty()) {
                const size_t copies = std::max<size_t>(node.instanceMatrices.size(), 1);
                for (size_t i = 0; i < copies; ++i)
                    scene.instances.push_back({*node.mesh, n, glm::mat4(1.0f), uint32_t(i), node.skin});
            }
            if (src.camera >= 0) {
                Camera cam = makeCamera(ctx, model.cameras[size_t(src.camera)], size_t(src.camera));
                cam.node = n;
                node.camera = uint32_t(scene.cameras.size());
                scene.cameras.push_back(std::move(cam));
            }
            if (const auto li = nodeLightIndex(ctx, src, n)) {
                Light light;
                if (makeLight(ctx, model.lights[*li], *li, light)) {
                    light.node = n;
                    node.light = uint32_t(scene.lights.size());
                    scene.lights.push_back(std::move(light));
                }
            }
        }
    }
    updateTransforms(scene);
    for (const Instance& instance : scene.instances)
        for (const Primitive& prim : scene.meshes[instance.mesh].primitives)
            for (uint32_t v = 0; v < prim.positions.size(); ++v)
                scene.bounds.extend(deformedPosition(scene, instance, prim, v));
}

}  // namespace idk::scene::gltf
