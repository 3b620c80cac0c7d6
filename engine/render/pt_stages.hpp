// pt_stages.hpp: adds the wavefront path tracer's compute passes to a render graph (one sample = camera, then per
// bounce trace [-> sort] -> shade -> args -> shadow, then accumulate; resolve once at the end). Each pass
// declares what it reads and writes; the graph places the barriers. Internal to path_tracer.cpp.
#pragma once
#include <functional>
#include <optional>

#include "render/pt_frame.hpp"
#include "shared/pt_wavefront.h"

namespace idk::vk {
class Context;
class ShaderLibrary;
}  // namespace idk::vk

namespace idk::render {

struct PtStageConfig {
    bool rayQuery = false;
    bool wideBvh = false;  // BVH rung: the 8-wide compressed walk (trace/shadow_bvh_wide) instead of the binary one
    bool sort = false;
    bool hasAlpha = false;
    bool nee = true;
    bool sobol = true;     // the paths' sampler (GpuPtStagePush::flags kPtPushSobol), else independent
    uint32_t blasStack = 1, tlasStack = 1;
    VkDeviceAddress scene = 0;     // GpuPtSceneDesc
    VkDeviceAddress camera = 0;    // GpuPtCamera
    VkDeviceAddress accum = 0;     // GpuPtAccum
    uint32_t maxDepth = 1, rouletteDepth = 3, seed = 0;
};

struct PtStageContext {
    vk::Context& ctx;
    vk::ShaderLibrary& shaders;
    graph::RenderGraph& graph;
    PtGraphResources& res;
    PtFrameResources& frame;
    const PtStageConfig& config;
};

// Zeroes the accumulation sums (first batch of a render).
void addPtClear(const PtStageContext& s);
// Where a sample ends early (capture mode of the conformance tests); None runs the whole sample.
struct PtStop {
    enum Kind : uint8_t { None, AfterCamera, AfterShade, AfterArgs } kind = None;
    uint32_t bounce = 0;
};
// One whole sample (or its beginning up to `stop`).
void addPtSample(const PtStageContext& s, uint32_t sampleIndex, PtStop stop = {});
// The means into the output images.
void addPtResolve(const PtStageContext& s);
// PT-C's edge-aware denoiser over the resolved images, copied into PtFrameResources::denoisedImage.
void addPtDenoise(const PtStageContext& s);
bool denoiserAvailable();

}  // namespace idk::render
