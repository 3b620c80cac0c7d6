// vrs_oracle.hpp: the CPU twin of the VRS classifier (vrs/classify.comp.glsl), built on the same per-tile
// decision (shared/vrs_types.h), and the shading-invocation count that a set of rates implies. The conformance
// tests hold the GPU classifier to it; `idk render --stats --json` reports the count.
#pragma once
#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace idk::frame {

struct VrsTileRates {
    uint32_t tileSize = 16, tilesX = 0, tilesY = 0;
    std::vector<uint32_t> rates;   // palette index per tile, row-major
};

// lit: RGBA per pixel (as stored, e.g. rounded through half), row-major; velocity: UV per frame per pixel, or
// empty for none.
VrsTileRates classifyTilesCpu(const std::vector<glm::vec4>& lit, const std::vector<glm::vec2>& velocity,
                              uint32_t width, uint32_t height, uint32_t tileSize, float frameSeconds,
                              float speedFactor, float lumVarianceFactor);

// Pixels shaded by lighting + sky at these rates: the coarse-cell anchors inside the image (width * height when
// every rate is 1x1).
uint64_t vrsShadingInvocations(const std::vector<uint32_t>& rates, uint32_t tilesX, uint32_t tileSize, uint32_t width,
                               uint32_t height);

}  // namespace idk::frame
