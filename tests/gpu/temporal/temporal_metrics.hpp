// temporal_metrics.hpp: helpers of the temporal-pass tests: the supersampled reference's box filter
// (core/image_resample.hpp), and the error of a frame against it (RMSE and FLIP of display-compressed
// values).
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "app/flip.hpp"
#include "app/image_compare.hpp"
#include "core/image_file.hpp"
#include "core/image_resample.hpp"

namespace idk::test {

using core::bilinearUpscale;  // core/image_resample.hpp
using core::boxDownsample;
using core::compressed;

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
