// same_pixels.hpp: per-pixel agreement of two renders of the same camera at the same seed (the GPU path tracer
// against its CPU reference): the fraction of pixels whose RGB all lie within 1e-3 relative of the reference's.
#pragma once
#include <cmath>
#include <cstddef>

#include "core/image_file.hpp"

namespace idk::test {

inline double samePixelFraction(const core::ImageRgba32f& gpu, const core::ImageRgba32f& cpu) {
    size_t same = 0;
    const size_t pixels = size_t(cpu.width) * cpu.height;
    for (size_t p = 0; p < pixels; ++p) {
        bool close = true;
        for (int k = 0; k < 3; ++k) {
            const float a = gpu.pixels[4 * p + k], b = cpu.pixels[4 * p + k];
            close &= std::abs(a - b) <= 1e-3f * (1.0f + std::abs(b));
        }
        same += close;
    }
    return double(same) / double(pixels);
}

}  // namespace idk::test
