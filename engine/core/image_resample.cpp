// image_resample.cpp: box filter, bilinear upscaling and display compression of RGBA float images.
#include "core/image_resample.hpp"

#include <algorithm>
#include <cmath>

namespace idk::core {

ImageRgba32f boxDownsample(const ImageRgba32f& big, uint32_t k) {
    ImageRgba32f out;
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

ImageRgba32f bilinearUpscale(const ImageRgba32f& small, uint32_t width, uint32_t height) {
    ImageRgba32f out;
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

ImageRgba32f compressed(const ImageRgba32f& image) {
    ImageRgba32f out = image;
    for (size_t i = 0; i < out.pixels.size(); ++i)
        if (i % 4 != 3) out.pixels[i] = std::max(out.pixels[i], 0.0f) / (1.0f + std::max(out.pixels[i], 0.0f));
    return out;
}

}  // namespace idk::core
