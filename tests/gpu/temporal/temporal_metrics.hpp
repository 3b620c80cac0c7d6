// temporal_metrics.hpp: helpers of the temporal-pass tests: the k x k box filter that turns a k-times-larger
// render into the supersampled reference, and the error of a frame against it (RMSE and FLIP of display-compressed
// values).
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "app/flip.hpp"
#include "app/image_compare.hpp"
#include "core/image_file.hpp"

namespace idk::test {

inline core::ImageRgba32f boxDownsample(const core::ImageRgba32f& big, uint32_t k) {
    core::ImageRgba32f out;
    out.width = big.width / k;
    out.height = big.height / k;
    out.pixels.assign(size_t(out.width) * out.height * 4, 0.0f);
    for (uint32_t y = 0; y < out.height; ++y)
        for (uint32_t x = 0; x < out.width; ++x)
            for (uint32_t c = 0; c < 4; ++c) {
                double sum = 0.0;
                for (uint32_t j = 0; j < k; ++j)
                    for (uint32_t i = 0; i < k; ++i)
                        sum += big.pixels[(size_t(y * k + j) * big.width + (x * k + i)) * 4 + c];
                out.pixels[(size_t(y) * out.width + x) * 4 + c] = float(sum / double(k * k));
            }
    return out;
}

// Bilinear resampling of `small` to width x height (pixel centres aligned, edges clamped): the plain upscaling
// the temporal upscaler is compared with.
inline core::ImageRgba32f bilinearUpscale(const core::ImageRgba32f& small, uint32_t width, uint32_t height) {
    core::ImageRgba32f out;
    out.width = width;
    out.height = height;
    out.pixels.assign(size_t(width) * height * 4, 0.0f);
    const auto at = [&](int x, int y, uint32_t c) {
        x = std::clamp(x, 0, int(small.width) - 1);
        y = std::clamp(y, 0, int(small.height) - 1);
        return small.pixels[(size_t(y) * small.width + x) * 4 + c];
    };
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) {
            const float sx = (float(x) + 0.5f) * float(small.width) / float(width) - 0.5f;
            const float sy = (float(y) + 0.5f) * float(small.height) / float(height) - 0.5f;
            const int x0 = int(std::floor(sx)), y0 = int(std::floor(sy));
            const float fx = sx - float(x0), fy = sy - float(y0);
            for (uint32_t c = 0; c < 4; ++c) {
                const float top = at(x0, y0, c) * (1.0f - fx) + at(x0 + 1, y0, c) * fx;
                const float bottom = at(x0, y0 + 1, c) * (1.0f - fx) + at(x0 + 1, y0 + 1, c) * fx;
                out.pixels[(size_t(y) * width + x) * 4 + c] = top * (1.0f - fy) + bottom * fy;
            }
        }
    return out;
}

// Errors of HDR frames as a display would show them: both images are compressed per channel with c / (1 + c)
// (Reinhard) first, so a bright light's edge counts like any other edge (the Cornell light is ~ 50, and relative
// MSE of the linear values is dominated by those few pixels).
inline core::ImageRgba32f compressed(const core::ImageRgba32f& image) {
    core::ImageRgba32f out = image;
    for (size_t i = 0; i < out.pixels.size(); ++i)
        if (i % 4 != 3) out.pixels[i] = std::max(out.pixels[i], 0.0f) / (1.0f + std::max(out.pixels[i], 0.0f));
    return out;
}

struct FrameError {
    double rmse = 0.0;  // RMSE of the compressed values (in [0, 1])
    double flip = 0.0;  // mean LDR-FLIP of the compressed values
    std::string text() const {
        char s[96];
        std::snprintf(s, sizeof s, "RMSE %.5f FLIP %.5f", rmse, flip);
        return s;
    }
};

inline FrameError frameError(const core::ImageRgba32f& image, const core::ImageRgba32f& reference) {
    const core::ImageRgba32f a = compressed(image), b = compressed(reference);
    return {app::compareImages(a, b).rmse, app::computeFlip(a, b).mean};
}

}  // namespace idk::test
