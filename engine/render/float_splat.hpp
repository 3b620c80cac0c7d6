// float_splat.hpp: float atomic add on every rung of the "float-atomics" ladder: bins[bin[i]] += value[i] by
// Vulkan float atomics (native), by OpenGL's GL_NV_shader_atomic_float on shared memory (gl-interop), or by a
// compare-and-swap loop (fallback), followed in the same render graph by a Vulkan pass that consumes the bins
// (their sum, through the reduction of compute_primitives). The splatting step of VXGI-style accumulation and
// of histogram builders; the conformance checks run it on each rung against splatOracle.
#pragma once
#include <volk.h>

#include <filesystem>
#include <optional>
#include <vector>

#include "render/compute_primitives.hpp"
#include "vk/features.hpp"

namespace idk::render {

struct SplatInput {
    std::vector<uint32_t> bins;   // one bin per sample; bins >= binCount are dropped
    std::vector<float> values;    // one value per sample (same size as bins)
    uint32_t binCount = 0;
};

struct SplatResult {
    std::vector<float> bins;  // binCount sums
    float total = 0.0f;       // their sum, computed by the consuming Vulkan pass
    vk::Rung rung = vk::Rung::Fallback;  // the rung that ran the splat
};

// The Vulkan rungs (Native, Fallback) recorded into cmd; the caller orders the inputs before and the bins after
// (compute-shader storage access). GlInterop is not recordable: it throws std::invalid_argument.
void recordSplatAdd(VkCommandBuffer cmd, const ComputeKernels& kernels, vk::Rung rung, GpuArray bins,
                    GpuArray sampleBins, GpuArray sampleValues, uint32_t count, uint32_t binCount);

// Uploads the input, runs the graph "splat (RUNG)" -> "sum bins" on `rung` (default: the ladder's choice) and
// reads the result back. The GL pass runs when the graph records it: its inputs were uploaded and handed to GL
// before recording (CPU-side wait), it finishes GL before returning, and records the acquire barrier that gives
// the bins back to Vulkan, so the next pass of the same graph reads them. glShaderDir/gl/splat_add.comp.glsl, when
// present, replaces the build's GL source (idk conformance --shader-dir).
// Throws std::runtime_error naming the reason when the rung is unavailable on this device.
SplatResult runSplatGraph(vk::Context& ctx, vk::ShaderLibrary& shaders, const SplatInput& input,
                          std::optional<vk::Rung> rung = std::nullopt,
                          const std::filesystem::path& glShaderDir = {});

// The CPU oracle: bins summed in double, in sample order, then rounded to float; total summed in double.
SplatResult splatOracle(const SplatInput& input);

}  // namespace idk::render
