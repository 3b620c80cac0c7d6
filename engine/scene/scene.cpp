// scene.cpp: Scene::features(), the summary of what the placed scene needs (skins, morphs, blending, textures,
// shadow-casting lights...) so the renderer allocates only that; IDKEngine's ModelLoader/ModelManager always
// allocate everything, which the port's "model only what a scene needs" rule replaces.
#include "scene/scene.hpp"

#include <algorithm>

namespace idk::scene {

SceneFeatures Scene::features() const {
    SceneFeatures f;
    f.hasAnimations = !animations.empty();
    std::vector<bool> materialUsed(materials.size(), false);
    for (const Instance& instance : instances) {
        const Mesh& mesh = meshes[instance.mesh];
        if (instance.skin && *instance.skin < skins.size()) {
            f.hasSkins = true;
            f.maxJoints = std::max(f.maxJoints, uint32_t(skins[*instance.skin].joints.size()));
        }
        if (!mesh.weights.empty()) {
            f.hasMorphs = true;
            f.maxMorphTargets = std::max(f.maxMorphTargets, uint32_t(mesh.weights.size()));
        }
        if (instance.gpuInstance > 0) f.hasGpuInstancing = true;
        for (const Primitive& prim : mesh.primitives) {
            if (prim.material && *prim.material < materials.size()) materialUsed[*prim.material] = true;
            f.hasVertexColors = f.hasVertexColors || !prim.colors.empty();
            f.hasUv1 = f.hasUv1 || !prim.uv1.empty();
        }
    }
    for (size_t i = 0; i < materials.size(); ++i) {
        if (!materialUsed[i]) continue;
        const Material& m = materials[i];
        f.hasBlend = f.hasBlend || m.alphaMode == AlphaMode::Blend;
        f.hasMask = f.hasMask || m.alphaMode == AlphaMode::Mask;
        const bool textured = m.baseColorTexture || m.metallicRoughnessTexture || m.normalTexture ||
                              m.occlusionTexture || m.emissiveTexture || m.transmissionTexture || m.thicknessTexture ||
                              m.specularTexture || m.specularColorTexture || m.clearcoatTexture ||
                              m.clearcoatRoughnessTexture || m.sheenColorTexture || m.sheenRoughnessTexture ||
                              (m.diffuseTransmission > 0.0f &&
                               (m.diffuseTransmissionTexture || m.diffuseTransmissionColorTexture)) ||
                              m.iridescenceTexture || m.iridescenceThicknessTexture || m.clearcoatNormalTexture ||
                              m.anisotropyTexture;
        f.hasTextures = f.hasTextures || textured;
        f.hasLayerTextures = f.hasLayerTextures || m.specularTexture || m.specularColorTexture ||
                             m.clearcoatTexture || m.clearcoatRoughnessTexture || m.sheenColorTexture ||
                             m.sheenRoughnessTexture || m.iridescenceTexture || m.iridescenceThicknessTexture ||
                             m.clearcoatNormalTexture || m.anisotropyTexture ||
                             (m.diffuseTransmission > 0.0f && !m.unlit &&
                              (m.diffuseTransmissionTexture || m.diffuseTransmissionColorTexture));
        if (!m.unlit) {  // the same conditions as the GPU material's flags (render/gpu_scene.cpp)
            const bool diffTransTextured = m.diffuseTransmission > 0.0f &&
                                           (m.diffuseTransmissionTexture || m.diffuseTransmissionColorTexture);
            const bool coatNormal = m.clearcoat > 0.0f && m.clearcoatNormalTexture.has_value();
            const bool anisotropic = m.anisotropyStrength > 0.0f;
            f.hasSpilledLayerTexels = f.hasSpilledLayerTexels ||
                                      (diffTransTextured && (m.iridescence > 0.0f || coatNormal || anisotropic)) ||
                                      (anisotropic && coatNormal);
        }
        f.hasNormalMaps = f.hasNormalMaps || m.normalTexture.has_value();
        f.hasTransmission = f.hasTransmission || m.transmission > 0.0f || m.transmissionTexture.has_value();
        f.hasVolume = f.hasVolume || m.thickness > 0.0f;
        f.hasUnlit = f.hasUnlit || m.unlit;
        f.hasEmissive = f.hasEmissive || m.emissive != glm::vec3(0.0f);
    }
    for (const Light& light : lights)
        if (light.intensity > 0.0f && light.color != glm::vec3(0.0f)) f.hasShadowCastingLights = true;
    return f;
}

}  // namespace idk::scene
