// pt_scene.cpp: geometry (per-mesh BLAS, deformed per-instance copies), TLAS and materials of a PathTraceScene.
#include "pathtrace/pt_scene.hpp"

#include <algorithm>
#include <cmath>

#include "pathtrace/texture_sampler.hpp"

namespace idk::pathtrace {

namespace {

// Maps object-space positions/normals/tangents of one vertex (identity for a shared mesh geometry).
struct VertexPlacement {
    bool skinned = false;
    const scene::Primitive* prim = nullptr;
    const scene::Node* node = nullptr;
    glm::mat4 world{1.0f};
    bool toWorld = false;
};

glm::mat4 skinMatrix(const VertexPlacement& pl, size_t v) {
    glm::mat4 skin(0.0f);
    float total = 0.0f;
    for (int j = 0; j < 4; ++j) {
        const float w = pl.prim->weights[v][j];
        const uint32_t joint = pl.prim->joints[v][j];
        if (w == 0.0f || joint >= pl.node->jointMatrices.size()) continue;
        skin += w * pl.node->jointMatrices[joint];
        total += w;
    }
    return total > 0.0f ? skin : glm::mat4(1.0f);
}

// Appends one primitive (morph targets at `weights`) to `g`, as render::meshTriangles orders triangles.
void appendPrimitive(PtGeometry& g, const scene::Primitive& prim, const std::vector<float>& weights,
                     uint32_t material, const VertexPlacement& pl) {
    const auto base = uint32_t(g.positions.size());
    for (size_t v = 0; v < prim.positions.size(); ++v) {
        glm::vec3 p = prim.positions[v];
        glm::vec3 n = v < prim.normals.size() ? prim.normals[v] : glm::vec3(0.0f, 0.0f, 1.0f);
        glm::vec4 t = v < prim.tangents.size() ? prim.tangents[v] : glm::vec4(0.0f);
        for (size_t k = 0; k < prim.targets.size() && k < weights.size(); ++k) {
            const scene::MorphTarget& mt = prim.targets[k];
            if (weights[k] == 0.0f) continue;
            if (!mt.positions.empty()) p += weights[k] * mt.positions[v];
            if (!mt.normals.empty()) n += weights[k] * mt.normals[v];
            if (!mt.tangents.empty() && t.w != 0.0f) t += glm::vec4(weights[k] * mt.tangents[v], 0.0f);
        }
        glm::mat4 m = pl.toWorld ? pl.world : glm::mat4(1.0f);
        if (pl.skinned) m = m * skinMatrix(pl, v);
        const glm::mat3 m3(m);
        const glm::mat3 nm = glm::transpose(glm::inverse(m3));
        g.positions.push_back(glm::vec3(m * glm::vec4(p, 1.0f)));
        g.normals.push_back(nm * n);
        g.tangents.push_back(glm::vec4(m3 * glm::vec3(t), t.w));
        g.uv0.push_back(v < prim.uv0.size() ? prim.uv0[v] : glm::vec2(0.0f));
        g.uv1.push_back(v < prim.uv1.size() ? prim.uv1[v] : glm::vec2(0.0f));
        g.colors.push_back(v < prim.colors.size() ? prim.colors[v] : glm::vec4(1.0f));
    }
    for (size_t i = 0; i + 2 < prim.indices.size(); i += 3) {
        g.triangles.push_back(glm::uvec3(prim.indices[i], prim.indices[i + 1], prim.indices[i + 2]) + base);
        g.triangleMaterial.push_back(material);
    }
}

bvh::Blas buildGeometryBlas(const PtGeometry& g) {
    std::vector<bvh::Triangle> tris(g.triangles.size());
    for (size_t i = 0; i < tris.size(); ++i)
        tris[i] = {g.positions[g.triangles[i].x], g.positions[g.triangles[i].y], g.positions[g.triangles[i].z]};
    return bvh::buildBlas(tris);
}

uint32_t materialOf(const scene::Scene& scene, const scene::Primitive& prim) {
    return prim.material && *prim.material < scene.materials.size() ? *prim.material
                                                                      : uint32_t(scene.materials.size());
}

bool emitsAny(const scene::Scene& scene, const scene::Mesh& mesh) {
    for (const scene::Primitive& prim : mesh.primitives)
        if (prim.material && *prim.material < scene.materials.size() &&
            scene.materials[*prim.material].emissive != glm::vec3(0.0f))
            return true;
    return false;
}

}  // namespace

bool hasGpuDeformation(const scene::Scene& scene, const scene::Instance& inst) {
    if (inst.mesh >= scene.meshes.size() || inst.node >= scene.nodes.size()) return false;
    const scene::Node& node = scene.nodes[inst.node];
    const bool skinnedNode = inst.skin && *inst.skin < scene.skins.size();
    for (const scene::Primitive& prim : scene.meshes[inst.mesh].primitives) {
        const size_t count = prim.positions.size();
        const bool skinned = skinnedNode && prim.joints.size() == count && prim.weights.size() == count;
        const bool morphed = !prim.targets.empty() && !node.weights.empty();
        if (!prim.indices.empty() && count > 0 && (skinned || morphed)) return true;
    }
    return false;
}

std::vector<gpu::GpuPtMaterial> packPtMaterials(const scene::Scene& scene) {
    std::vector<gpu::GpuPtMaterial> out;
    std::vector<scene::Material> all = scene.materials;
    all.push_back(scene::Material{});
    for (const scene::Material& m : all) {
        gpu::GpuPtMaterial p{};
        p.transmission = m.transmission;
        p.ior = m.ior;
        p.thickness = m.thickness;
        p.attenuationDistance = std::isfinite(m.attenuationDistance) ? m.attenuationDistance : 0.0f;
        p.attenuationColor = m.attenuationColor;
        p.transmissionTexture = gpu::kPtNoTexture;
        p.transmissionRow0 = glm::vec3(1.0f, 0.0f, 0.0f);
        p.transmissionRow1 = glm::vec3(0.0f, 1.0f, 0.0f);
        if (m.transmissionTexture && m.transmissionTexture->texture < scene.textures.size()) {
            p.transmissionTexture = m.transmissionTexture->texture;
            p.transmissionTexCoord = m.transmissionTexture->texCoord;
            textureTransformRows(*m.transmissionTexture, p.transmissionRow0, p.transmissionRow1);
        }
        p.specular = m.specular;
        p.specularColor = m.specularColor;
        p.clearcoat = m.clearcoat;
        p.clearcoatRoughness = m.clearcoatRoughness;
        p.sheenColor = m.sheenColor;
        p.sheenRoughness = m.sheenRoughness;
        p.anisotropyStrength = m.anisotropyStrength;
        p.anisotropyRotation = m.anisotropyRotation;
        out.push_back(p);
    }
    return out;
}

PathTraceScene buildPathTraceScene(const scene::Scene& scene, const core::ImageRgba32f* environment,
                                   float envIntensity, glm::vec3 constantRadiance, PtPosing posing) {
    PathTraceScene pts;
    pts.materials = scene.materials;
    pts.materials.push_back(scene::Material{});
    pts.ptMaterials = packPtMaterials(scene);
    for (const scene::Material& m : pts.materials)
        pts.alphaTesting |= m.alphaMode != scene::AlphaMode::Opaque;
    pts.textures = decodeSceneTextures(scene, pts.warnings);

    // Shared geometry per mesh (default weights, object space), built lazily.
    std::vector<int64_t> meshGeometry(scene.meshes.size(), -1);
    for (const scene::Instance& inst : scene.instances) {
        const scene::Mesh& mesh = scene.meshes.at(inst.mesh);
        const scene::Node& node = scene.nodes.at(inst.node);
        const std::vector<float>& weights = node.weights.empty() ? mesh.weights : node.weights;
        const bool skinned = inst.skin.has_value() && !node.jointMatrices.empty();
        const bool ownMorph = weights != mesh.weights;
        bvh::BlasInstance bi;
        bi.objectToWorld = inst.world;
        const bool gpuPosed =
            posing == PtPosing::Gpu && hasGpuDeformation(scene, inst) && !emitsAny(scene, mesh);
        if (gpuPosed) {  // its own object-space rest copy: the GPU writes the pose and refits the BLAS
            PtGeometry g;
            for (const scene::Primitive& prim : mesh.primitives)
                appendPrimitive(g, prim, mesh.weights, materialOf(scene, prim), VertexPlacement{});
            bi.blasIndex = uint32_t(pts.geometries.size());
            pts.gpuPosedInstances.push_back(uint32_t(pts.instances.size()));
            pts.geometries.push_back(std::move(g));
        } else if (skinned || ownMorph) {  // a world-space copy of its own
            pts.cpuPosedDeformation = true;
            PtGeometry g;
            for (const scene::Primitive& prim : mesh.primitives) {
                VertexPlacement pl;
                pl.prim = &prim;
                pl.node = &node;
                pl.world = inst.world;
                pl.toWorld = true;
                pl.skinned = skinned && prim.joints.size() == prim.positions.size() &&
                             prim.weights.size() == prim.positions.size();
                appendPrimitive(g, prim, weights, materialOf(scene, prim), pl);
            }
            bi.objectToWorld = glm::mat4(1.0f);
            bi.blasIndex = uint32_t(pts.geometries.size());
            pts.geometries.push_back(std::move(g));
        } else {
            if (meshGeometry[inst.mesh] < 0) {
                PtGeometry g;
                for (const scene::Primitive& prim : mesh.primitives)
                    appendPrimitive(g, prim, mesh.weights, materialOf(scene, prim), VertexPlacement{});
                meshGeometry[inst.mesh] = int64_t(pts.geometries.size());
                pts.geometries.push_back(std::move(g));
            }
            bi.blasIndex = uint32_t(meshGeometry[inst.mesh]);
        }
        const glm::mat3 m3(bi.objectToWorld);
        const float det = glm::determinant(m3);
        pts.normalMatrices.push_back(std::abs(det) > 0.0f ? glm::transpose(glm::inverse(m3)) : glm::mat3(1.0f));
        // World-space copies keep the winding of their placed transform (skinning is assumed not to mirror).
        pts.mirrored.push_back(glm::determinant(glm::mat3(inst.world)) < 0.0f ? 1 : 0);
        pts.instances.push_back(bi);
    }
    pts.blases.reserve(pts.geometries.size());
    for (const PtGeometry& g : pts.geometries) pts.blases.push_back(buildGeometryBlas(g));
    pts.tlas = bvh::buildTlas(pts.instances, pts.blases);

    bvh::Box bounds;
    for (const bvh::Box& b : pts.tlas.worldBoxes) bounds.grow(b);
    if (!bounds.isEmpty()) {
        pts.boundsCentre = 0.5f * (bounds.min + bounds.max);
        pts.boundsRadius = 0.5f * glm::length(bounds.max - bounds.min);
    }

    pts.environment = environment ? buildEnvironmentMap(*environment, envIntensity)
                                  : constantEnvironment(constantRadiance);
    buildLights(pts, scene);
    return pts;
}

}  // namespace idk::pathtrace
