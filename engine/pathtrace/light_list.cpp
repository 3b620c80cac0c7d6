// light_list.cpp: the NEE light list of a PathTraceScene (buildLights in pt_scene.hpp): KHR_lights_punctual
// lights, then one triangle light per triangle of every instance whose mesh has an emissive primitive; the alias
// table over their powers (point/spot 4 pi I, directional E pi R^2 over the scene's bounding sphere, triangles
// pi A L, twice that when double-sided) and the probability of sampling the environment instead (its power
// pi^2 R^2 * mean luminance, clamped to [0.1, 0.9] when both exist). Power only shapes the variance: every
// light that can contribute keeps a non-zero probability.
#include <algorithm>
#include <cmath>

#include "pathtrace/alias_table.hpp"
#include "pathtrace/pt_scene.hpp"

namespace idk::pathtrace {

namespace {

constexpr double kPi = 3.14159265358979323846;

double luminance(const glm::vec3& c) { return std::max(0.0, 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z); }

gpu::GpuPtLight punctual(const scene::Light& l) {
    gpu::GpuPtLight g{};
    g.type = l.type == scene::LightType::Directional ? gpu::kPtLightDirectional
             : l.type == scene::LightType::Spot      ? gpu::kPtLightSpot
                                                     : gpu::kPtLightPoint;
    g.position = l.position;
    g.direction = glm::normalize(l.direction);
    g.range = l.range;
    g.intensity = l.color * l.intensity;
    const float cosOuter = std::cos(l.outerConeAngle), cosInner = std::cos(l.innerConeAngle);
    g.spotScale = 1.0f / std::max(0.001f, cosInner - cosOuter);
    g.spotOffset = -cosOuter * g.spotScale;
    g.instance = g.triangle = g.material = gpu::kPtNoLight;
    return g;
}

}  // namespace

void buildLights(PathTraceScene& pts, const scene::Scene& scene) {
    std::vector<double> power;
    pts.lights.clear();
    const double radius = std::max(1e-3, double(pts.boundsRadius));
    pts.instanceLights.assign(pts.instances.size(), gpu::GpuPtInstance{gpu::kPtNoLight});

    for (uint32_t i = 0; i < pts.instances.size(); ++i) {
        const bvh::BlasInstance& inst = pts.instances[i];
        const PtGeometry& g = pts.geometries[inst.blasIndex];
        bool emits = false;
        for (uint32_t m : g.triangleMaterial) emits |= pts.materials[m].emissive != glm::vec3(0.0f);
        if (!emits) continue;
        pts.instanceLights[i].firstLight = uint32_t(pts.lights.size());
        for (uint32_t t = 0; t < g.triangles.size(); ++t) {
            const scene::Material& m = pts.materials[g.triangleMaterial[t]];
            const glm::uvec3 tri = g.triangles[t];
            const glm::vec3 p0 = glm::vec3(inst.objectToWorld * glm::vec4(g.positions[tri.x], 1.0f));
            const glm::vec3 p1 = glm::vec3(inst.objectToWorld * glm::vec4(g.positions[tri.y], 1.0f));
            const glm::vec3 p2 = glm::vec3(inst.objectToWorld * glm::vec4(g.positions[tri.z], 1.0f));
            gpu::GpuPtLight l{};
            l.type = gpu::kPtLightTriangle;
            l.position = p0;
            l.direction = p1 - p0;
            l.edge2 = p2 - p0;
            l.intensity = m.emissive;
            l.instance = i;
            l.triangle = t;
            l.material = g.triangleMaterial[t];
            l.flags = (m.doubleSided ? gpu::kPtLightDoubleSided : 0u) |
                      (m.emissiveTexture ? gpu::kPtLightTextured : 0u) |
                      (pts.mirrored[i] ? gpu::kPtLightFlipped : 0u);
            double area = 0.5 * double(glm::length(glm::cross(l.direction, l.edge2)));
            if (!std::isfinite(area)) area = 0.0;
            double lum = luminance(m.emissive);
            if (m.emissiveTexture && m.emissiveTexture->texture < pts.textures.size()) {
                // The texture's mean (its 1x1 mip); at least one 8-bit step, so a dark average never hides texels.
                const glm::vec4 mean = pts.textures[m.emissiveTexture->texture].mean;
                lum = luminance(m.emissive * glm::max(glm::vec3(mean), glm::vec3(1.0f / 255.0f)));
            }
            power.push_back(kPi * area * lum * (m.doubleSided ? 2.0 : 1.0));
            pts.lights.push_back(l);
        }
    }
    // Punctual lights after the triangles.
    for (const scene::Light& sl : scene.lights) {
        const gpu::GpuPtLight l = punctual(sl);
        const double lum = luminance(l.intensity);
        const double p = l.type == gpu::kPtLightDirectional ? lum * kPi * radius * radius : 4.0 * kPi * lum;
        if (!(p > 0.0) || !std::isfinite(p)) continue;  // a black light can be dropped: it never contributes
        power.push_back(p);
        pts.lights.push_back(l);
    }
    pts.lightAlias = buildAliasTable(power);

    double lightPower = 0.0;
    for (double p : power) lightPower += std::isfinite(p) ? p : 0.0;
    const double envPower = pts.environment.black() ? 0.0 : kPi * kPi * radius * radius * pts.environment.meanLuminance;
    float envProbability = 0.0f;
    if (envPower > 0.0 && pts.lightAlias.empty()) envProbability = 1.0f;
    if (envPower > 0.0 && !pts.lightAlias.empty())
        envProbability = float(std::clamp(envPower / (envPower + lightPower), 0.1, 0.9));
    pts.environmentDesc.width = pts.environment.width;
    pts.environmentDesc.height = pts.environment.height;
    pts.environmentDesc.selectProbability = envProbability;
    pts.environmentDesc.lightCount = pts.lightAlias.empty() ? 0u : uint32_t(pts.lights.size());
}

}  // namespace idk::pathtrace
