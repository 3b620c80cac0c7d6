// pt_math_checks.cpp: the path tracer's shared maths (shared/pt_sampling.h) compiled as GLSL
// (conformance/pt_bsdf_probe.comp.glsl) against its C++ compilation, on 4096 random cases: the RNG bit for bit;
// BSDF evaluation (f cos and pdf), BSDF sampling (lobe, direction, weight, pdf), light sampling and pdf, the
// equirectangular mapping, texel lookup, environment pdf and sampling within the stated tolerances. Tolerances:
// values relative 2e-3 of max(|C++|, 1e-2) (GPU transcendentals: Vulkan allows sin/cos 2^-11 absolute error, the
// GGX peak amplifies float rounding); directions 2e-3 absolute. Discontinuities (lobe choice, texel borders,
// cone and horizon tests) may flip for cases within rounding of the edge: at most 0.5% of the cases.
// Moved here from tests/conformance/pt_math/ so `idk conformance` runs it (check "pathtrace/bsdf probe").
#include <algorithm>
#include <cmath>
#include <random>

#include "conformance/conformance.hpp"
#include "pathtrace/albedo_integrator.hpp"
#include "shared/pt_probe_types.h"
#include "shared/pt_sampling.h"
#include "vk/context.hpp"
#include "vk/shader_library.hpp"
#include "vk/transfer.hpp"

