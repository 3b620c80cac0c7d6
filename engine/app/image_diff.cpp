// image_diff.cpp: PSNR and the diff image of `idk compare` (app/image_compare.hpp).
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "app/image_compare.hpp"
#include "core/log.hpp"

namespace idk::app {

double psnr(const ImageDifference& d) {
    if (d.rmse == 0.0) return std::numeric_limits<double>::infinity();
    return -20.0 * std::log10(d.rmse);
}

DiffImage diffImage(const core::ImageRgba32f& a, const core::ImageRgba32f& b, float epsilon) {
    if (a.width != b.width || a.height != b.height)
        throw std::invalid_argument(core::concat("image sizes differ: ", a.width, "x", a.height, " vs ", b.width, "x",
                                                 b.height));
    DiffImage out;
    out.image.width = a.width;
    out.image.height = a.height;
    out.image.pixels.resize(a.pixels.size());
    const size_t pixels = size_t(a.width) * a.height;
    for (size_t p = 0; p < pixels; ++p) {
        bool changed = false;
        for (size_t c = 0; c < 4; ++c) {
            const float va = a.pixels[4 * p + c], vb = b.pixels[4 * p + c];
            if (va == vb || (std::isnan(va) && std::isnan(vb))) continue;  // equal infinities too
            changed = changed || !(std::fabs(va - vb) <= epsilon);  // NaN against a number: changed
        }
        float* o = &out.image.pixels[4 * p];
        if (changed) {
            o[0] = 1.0f, o[1] = 0.0f, o[2] = 1.0f;
            ++out.changedPixels;
        } else {
            const float* r = &b.pixels[4 * p];
            const float y = 0.2126f * r[0] + 0.7152f * r[1] + 0.0722f * r[2];
            o[0] = o[1] = o[2] = std::isfinite(y) ? 0.25f * std::clamp(y, 0.0f, 1.0f) : 0.0f;
        }
        o[3] = 1.0f;
    }
    return out;
}

}  // namespace idk::app
