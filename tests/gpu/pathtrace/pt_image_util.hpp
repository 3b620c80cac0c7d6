// pt_image_util.hpp: what the GPU path-tracer tests share: image error metrics (RMSE over RGB, mean radiance),
// the finiteness check, the same-seed check of the GPU tracer against its CPU reference, and a GPU render of N spp
// assembled from independent 4-spp batches with distinct seeds, so one run yields the 4, 16, 64 ... spp estimates
// of a convergence curve.
#pragma once
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "core/image_file.hpp"
#include "render/path_tracer.hpp"
#include "support/same_pixels.hpp"

namespace idk::test {

inline double rmse(const core::ImageRgba32f& a, const core::ImageRgba32f& b) {
    EXPECT_EQ(a.pixels.size(), b.pixels.size());
    double sum = 0.0;
    size_t n = 0;
    for (size_t i = 0; i < a.pixels.size() && i < b.pixels.size(); ++i) {
        if (i % 4 == 3) continue;
        const double d = double(a.pixels[i]) - double(b.pixels[i]);
        sum += d * d;
        ++n;
    }
    return n ? std::sqrt(sum / double(n)) : 0.0;
}

inline double meanRadiance(const core::ImageRgba32f& a) {
    double sum = 0.0;
    for (size_t i = 0; i < a.pixels.size(); ++i)
        if (i % 4 != 3) sum += a.pixels[i];
    return a.pixels.empty() ? 0.0 : sum / double(a.pixels.size() / 4 * 3);
}

inline size_t nonFiniteCount(const core::ImageRgba32f& a) {
    size_t bad = 0;
    for (float v : a.pixels) bad += !std::isfinite(v);
    return bad;
}

// The GPU path tracer (BVH traversal) renders `sc` with the settings the CPU reference `cpu` was rendered with, and
// must draw the same samples: no non-finite pixel, at least 90% of the pixels equal to the CPU's (samePixelFraction;
// a discrete choice may flip on rounding) and the means within 1%. `what` names the scene in the printed line.
// Returns the GPU image.
inline core::ImageRgba32f expectGpuDrawsTheCpuSamples(vk::Context& ctx, vk::ShaderLibrary& shaders,
                                                       const scene::Scene& sc, const pathtrace::PathTraceScene& pts,
                                                       const scene::CameraView& camera, uint32_t size,
                                                       const render::PathTraceSettings& settings,
                                                       const core::ImageRgba32f& cpu, const char* what) {
    render::PathTracerOptions options;
    options.traversal = render::PtTraversal::Bvh;
    render::PathTracer tracer(ctx, shaders, sc, pts, options);
    core::ImageRgba32f gpu = tracer.render(camera, size, size, settings).image;
    EXPECT_EQ(nonFiniteCount(gpu), 0u) << what;
    const double same = samePixelFraction(gpu, cpu);
    const double meanCpu = meanRadiance(cpu), meanGpu = meanRadiance(gpu);
    std::printf("%s: %.2f%% of the pixels equal to the CPU's at the same seed; mean GPU %.6f CPU %.6f\n", what,
                100.0 * same, meanGpu, meanCpu);
    EXPECT_GT(same, 0.9) << what;
    EXPECT_NEAR(meanGpu, meanCpu, 0.01 * meanCpu) << what;
    return gpu;
}

// Running mean of batches: image k of `levels` is the mean of the first 4 * 4^k spp.
struct ConvergenceRun {
    std::vector<core::ImageRgba32f> levels;  // 4, 16, 64, ... spp
    double gpuMilliseconds = 0.0;
};

inline ConvergenceRun renderLevels(render::PathTracer& tracer, const scene::CameraView& camera, uint32_t size,
                                   render::PathTraceSettings settings, uint32_t levelCount, uint32_t seedBase) {
    ConvergenceRun run;
    core::ImageRgba32f sum;
    uint32_t batches = 0, nextLevel = 1;
    settings.spp = 4;
    while (run.levels.size() < levelCount) {
        settings.seed = seedBase + batches;
        const render::PathTraceResult r = tracer.render(camera, size, size, settings);
        run.gpuMilliseconds += r.gpuMilliseconds;
        if (sum.pixels.empty()) sum = r.image;
        else
            for (size_t i = 0; i < sum.pixels.size(); ++i) sum.pixels[i] += r.image.pixels[i];
        ++batches;
        if (batches == nextLevel) {
            core::ImageRgba32f mean = sum;
            for (float& v : mean.pixels) v /= float(batches);
            run.levels.push_back(mean);
            nextLevel *= 4;
        }
    }
    return run;
}

}  // namespace idk::test
