// path_tracer.hpp: the GPU wavefront path tracer. Each sample is a chain of compute passes on the render graph:
// camera rays -> for every bounce: closest hit (our BVH or VK_KHR_ray_query) -> [ray sort by material/direction]
// -> shade (emission, next-event shadow ray, extension ray, Russian roulette; alive rays compacted by atomic
// append) -> args (indirect dispatch sizes on the GPU) -> shadow rays -> after the last bounce: accumulate into
// RGBA32F sums; a final resolve writes the mean radiance and the first-hit albedo/normal/depth guides.
// Ports IDKEngine's PathTracer.cs / PathTracerPipeline.cs (reference 1.6, 2.1) with the differences stated there:
// NEE + MIS, GPU-side dispatch sizes, a stable radix sort instead of the fixed 2^21-bucket counting sort.
#pragma once
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/image_file.hpp"
#include "pathtrace/pt_settings.hpp"
#include "render/atmosphere.hpp"
#include "scene/camera.hpp"
#include "scene/scene.hpp"
#include "shared/pt_wavefront.h"

namespace idk::vk {
class Context;
class ShaderLibrary;
}  // namespace idk::vk
namespace idk::pathtrace {
struct PathTraceScene;
}  // namespace idk::pathtrace

namespace idk::render {

enum class PtTraversal : uint8_t {
    Auto,      // the "ray traversal" capability ladder's rung (ray query when the device has it, not with --fallback
               // or on a CPU device such as lavapipe, whose software ray query is far slower than our BVH)
    Bvh,       // our GLSL BVH, 8-wide compressed (engine/bvh trees collapsed by bvh/wide8.hpp,
               // include/bvh_traverse_wide.glsl): the portable rung
    Bvh2,      // the portable rung's binary walk (include/bvh_traverse.glsl); same hits as Bvh
    RayQuery,  // VK_KHR_ray_query over driver acceleration structures
};
const char* traversalName(PtTraversal traversal);  // "auto", "bvh", "bvh2", "rayquery"

struct PathTracerOptions {
    PtTraversal traversal = PtTraversal::Auto;
    bool sortRays = false;   // sort each bounce's rays by (material, direction octant) before shading
    bool denoise = false;    // also run PT-C's edge-aware denoiser on the result (PathTraceResult::denoised)
    bool readGuides = false; // read back the albedo/normal/depth guide images
    bool readSum = false;    // read back the raw radiance sum (PathTraceResult::sum) for `idk merge`
    uint32_t samplesPerBatch = 4;  // samples recorded per submission (progress granularity)
    float environmentIntensity = 1.0f;
    // Equirectangular HDR environment: nullopt = defaultEnvironmentPath(); an empty path = constant radiance 0.5.
    std::optional<std::filesystem::path> environment;
    // `--sky atmosphere` (atmosphere.enabled): the sky render::bakeSky bakes for these settings replaces the file,
    // the same equirectangular map the raster's environment uses (its importance-sampling tables built from it).
    AtmosphereSettings atmosphere;
};

// What a render computes: PT-A's settings struct, shared with the CPU reference (pathtrace::renderReference), so
// both tracers read the same knobs (spp, maxDepth in ray segments, seed, nee, rouletteDepth).
using PathTraceSettings = pathtrace::PtSettings;

struct PtStageTime {
    std::string stage;  // camera, trace, sort, shade, args, shadow, accumulate, resolve, denoise
    double milliseconds = 0.0;
};

struct PathTraceResult {
    core::ImageRgba32f image;     // mean linear radiance, alpha 1
    core::ImageRgba32f albedo;    // readGuides/denoise: first-hit albedo (1 for the sky)
    core::ImageRgba32f normal;    // readGuides/denoise: first-hit world normal (0 for the sky)
    core::ImageRgba32f depth;     // readGuides/denoise: first-hit distance along the ray in r (0 for the sky)
    core::ImageRgba32f denoised;  // denoise: the denoiser's output
    core::ImageRgba32f sum;       // readSum: the accumulation as summed on the GPU (RGB), sample count in A
    std::vector<PtStageTime> stageTimes;  // GPU time per stage, summed over samples and bounces
    double gpuMilliseconds = 0.0;
    double wallMilliseconds = 0.0;
    uint32_t samples = 0;
    PtTraversal traversal = PtTraversal::Bvh;  // the rung that ran
    bool didDenoise = false;      // the denoiser ran (denoised holds its output)
};

// The wavefront state after the shade stage of one bounce of sample 0 (conformance tests of compaction,
// sorting and traversal).
struct PtCapture {
    std::vector<gpu::GpuPtPath> paths;   // after shade
    std::vector<gpu::GpuPtHit> hits;     // of this bounce's rays
    std::vector<gpu::GpuPtPath> rays;    // path state before trace (the rays that were traced)
    std::vector<uint32_t> queueIn;       // header + items (sorted when sorting is on)
    std::vector<uint32_t> queueOut;      // header + items appended by shade
    std::vector<uint32_t> argsOut;       // the next bounce's dispatch size (x, y, z), as the args stage computes it
    std::vector<uint32_t> keys;          // sort keys per queue slot (sorting on)
};

class PathTracer {
public:
    using Progress = std::function<void(uint32_t samplesDone, uint32_t samplesTotal)>;

