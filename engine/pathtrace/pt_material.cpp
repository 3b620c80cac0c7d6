// pt_material.cpp: hit attributes and glTF material evaluation for the CPU path tracer.
#include "pathtrace/pt_material.hpp"

#include <algorithm>
#include <cmath>

#include "shared/pt_anisotropy.h"

namespace idk::pathtrace {

namespace {

glm::vec3 safeNormalize(const glm::vec3& v, const glm::vec3& fallback) {
    const float l2 = glm::dot(v, v);
    return l2 > 1e-30f && std::isfinite(l2) ? v / std::sqrt(l2) : fallback;
}

glm::vec4 sampleRef(const PathTraceScene& pts, const std::optional<scene::TextureRef>& ref, const PtHitPoint& hit,
                    bool srgb) {
    if (!ref || ref->texture >= pts.textures.size()) return glm::vec4(1.0f);
    const glm::vec2 uv = transformUv(*ref, ref->texCoord == 1 ? hit.uv1 : hit.uv0);
    return sampleTexture(pts.textures[ref->texture], uv, srgb);
}

// Normal mapping in the vertex tangent frame (B = cross(N, T) * w), z rebuilt from the remapped xy; n when the
// hit has no usable tangent.
glm::vec3 mapNormal(const PtHitPoint& hit, const glm::vec4& texel, float scale) {
    const glm::vec3 n = hit.normal;
    if (hit.tangent.w == 0.0f) return n;
    glm::vec3 t = glm::vec3(hit.tangent) - n * glm::dot(n, glm::vec3(hit.tangent));
    const float len2 = glm::dot(t, t);
    if (!(len2 > 1e-20f)) return n;
    t /= std::sqrt(len2);
    const glm::vec3 b = glm::cross(n, t) * hit.tangent.w;
    const glm::vec2 xy = glm::vec2(texel) * 2.0f - 1.0f;
    const glm::vec3 tn(xy * scale, std::sqrt(std::max(1.0f - glm::dot(xy, xy), 0.0f)));
    return safeNormalize(t * tn.x + b * tn.y + n * tn.z, n);
}

}  // namespace

PtHitPoint hitPoint(const PathTraceScene& pts, uint32_t instance, uint32_t triangle, float u, float v) {
    PtHitPoint h;
    const bvh::BlasInstance& inst = pts.instances.at(instance);
    const PtGeometry& g = pts.geometries.at(inst.blasIndex);
    const glm::uvec3 tri = g.triangles.at(triangle);
    const float w = 1.0f - u - v;
    h.instance = instance;
    h.triangle = triangle;
    h.material = g.triangleMaterial[triangle];
    const glm::mat4& m = inst.objectToWorld;
    const glm::mat3& nm = pts.normalMatrices[instance];
    const glm::vec3 p0 = glm::vec3(m * glm::vec4(g.positions[tri.x], 1.0f));
    const glm::vec3 p1 = glm::vec3(m * glm::vec4(g.positions[tri.y], 1.0f));
    const glm::vec3 p2 = glm::vec3(m * glm::vec4(g.positions[tri.z], 1.0f));
    h.position = w * p0 + u * p1 + v * p2;
    const float flip = pts.mirrored[instance] ? -1.0f : 1.0f;
    const glm::vec3 ng = safeNormalize(glm::cross(p1 - p0, p2 - p0) * flip, glm::vec3(0.0f, 0.0f, 1.0f));
    h.geometricNormal = ng;
    const glm::vec3 n = w * g.normals[tri.x] + u * g.normals[tri.y] + v * g.normals[tri.z];
    h.normal = safeNormalize(nm * n, ng);
    const glm::vec4 t = w * g.tangents[tri.x] + u * g.tangents[tri.y] + v * g.tangents[tri.z];
    const float handedness = g.tangents[tri.x].w;
    h.tangent = handedness != 0.0f ? glm::vec4(glm::mat3(m) * glm::vec3(t), handedness < 0.0f ? -1.0f : 1.0f)
                                   : glm::vec4(0.0f);
    h.uv0 = w * g.uv0[tri.x] + u * g.uv0[tri.y] + v * g.uv0[tri.z];
    h.uv1 = w * g.uv1[tri.x] + u * g.uv1[tri.y] + v * g.uv1[tri.z];
    h.color = w * g.colors[tri.x] + u * g.colors[tri.y] + v * g.colors[tri.z];
    return h;
}

glm::vec3 emissionAt(const PathTraceScene& pts, const PtHitPoint& hit, const glm::vec3& wo) {
    const scene::Material& m = pts.materials.at(hit.material);
    if (m.emissive == glm::vec3(0.0f)) return glm::vec3(0.0f);
    if (!m.doubleSided && glm::dot(wo, hit.geometricNormal) <= 0.0f) return glm::vec3(0.0f);
    return m.emissive * glm::vec3(sampleRef(pts, m.emissiveTexture, hit, true));
}

PtMaterialHit evaluateMaterial(const PathTraceScene& pts, const PtHitPoint& hit, const glm::vec3& wo) {
    const scene::Material& m = pts.materials.at(hit.material);
    const gpu::GpuPtMaterial& pm = pts.ptMaterials.at(hit.material);
    PtMaterialHit out;
    gpu::PtSurface& s = out.surface;

    const glm::vec4 base = m.baseColorFactor * sampleRef(pts, m.baseColorTexture, hit, true) * hit.color;
    out.alpha = base.a;
    if (m.alphaMode == scene::AlphaMode::Mask) out.passThrough = !(base.a >= m.alphaCutoff);
    if (m.alphaMode == scene::AlphaMode::Blend) out.blendAlpha = std::clamp(base.a, 0.0f, 1.0f);

    const glm::vec4 mr = sampleRef(pts, m.metallicRoughnessTexture, hit, false);
    s.baseColor = glm::vec3(base);
    s.alpha = base.a;
    s.metallic = std::clamp(m.metallic * mr.b, 0.0f, 1.0f);
    s.roughness = std::clamp(m.roughness * mr.g, 0.0f, 1.0f);
    s.transmission = std::clamp(m.transmission * sampleRef(pts, m.transmissionTexture, hit, false).r, 0.0f, 1.0f);
    s.ior = m.ior;
    s.thickness = m.thickness;
    s.attenuationColor = pm.attenuationColor;
    s.attenuationDistance = pm.attenuationDistance;
    s.emission = emissionAt(pts, hit, wo);
    s.geometricNormal = hit.geometricNormal;
    // KHR_materials_specular / _clearcoat / _sheen: factor x texture channel (wfEvaluateMaterial's twin).
    s.specular = pm.specular * sampleRef(pts, m.specularTexture, hit, false).a;
    s.specularColor = pm.specularColor * glm::vec3(sampleRef(pts, m.specularColorTexture, hit, true));
    s.clearcoat = pm.clearcoat * sampleRef(pts, m.clearcoatTexture, hit, false).r;
    s.clearcoatRoughness = pm.clearcoatRoughness * sampleRef(pts, m.clearcoatRoughnessTexture, hit, false).g;
    s.sheenColor = pm.sheenColor * glm::vec3(sampleRef(pts, m.sheenColorTexture, hit, true));
    s.sheenRoughness = pm.sheenRoughness * sampleRef(pts, m.sheenRoughnessTexture, hit, false).a;
    // KHR_materials_diffuse_transmission, KHR_materials_dispersion (wfEvaluateMaterial's twin).
    s.diffuseTransmission = 0.0f;
    s.diffuseTransmissionColor = glm::vec3(1.0f);
    if (!m.unlit && m.diffuseTransmission > 0.0f) {
        s.diffuseTransmission =
            std::clamp(m.diffuseTransmission * sampleRef(pts, m.diffuseTransmissionTexture, hit, false).a, 0.0f, 1.0f);
        s.diffuseTransmissionColor =
            m.diffuseTransmissionColor * glm::vec3(sampleRef(pts, m.diffuseTransmissionColorTexture, hit, true));
    }
    s.dispersion = m.unlit ? 0.0f : m.dispersion;
    // KHR_materials_iridescence: factor x R, thickness = mix(min, max, G) (no texture: G = 1, the maximum).
    if (m.iridescence > 0.0f) {
        s.iridescence = std::clamp(m.iridescence * sampleRef(pts, m.iridescenceTexture, hit, false).r, 0.0f, 1.0f);
        s.iridescenceIor = m.iridescenceIor;
        const float g = sampleRef(pts, m.iridescenceThicknessTexture, hit, false).g;
        s.iridescenceThickness = glm::mix(m.iridescenceThicknessMin, m.iridescenceThicknessMax, g);
    }

    // Normal mapping in the vertex tangent frame (B = cross(N, T) * w), z rebuilt from the remapped xy.
    glm::vec3 n = hit.normal;
    if (m.normalTexture && hit.tangent.w != 0.0f)
        n = mapNormal(hit, sampleRef(pts, m.normalTexture, hit, false), m.normalScale);
    // Interpolated normals may point to the other side of the triangle than its winding says: keep the shading
    // normal on the geometric normal's side (the BSDF turns both toward wo).
    if (glm::dot(n, hit.geometricNormal) < 0.0f) n = -n;
    s.shadingNormal = n;
    // clearcoatNormalTexture: the coat's own normal, mapped from the interpolated normal like the base's (0: none).
    if (m.clearcoatNormalTexture && s.clearcoat > 0.0f && hit.tangent.w != 0.0f) {
        glm::vec3 c = mapNormal(hit, sampleRef(pts, m.clearcoatNormalTexture, hit, false), m.clearcoatNormalScale);
        if (glm::dot(c, hit.geometricNormal) < 0.0f) c = -c;
        s.clearcoatNormal = c;
    }
    // KHR_materials_anisotropy: the direction in the vertex frame; anisotropyTexture RG turns it (no texture:
    // RG = (1, 0.5), the tangent), B scales the strength.
    glm::vec4 anisotropyTexel(1.0f, 0.5f, 1.0f, 1.0f);
    if (m.anisotropyTexture && pm.anisotropyStrength > 0.0f)
        anisotropyTexel = sampleRef(pts, m.anisotropyTexture, hit, false);
    s.anisotropyStrength = std::clamp(pm.anisotropyStrength * anisotropyTexel.b, 0.0f, 1.0f);
    s.anisotropyDirection = s.anisotropyStrength > 0.0f
                                ? gpu::ptAnisotropyDirection(hit.tangent, hit.normal, pm.anisotropyRotation,
                                                             glm::vec2(anisotropyTexel))
                                : glm::vec3(0.0f);

    if (m.unlit) {
        out.unlit = true;
        s.emission = glm::vec3(base);
        s.baseColor = glm::vec3(0.0f);
        s.metallic = 0.0f;
        s.transmission = 0.0f;
        s.ior = 1.0f;  // no Fresnel reflection either: nothing scatters
        s.clearcoat = 0.0f;
        s.sheenColor = glm::vec3(0.0f);
        s.anisotropyStrength = 0.0f;
        s.diffuseTransmission = 0.0f;
        s.dispersion = 0.0f;
        s.iridescence = 0.0f;
    }
    return out;
}

}  // namespace idk::pathtrace
