// vrs_oracle.cpp: the VRS classifier on the CPU: per tile, the maximum sanitised luminance, then the integer sums
// of fixed-point luminance, its square and speed, then the shared decision gpu::vrsTileRate. Integer sums are
// order-free and the shared arithmetic rounds the same everywhere (shared/vrs_types.h; this file is compiled
// without fma contraction), so this matches the GPU's subgroup and shared-memory reductions exactly.
#include "frame/vrs_oracle.hpp"

#include <algorithm>

#include "shared/vrs_types.h"

namespace idk::frame {

VrsTileRates classifyTilesCpu(const std::vector<glm::vec4>& lit, const std::vector<glm::vec2>& velocity,
                              uint32_t width, uint32_t height, uint32_t tileSize, float frameSeconds,
                              float speedFactor, float lumVarianceFactor) {
    VrsTileRates out;
    out.tileSize = tileSize;
    out.tilesX = (width + tileSize - 1) / tileSize;
    out.tilesY = (height + tileSize - 1) / tileSize;
    const uint32_t tilePixels = tileSize * tileSize;
    const float invFrameSeconds = 1.0f / frameSeconds;
    for (uint32_t ty = 0; ty < out.tilesY; ++ty) {
        for (uint32_t tx = 0; tx < out.tilesX; ++tx) {
            const uint32_t x0 = tx * tileSize, y0 = ty * tileSize;
            const uint32_t x1 = std::min(x0 + tileSize, width), y1 = std::min(y0 + tileSize, height);
            uint32_t maxBits = 0, speed = 0;
            for (uint32_t y = y0; y < y1; ++y)
                for (uint32_t x = x0; x < x1; ++x) {
                    const size_t i = size_t(y) * width + x;
                    maxBits = std::max(maxBits, glm::floatBitsToUint(gpu::vrsLuminance(glm::vec3(lit[i]))));
                    if (!velocity.empty()) speed += gpu::vrsSpeedFixed(velocity[i], invFrameSeconds, tilePixels);
                }
            uint32_t s1 = 0, s2 = 0;
            if (maxBits >= glm::floatBitsToUint(gpu::kVrsDarkLuminance)) {
                const float scale = gpu::vrsLumScale(maxBits, gpu::vrsLumBits(tilePixels));
                for (uint32_t y = y0; y < y1; ++y)
                    for (uint32_t x = x0; x < x1; ++x) {
                        const uint32_t q = gpu::vrsLumFixed(gpu::vrsLuminance(glm::vec3(lit[size_t(y) * width + x])), scale);
                        s1 += q;
                        s2 += q * q;
                    }
            }
            out.rates.push_back(gpu::vrsTileRate((x1 - x0) * (y1 - y0), tilePixels, maxBits, s1, s2, speed,
                                                 speedFactor, lumVarianceFactor));
        }
    }
    return out;
}

uint64_t vrsShadingInvocations(const std::vector<uint32_t>& rates, uint32_t tilesX, uint32_t tileSize, uint32_t width,
                               uint32_t height) {
    uint64_t count = 0;
    for (size_t t = 0; t < rates.size(); ++t) {
        const uint32_t x0 = uint32_t(t % tilesX) * tileSize, y0 = uint32_t(t / tilesX) * tileSize;
        const uint32_t w = std::min(tileSize, width - x0), h = std::min(tileSize, height - y0);
        const glm::uvec2 cell = gpu::vrsCellSize(rates[t]);
        count += uint64_t((w + cell.x - 1) / cell.x) * ((h + cell.y - 1) / cell.y);  // anchors at multiples of the cell
    }
    return count;
}

}  // namespace idk::frame