    // Builds PT-A's PathTraceScene (BVHs, lights, environment tables from options.environment or the baked sky of
    // options.atmosphere) and uploads it with
    // the GpuScene materials and textures (+ acceleration structures for the ray-query rung). Throws
    // std::runtime_error when the requested traversal cannot run on the device.
    PathTracer(vk::Context& ctx, vk::ShaderLibrary& shaders, const scene::Scene& scene, PathTracerOptions options = {});
    // The same from an already built PathTraceScene of `scene` (tests share it with the CPU reference; the
    // environment options are then ignored). `pts` is only read during construction.
    PathTracer(vk::Context& ctx, vk::ShaderLibrary& shaders, const scene::Scene& scene,
               const pathtrace::PathTraceScene& pts, PathTracerOptions options = {});
    ~PathTracer();
    PathTracer(const PathTracer&) = delete;
    PathTracer& operator=(const PathTracer&) = delete;

    // Poses the scene as `scene` is now (after scene::evaluateAnimations; the same scene the tracer was built
    // from): instance transforms, and skins and morphs through the rasterizer's skinning compute, BLAS refit on
    // the GPU and the TLAS rebuilt (render/pt_pose.hpp). Construction already applies the scene's pose at that
    // time. Throws std::invalid_argument for another scene or a moved emissive instance (its light entries are
    // world-space triangles), or when skinned/morphed instances were posed on the CPU (a PtPosing::Cpu scene).
    void setPose(const scene::Scene& scene);

    PathTraceResult render(const scene::CameraView& camera, uint32_t width, uint32_t height,
                           const PathTraceSettings& settings, const Progress& progress = {});
    // Progressive accumulation (a viewer's path-traced mode): beginProgressive clears the sums for an image of
    // `camera` at width x height with `settings` (spp is ignored; samples are numbered from settings.firstSample),
    // accumulate(n) adds the next n samples (in samplesPerBatch submissions) and returns the count so far,
    // resolveProgressive writes the mean of the samples so far (and the denoiser's output with options.denoise) and
    // reads it back as render() does; accumulating can go on after it. The same seed and samples give render()'s
    // image. render() and capture() reuse the accumulation: they end the progressive image (accumulate and
    // resolveProgressive then throw std::logic_error until the next beginProgressive).
    void beginProgressive(const scene::CameraView& camera, uint32_t width, uint32_t height,
                          const PathTraceSettings& settings);
    uint32_t accumulate(uint32_t samples);
    uint32_t accumulatedSamples() const noexcept;  // since beginProgressive; 0 without a progressive image
    PathTraceResult resolveProgressive();

    PtCapture capture(const scene::CameraView& camera, uint32_t width, uint32_t height,
                      const PathTraceSettings& settings, uint32_t bounce);

    PtTraversal traversal() const noexcept;  // resolved (never Auto)
    struct Impl;

private:
    std::unique_ptr<Impl> impl_;
};

}  // namespace idk::render
