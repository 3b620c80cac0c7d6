// cpu_path_tracer.cpp: the reference integrator (unidirectional path tracing with NEE + MIS) and its threaded
// image loop.
#include "pathtrace/cpu_path_tracer.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <mutex>
#include <thread>

#include "pathtrace/scene_rays.hpp"
#include "shared/pt_sampling.h"

namespace idk::pathtrace {

namespace {

struct Medium {
    bool inside = false;
    glm::vec3 color{1.0f};
    float distance = 0.0f;
};

glm::vec3 transmittance(const Medium& m, float distance) {
    if (!m.inside) return glm::vec3(1.0f);
    return gpu::ptVolumeTransmittance(m.color, m.distance, std::min(distance, 1e30f));
}

float envSelectProbability(const PathTraceScene& pts) { return pts.environmentDesc.selectProbability; }
bool lightsSampled(const PathTraceScene& pts) { return !pts.lightAlias.empty(); }

// Next-event estimation at a surface: one sample of the environment or of a light chosen by power, weighted by
// the power heuristic against BSDF sampling (punctual lights: weight 1).
glm::vec3 sampleDirect(const PathTraceScene& pts, const gpu::PtSurface& surface, const glm::vec3& position,
                       const glm::vec3& wo, const Medium& medium, uint32_t dim, gpu::PtRng& rng) {
    const float envSelect = envSelectProbability(pts);
    const bool lights = lightsSampled(pts);
    if (!lights && !(envSelect > 0.0f)) return glm::vec3(0.0f);
    const float choose = gpu::ptSample(rng, dim + gpu::kPtDimLightChoice);
    // Draws are named one per statement: the order of evaluation of constructor arguments is unspecified in
    // C++, and the GPU tracer (shaders_glsl/pathtrace/wf_shading.h) draws in this exact order (the independent
    // sampler ignores the dimension and goes by call order).
    const float uSlot = gpu::ptSample(rng, dim + gpu::kPtDimLightSlot);
    const float uAlias = gpu::ptSample(rng, dim + gpu::kPtDimLightAlias);
    const float ux = gpu::ptSample(rng, dim + gpu::kPtDimLightX);
    const float uy = gpu::ptSample(rng, dim + gpu::kPtDimLightY);
    const glm::vec2 u(ux, uy);

    glm::vec3 direction, radiance;
    float distance, pdf;
    bool isDelta = false;
    if (choose < envSelect || !lights) {
        const auto& table = pts.environment.aliasTable;
        const uint32_t slot = gpu::ptAliasSlot(uSlot, uint32_t(table.size()));
        const uint32_t texel = gpu::ptAliasResolve(table[slot], slot, uAlias);
        const float p = gpu::ptSampleEnvironment(texel, table[texel].probability, pts.environment.width,
                                                 pts.environment.height, u, direction);
        if (!(p > 0.0f)) return glm::vec3(0.0f);
        radiance = pts.environment.radiance[texel];
        distance = gpu::kPtFar;
        pdf = envSelect * p;
    } else {
        const uint32_t slot = gpu::ptAliasSlot(uSlot, uint32_t(pts.lightAlias.size()));
        const uint32_t index = gpu::ptAliasResolve(pts.lightAlias[slot], slot, uAlias);
        const gpu::GpuPtLight& light = pts.lights[index];
        gpu::PtLightSample s;
        if (!gpu::ptSampleLight(light, position, u, s)) return glm::vec3(0.0f);
        radiance = s.radiance;
        if (light.type == gpu::kPtLightTriangle) {
            const PtHitPoint p = hitPoint(pts, light.instance, light.triangle, s.u, s.v);
            radiance = emissionAt(pts, p, -s.direction);
        }
        direction = s.direction;
        distance = s.distance;
        isDelta = s.isDelta;
        pdf = (1.0f - envSelect) * pts.lightAlias[index].probability * s.pdf;
    }
    if (!(pdf > 0.0f) || radiance == glm::vec3(0.0f)) return glm::vec3(0.0f);
    float bsdfPdf;
    const glm::vec3 f = gpu::ptEvalBsdf(surface, wo, direction, bsdfPdf);
    if (f == glm::vec3(0.0f)) return glm::vec3(0.0f);
    const glm::vec3 origin = offsetOrigin(position, surface.geometricNormal, direction);
    if (!visible(pts, origin, direction, distance, rng)) return glm::vec3(0.0f);
    const float w = isDelta ? 1.0f : gpu::ptPowerHeuristic(pdf, bsdfPdf);
    return f * radiance * transmittance(medium, distance) * (w / pdf);
}

}  // namespace

glm::vec3 traceRadiance(const PathTraceScene& pts, glm::vec3 origin, glm::vec3 direction, gpu::PtRng& rng,
                        const PtSettings& settings) {
    glm::vec3 radiance(0.0f), throughput(1.0f);
    bool previousDelta = true;  // the camera: what it sees directly is counted in full
    float previousPdf = 0.0f;
    glm::vec3 previousPosition = origin;
    Medium medium;
    uint32_t channel = gpu::kPtNoChannel;  // KHR_materials_dispersion (shared/pt_dispersion.h)
    const float envSelect = envSelectProbability(pts);
    for (uint32_t depth = 1; depth <= settings.maxDepth; ++depth) {
        const SceneHit hit = closestSurface(pts, origin, direction, bvh::kInfinity, rng);
        throughput *= transmittance(medium, hit.hit ? hit.t : gpu::kPtFar);
        const bool mis = settings.nee && !previousDelta;
        if (!hit.hit) {
            const glm::vec3 le = pts.environment.lookup(direction);
            float w = 1.0f;
            if (mis && envSelect > 0.0f) {
                const uint32_t texel =
                    gpu::ptEnvironmentTexel(direction, pts.environment.width, pts.environment.height);
                const float lightPdf = envSelect * gpu::ptEnvironmentPdf(pts.environment.aliasTable[texel].probability,
                                                                         direction, pts.environment.width,
                                                                         pts.environment.height);
                w = gpu::ptPowerHeuristic(previousPdf, lightPdf);
            }
            radiance += throughput * le * w;
            break;
        }
        gpu::PtSurface surface = hit.material.surface;
        const glm::vec3 wo = -direction;
        const glm::vec3 position = hit.point.position;
        if (surface.emission != glm::vec3(0.0f)) {
            float w = 1.0f;
            const uint32_t first = pts.instanceLights[hit.point.instance].firstLight;
            if (mis && first != gpu::kPtNoLight && lightsSampled(pts)) {
                const uint32_t index = first + hit.point.triangle;
                const float lightPdf = (1.0f - envSelect) * pts.lightAlias[index].probability *
                                       gpu::ptLightPdf(pts.lights[index], previousPosition, position);
                w = gpu::ptPowerHeuristic(previousPdf, lightPdf);
            }
            radiance += throughput * surface.emission * w;
        }
        if (depth == settings.maxDepth || hit.material.unlit) break;

        const uint32_t dim = gpu::ptDimVertexBase(depth);
        if (gpu::ptIsDispersive(surface)) {  // KHR_materials_dispersion: the path keeps one channel from here on
            if (channel == gpu::kPtNoChannel) {
                channel = gpu::ptPickChannel(gpu::ptSample(rng, dim + gpu::kPtDimDispersion));
                throughput *= gpu::ptChannelWeight(channel);
            }
            surface = gpu::ptDispersedSurface(surface, channel);
        }
        if (settings.nee) radiance += throughput * sampleDirect(pts, surface, position, wo, medium, dim, rng);

        const float u0 = gpu::ptSample(rng, dim + gpu::kPtDimBsdfLobe);  // one draw per statement (see sampleDirect)
        const float u1 = gpu::ptSample(rng, dim + gpu::kPtDimBsdfX);
        const float u2 = gpu::ptSample(rng, dim + gpu::kPtDimBsdfY);
        const glm::vec3 u(u0, u1, u2);
        glm::vec3 wi, weight;
        float pdf;
        uint32_t lobe;
        gpu::ptSampleBsdf(surface, wo, u, wi, weight, pdf, lobe);
        if (lobe == gpu::kPtLobeNone) break;
        throughput *= weight;
        if (!gpu::ptFinite3(throughput) || throughput == glm::vec3(0.0f)) break;
        previousDelta = (lobe & gpu::kPtLobeDeltaFlag) != 0u;
        previousPdf = pdf;
        previousPosition = position;
        const uint32_t through = lobe & ~gpu::kPtLobeDeltaFlag;  // into (or out of) a volume: both transmissions
        if ((through == gpu::kPtLobeTransmission || through == gpu::kPtLobeDiffuseTransmission) &&
            surface.thickness > 0.0f) {
            medium.inside = glm::dot(wi, surface.geometricNormal) < 0.0f;  // into the volume: against its outside
            medium.color = surface.attenuationColor;
            medium.distance = surface.attenuationDistance;
        }
        origin = offsetOrigin(position, surface.geometricNormal, wi);
        direction = wi;
        if (depth >= settings.rouletteDepth) {
            const float q = gpu::ptSurvivalProbability(throughput);
            if (!(gpu::ptSample(rng, dim + gpu::kPtDimRoulette) < q)) break;
            throughput /= q;
        }
    }
    return radiance;
}

glm::mat4 inverseViewProjection(const scene::CameraView& camera, uint32_t width, uint32_t height) {
    const float aspect = float(std::max(width, 1u)) / float(std::max(height, 1u));
    const glm::dmat4 vp = glm::dmat4(scene::projectionMatrix(camera, aspect)) * glm::dmat4(scene::viewMatrix(camera));
    return glm::mat4(glm::inverse(vp));
}

core::ImageRgba32f renderReference(const PathTraceScene& pts, const scene::CameraView& camera, uint32_t width,
                                   uint32_t height, const PtSettings& settings, const PtProgress& progress,
                                   uint32_t threads) {
    core::ImageRgba32f image;
    image.width = width;
    image.height = height;
    image.pixels.assign(size_t(width) * height * 4, 0.0f);
    if (width == 0 || height == 0) return image;
    const glm::mat4 inverseVp = inverseViewProjection(camera, width, height);
    const glm::vec2 size{float(width), float(height)};
    const uint32_t spp = std::max(settings.spp, 1u);

    std::atomic<uint32_t> nextRow{0};
    std::mutex progressMutex;
    uint32_t rowsDone = 0;
    auto work = [&] {
        for (uint32_t y = nextRow++; y < height; y = nextRow++) {
            for (uint32_t x = 0; x < width; ++x) {
                glm::dvec3 sum(0.0);
                for (uint32_t s = 0; s < spp; ++s) {
                    gpu::PtRng rng = gpu::ptRngInitSampler(y * width + x, settings.firstSample + s, settings.seed,
                                                           samplerId(settings.sampler));
                    // one draw per statement (see sampleDirect)
                    const float jitterX = gpu::ptSample(rng, gpu::kPtDimJitterX);
                    const float jitterY = gpu::ptSample(rng, gpu::kPtDimJitterY);
                    const glm::vec2 pixel(float(x) + jitterX, float(y) + jitterY);
                    glm::vec3 origin, direction;
                    gpu::ptCameraRay(inverseVp, pixel, size, origin, direction);
                    const glm::vec3 l = traceRadiance(pts, origin, direction, rng, settings);
                    if (gpu::ptFinite3(l)) sum += glm::dvec3(l);
                }
                float* out = &image.pixels[(size_t(y) * width + x) * 4];
                for (int c = 0; c < 3; ++c) out[c] = float(sum[c] / spp);
                out[3] = 1.0f;
            }
            if (progress) {
                std::lock_guard<std::mutex> lock(progressMutex);
                progress(++rowsDone, height);
            }
        }
    };
    const uint32_t count = std::max(1u, std::min(threads ? threads : std::thread::hardware_concurrency(), height));
    std::vector<std::thread> pool;
    for (uint32_t i = 1; i < count; ++i) pool.emplace_back(work);
    work();
    for (std::thread& t : pool) t.join();
    return image;
}

}  // namespace idk::pathtrace
