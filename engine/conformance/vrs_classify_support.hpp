// vrs_classify_support.hpp: what the VRS checks (vrs_checks.cpp, vrs_frame_checks.cpp) and their asset-based tests
// (tests/conformance/vrs/, tests/gpu/vrs/) share. For the classifier: an HDR frame the renderer produced with a camera-like velocity field, at a size
// that leaves partial tiles, the edge-case tiles patched into it, the GPU classifier (vrs/classify.comp.glsl) run
// on it, and the comparison with its CPU oracle (frame::classifyTilesCpu): identical rates on every tile (the shared
// arithmetic of shared/vrs_types.h rounds the same on every device).
#pragma once
#include <glm/glm.hpp>

#include <array>
#include <string>
#include <vector>

#include "conformance/conformance.hpp"
#include "core/image_file.hpp"
#include "passes/vrs_passes.hpp"
#include "scene/scene.hpp"

namespace idk::conformance {

constexpr uint32_t kVrsWidth = 200, kVrsHeight = 136;  // not multiples of 16 or 32: partial tiles

struct VrsFrame {
    std::vector<glm::vec4> lit;  // as stored in RGBA16F
    std::vector<glm::vec2> velocity;
};

// An HDR frame of the scene (values exactly as the RGBA16F target held them) and a velocity field: a rotation
// about the image centre plus a zoom, up to ~0.008 UV per frame (0.5 UV/s at 60 Hz).
VrsFrame recordVrsFrame(vk::Context& ctx, vk::ShaderLibrary& shaders, const scene::Scene& scene);

// Edge cases in tiles of 32 pixels (each covers whole tiles of every tested size), row 0 lit, row 1 velocity: zero
// luminance, constant colour, NaN, +inf, 65504/0.01, negative radiance; velocity 1e6 and NaN; mean below 0.001.
void patchVrsEdgeCases(VrsFrame& f);

// The GPU classifier's rate per tile (row-major tiles).
std::vector<uint32_t> classifyOnGpu(vk::Context& ctx, vk::ShaderLibrary& shaders, const VrsFrame& f,
                                    const passes::VrsClassifyParams& params);

// GPU vs CPU oracle on every tile, recorded in v; returns the histogram of the oracle's rates (1x1 .. 4x4).
std::array<int, 5> expectClassifierMatches(Verdict& v, vk::Context& ctx, vk::ShaderLibrary& shaders, const VrsFrame& f,
                                           const passes::VrsClassifyParams& params, const std::string& what);

// The software rung's frame checks on `scene` (two views; vrs_frame_checks.cpp registers them on the Cornell box):
// 1x1 everywhere equals VRS off bit for bit; at coarse rates exactly the counted anchors are shaded.
void expectOneByOneEqualsOff(CheckEnv& env, Verdict& v, const scene::Scene& scene);
void expectCoarseCountedInvocations(CheckEnv& env, Verdict& v, const scene::Scene& scene);

// PSNR (peak 1) over the RGB channels with radiance clipped at 1: the VRS frame comparisons (the hardware rung
// against the software rung, VRS on against off on DamagedHelmet).
double clippedPsnr(const core::ImageRgba32f& a, const core::ImageRgba32f& b);

// The frame-level checks of vrs_frame_checks.cpp (software rung 1x1 and coarse rates, hardware rung), which
// vrsChecks() lists too.
std::vector<Check> vrsFrameChecks();

}  // namespace idk::conformance