namespace idk::conformance {
namespace {

using namespace idk::gpu;

struct ProbePush {
    uint64_t cases;
    uint64_t results;
    uint32_t count, envWidth, envHeight, pad;
    uint64_t albedoTables;  // pathtrace::albedoTableData() (shared/pt_energy.h)
};
static_assert(sizeof(ProbePush) == 40);

constexpr uint32_t kEnvWidth = 64, kEnvHeight = 32;

glm::vec3 randomUnit(std::mt19937& gen) {
    std::normal_distribution<float> n(0.0f, 1.0f);
    return glm::normalize(glm::vec3(n(gen), n(gen), n(gen)) + glm::vec3(1e-6f));
}

GpuPtProbeCase randomCase(std::mt19937& gen, uint32_t i) {
    std::uniform_real_distribution<float> uni(0.0f, 1.0f);
    GpuPtProbeCase c{};
    PtSurface& s = c.surface;
    s.baseColor = glm::vec3(uni(gen), uni(gen), uni(gen));
    s.alpha = 1.0f;
    s.metallic = i % 5 == 0 ? 1.0f : (i % 5 == 1 ? 0.0f : uni(gen));
    s.roughness = i % 11 == 0 ? 0.0f : 0.1f + 0.9f * uni(gen);  // exact 0: delta lobes
    s.transmission = i % 3 == 0 ? uni(gen) : 0.0f;
    s.ior = i % 7 == 0 ? 1.0f : 1.0f + 1.5f * uni(gen);
    s.thickness = i % 2 == 0 ? 1.0f : 0.0f;
    s.attenuationColor = glm::vec3(1.0f);
    s.geometricNormal = randomUnit(gen);
    s.shadingNormal = glm::normalize(s.geometricNormal + 0.3f * randomUnit(gen));
    // Material extensions (shared/pt_bsdf_frame.h), each on a share of the cases: KHR_materials_specular,
    // _clearcoat (exact 0 roughness: a delta coat), _sheen. The rest keep the core defaults.
    s.specular = i % 4 == 0 ? uni(gen) : 1.0f;
    s.specularColor = i % 4 == 0 ? glm::vec3(uni(gen), uni(gen), uni(gen)) * 2.0f : glm::vec3(1.0f);
    s.clearcoat = i % 6 == 1 ? uni(gen) : 0.0f;
    s.clearcoatRoughness = i % 12 == 1 ? 0.0f : uni(gen);
    s.sheenColor = i % 5 == 2 ? glm::vec3(uni(gen), uni(gen), uni(gen)) : glm::vec3(0.0f);
    s.sheenRoughness = uni(gen);
    // KHR_materials_anisotropy on a share of the cases, some without a direction (the BSDF's basis then). Drawn
    // from a generator of their own so that the other cases stay the ones this probe always ran.
    std::mt19937 anisoGen(i * 2654435761u + 1u);
    s.anisotropyStrength = i % 9 == 3 ? uni(anisoGen) : 0.0f;
    s.anisotropyDirection = i % 18 == 3 ? randomUnit(anisoGen) : glm::vec3(0.0f);
    // KHR_materials_diffuse_transmission the same way (its own generator; the colour stays 1 on the other cases).
    std::mt19937 diffTransGen(i * 2246822519u + 7u);
    s.diffuseTransmission = i % 7 == 2 ? uni(diffTransGen) : 0.0f;
    s.diffuseTransmissionColor = i % 7 == 2 ? glm::vec3(uni(diffTransGen), uni(diffTransGen), uni(diffTransGen))
                                            : glm::vec3(1.0f);
    // KHR_materials_iridescence on a share of the cases (own generator, as above); a few with thickness 0.
    std::mt19937 iridGen(i * 2246822519u + 7u);
    s.iridescence = i % 7 == 4 ? uni(iridGen) : 0.0f;
    s.iridescenceIor = 1.0f + 1.5f * uni(iridGen);
    s.iridescenceThickness = i % 21 == 4 ? 0.0f : 1000.0f * uni(iridGen);
    // clearcoatNormalTexture: a coat normal of its own on half of the coated cases (own generator).
    std::mt19937 coatGen(i * 3266489917u + 3u);
    s.clearcoatNormal = i % 12 == 7 ? glm::normalize(s.shadingNormal + 0.4f * randomUnit(coatGen)) : glm::vec3(0.0f);
    c.wo = randomUnit(gen);
    c.wi = randomUnit(gen);
    c.u = glm::vec3(uni(gen), uni(gen), uni(gen));
    c.pixel = uint32_t(gen());
    c.sampleIndex = uint32_t(gen());
    c.seed = uint32_t(gen());
    GpuPtLight& l = c.light;
    l.type = i % 4;  // point, spot, directional, triangle
    l.position = 2.0f * randomUnit(gen);
    l.direction = l.type == kPtLightTriangle ? randomUnit(gen) * (0.2f + uni(gen)) : randomUnit(gen);
    l.edge2 = randomUnit(gen) * (0.2f + uni(gen));
    l.range = i % 8 < 4 ? 0.0f : 5.0f;
    l.intensity = glm::vec3(uni(gen), uni(gen), uni(gen)) * 10.0f;
    l.spotScale = 1.0f / 0.3f;
    l.spotOffset = -0.5f * l.spotScale;
    l.flags = i % 3 == 0 ? kPtLightDoubleSided : (i % 3 == 1 ? kPtLightFlipped : 0u);
    c.point = 0.5f * randomUnit(gen);
    c.lightU = glm::vec2(uni(gen), uni(gen));
    c.envDir = randomUnit(gen);
    c.envU = glm::vec2(uni(gen), uni(gen));
    c.envTexel = uint32_t(gen() % (kEnvWidth * kEnvHeight));
    c.envProbability = uni(gen) * 1e-3f;
    return c;
}

GpuPtProbeResult cpuResult(const GpuPtProbeCase& c) {
    GpuPtProbeResult r{};
    r.evalValue = ptEvalBsdf(c.surface, c.wo, c.wi, r.evalPdf);
    ptSampleBsdf(c.surface, c.wo, c.u, r.sampleWi, r.sampleWeight, r.samplePdf, r.sampleLobe);
    PtRng rng = ptRngInit(c.pixel, c.sampleIndex, c.seed);
    r.rngUints.x = ptNextUint(rng);
    r.rngUints.y = ptNextUint(rng);
    r.rngUints.z = ptNextUint(rng);
    r.rngUints.w = ptNextUint(rng);
    r.rngFloat = ptRandom(rng);
    r.hash = ptHash(c.pixel);
    PtLightSample ls;
    r.lightOk = ptSampleLight(c.light, c.point, c.lightU, ls) ? 1u : 0u;
    r.lightDistance = ls.distance;
    r.lightPdf = ls.pdf;
    r.lightDirection = ls.direction;
    r.lightRadiance = ls.radiance;
    r.lightPdfAtSample = ptLightPdf(c.light, c.point, ls.position);
    r.envUv = ptEquirectUv(c.envDir);
    r.envTexel = ptEnvironmentTexel(c.envDir, kEnvWidth, kEnvHeight);
    r.envPdf = ptEnvironmentPdf(c.envProbability, c.envDir, kEnvWidth, kEnvHeight);
    r.envSamplePdf = ptSampleEnvironment(c.envTexel, c.envProbability, kEnvWidth, kEnvHeight, c.envU, r.envSampleDir);
    return r;
}

bool close(float gpu, float cpu, float rel = 2e-3f, float floor = 1e-2f) {
    return std::abs(gpu - cpu) <= rel * std::max(std::abs(cpu), floor);
}
bool close3(glm::vec3 gpu, glm::vec3 cpu, float rel = 2e-3f, float floor = 1e-2f) {
    const float scale = std::max({std::abs(cpu.x), std::abs(cpu.y), std::abs(cpu.z), floor});
    return glm::all(glm::lessThanEqual(glm::abs(gpu - cpu), glm::vec3(rel * scale)));
}

void bsdfProbe(CheckEnv& env, Verdict& v) {
    const uint32_t count = 4096;
    std::mt19937 gen(2024);
    std::vector<GpuPtProbeCase> cases(count);
    for (uint32_t i = 0; i < count; ++i) cases[i] = randomCase(gen, i);

    vk::Buffer in = env.ctx.createBuffer({count * sizeof(GpuPtProbeCase), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                        vk::MemoryUsage::GpuOnly, "pt probe cases", "conformance"});
    vk::Buffer out = env.ctx.createBuffer({count * sizeof(GpuPtProbeResult), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                         vk::MemoryUsage::GpuOnly, "pt probe results", "conformance"});
    vk::uploadBuffer(env.ctx, in, std::span<const GpuPtProbeCase>(cases));
    const std::vector<float> albedo = pathtrace::albedoTableData();
    vk::Buffer tables = env.ctx.createBuffer({albedo.size() * sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                            vk::MemoryUsage::GpuOnly, "albedo tables", "conformance"});
    vk::uploadBuffer(env.ctx, tables, std::span<const float>(albedo));
    const vk::Pipeline& probe =
        env.shaders.compute({vk::ShaderId::conformance_pt_bsdf_probe_comp, {}, sizeof(ProbePush), {{64, 1, 1}}});
    ProbePush push{in.address, out.address, count, kEnvWidth, kEnvHeight, 0, tables.address};
    env.ctx.runImmediate([&](VkCommandBuffer cmd) {
        vk::bindPipeline(cmd, probe);
        vk::pushConstants(cmd, env.ctx, push);
        vkCmdDispatch(cmd, vk::groupCount(count, 64), 1, 1);
    });
    const std::vector<GpuPtProbeResult> gpu = vk::downloadBuffer<GpuPtProbeResult>(env.ctx, out, count);
    env.ctx.destroy(in);
    env.ctx.destroy(out);
    env.ctx.destroy(tables);

    uint32_t lobeFlips = 0, lightFlips = 0, texelFlips = 0, evaluated = 0, sampled = 0, lit = 0;
    uint32_t lobeCounts[8] = {};  // agreeing samples per lobe (kPtLobe*)
    for (uint32_t i = 0; i < count; ++i) {
        const GpuPtProbeResult cpu = cpuResult(cases[i]);
        const GpuPtProbeResult& g = gpu[i];
        // RNG: bit for bit.
        if (!v.expect(g.hash == cpu.hash, "case " + std::to_string(i) + ": hash")) return;
        if (!v.expect(g.rngUints == cpu.rngUints, "case " + std::to_string(i) + ": rng uints")) return;
        if (!v.expect(g.rngFloat == cpu.rngFloat, "case " + std::to_string(i) + ": rng float")) return;
        // BSDF evaluation.
        v.expect(close3(g.evalValue, cpu.evalValue), "case " + std::to_string(i) + ": evalValue");
        v.expect(close(g.evalPdf, cpu.evalPdf), "case " + std::to_string(i) + ": evalPdf");
        evaluated += cpu.evalPdf > 0.0f ? 1 : 0;
        // BSDF sampling.
        if (g.sampleLobe != cpu.sampleLobe) {
            ++lobeFlips;
        } else if (cpu.sampleLobe != kPtLobeNone) {
            v.expect(close3(g.sampleWi, cpu.sampleWi, 2e-3f, 1.0f), "case " + std::to_string(i) + ": sampleWi");
            v.expect(close3(g.sampleWeight, cpu.sampleWeight, 5e-3f), "case " + std::to_string(i) + ": sampleWeight");
            v.expect(close(g.samplePdf, cpu.samplePdf, 5e-3f), "case " + std::to_string(i) + ": samplePdf");
            ++sampled;
            ++lobeCounts[std::min<uint32_t>(cpu.sampleLobe & ~kPtLobeDeltaFlag, 7u)];
        }
        // Lights.
        if (g.lightOk != cpu.lightOk) {
            ++lightFlips;
        } else if (cpu.lightOk) {
            v.expect(close(g.lightDistance, cpu.lightDistance), "case " + std::to_string(i) + ": lightDistance");
            v.expect(close(g.lightPdf, cpu.lightPdf), "case " + std::to_string(i) + ": lightPdf");
            v.expect(close3(g.lightDirection, cpu.lightDirection, 2e-3f, 1.0f), "case " + std::to_string(i) + ": lightDirection");
            v.expect(close3(g.lightRadiance, cpu.lightRadiance), "case " + std::to_string(i) + ": lightRadiance");
            v.expect(close(g.lightPdfAtSample, cpu.lightPdfAtSample), "case " + std::to_string(i) + ": lightPdfAtSample");
            ++lit;
        }
        // Environment.
        v.expectNear(g.envUv.x, cpu.envUv.x, 1e-4f, "case " + std::to_string(i) + ": envUv.x");
        v.expectNear(g.envUv.y, cpu.envUv.y, 1e-4f, "case " + std::to_string(i) + ": envUv.y");
        if (g.envTexel != cpu.envTexel) ++texelFlips;
        v.expect(close(g.envPdf, cpu.envPdf), "case " + std::to_string(i) + ": envPdf");
        v.expect(close3(g.envSampleDir, cpu.envSampleDir, 2e-3f, 1.0f), "case " + std::to_string(i) + ": envSampleDir");
        v.expect(close(g.envSamplePdf, cpu.envSamplePdf), "case " + std::to_string(i) + ": envSamplePdf");
    }
    v.expect(lobeFlips <= count / 200, "lobeFlips = " + std::to_string(lobeFlips) + ", limit <= " + std::to_string(count / 200));
    v.expect(lightFlips <= count / 200, "lightFlips = " + std::to_string(lightFlips) + ", limit <= " + std::to_string(count / 200));
    v.expect(texelFlips <= count / 200, "texelFlips = " + std::to_string(texelFlips) + ", limit <= " + std::to_string(count / 200));
    // The random cases exercise every path.
    v.expect(evaluated > count / 4, "evaluated = " + std::to_string(evaluated) + ", limit > " + std::to_string(count / 4));
    v.expect(sampled > count / 2, "sampled = " + std::to_string(sampled) + ", limit > " + std::to_string(count / 2));
    v.expect(lit > count / 3, "lit = " + std::to_string(lit) + ", limit > " + std::to_string(count / 3));
    for (uint32_t lobe : {kPtLobeDiffuse, kPtLobeSpecular, kPtLobeTransmission, kPtLobeMultiScatter, kPtLobeSheen,
                          kPtLobeClearcoat, kPtLobeDiffuseTransmission})
        v.expect(lobeCounts[lobe] > 20u, "lobe " + std::to_string(lobe) + " is hardly sampled (" +
                                             std::to_string(lobeCounts[lobe]) + " cases): the cases miss it");
}

}  // namespace

std::vector<Check> ptMathChecks() {
    return {
        {"pathtrace/bsdf probe", "",
         "2e-3 relative values, 2e-3 absolute directions, <= 0.5% discontinuity flips; RNG exact", bsdfProbe},
    };
}

}  // namespace idk::conformance
