// cpu_path_tracer.hpp: the CPU reference path tracer, the oracle of the GPU wavefront tracer: unidirectional path
// tracing over a PathTraceScene with the shared maths of shared/pt_sampling.h (same BSDF, light and environment
// sampling), next-event estimation + MIS (power heuristic) or BSDF sampling only, transmission with IOR and
// Beer-Lambert absorption, alpha MASK/BLEND pass-through, Russian roulette, multithreaded over image rows
// (std::thread). Ports what IDKEngine's FirstHit/NHit shaders compute (reference 2.1), with the light transport
// of pt_sampling.h instead of its heuristic lobes.
#pragma once
#include <cstdint>
#include <functional>

#include "core/image_file.hpp"
#include "pathtrace/pt_scene.hpp"
#include "pathtrace/pt_settings.hpp"
#include "scene/camera.hpp"
#include "shared/pt_common.h"

namespace idk::pathtrace {

// Called with (rows finished, total rows) after each finished row, from worker threads one at a time.
using PtProgress = std::function<void(uint32_t done, uint32_t total)>;

// Linear radiance per pixel (alpha 1), the mean of settings.spp samples; pixel (x, y) uses RNG stream
// ptRngInit(y * width + x, sample, settings.seed). Deterministic for a given input, whatever the thread count.
// Samples that come out NaN or infinite are dropped (counted as zero). threads = 0: hardware concurrency.
core::ImageRgba32f renderReference(const PathTraceScene& scene, const scene::CameraView& camera, uint32_t width,
                                   uint32_t height, const PtSettings& settings, const PtProgress& progress = {},
                                   uint32_t threads = 0);

// One path's radiance estimate for a given primary ray (exposed for tests).
glm::vec3 traceRadiance(const PathTraceScene& scene, glm::vec3 origin, glm::vec3 direction, gpu::PtRng& rng,
                        const PtSettings& settings);

// inverse(projection * view) for a width x height image, the matrix ptCameraRay takes.
glm::mat4 inverseViewProjection(const scene::CameraView& camera, uint32_t width, uint32_t height);

}  // namespace idk::pathtrace
