// image_compare.hpp: error metrics between a test image and a reference image (`idk compare`, the path-tracer
// benchmarks): RMSE, relative MSE, mean and max absolute error over the RGB channels, and non-finite counts.
// No IDKEngine counterpart (the original has no image comparison tool).
#pragma once
#include <cstddef>

#include "core/image_file.hpp"

namespace idk::app {

struct ImageDifference {
    size_t channels = 0;          // RGB channels compared (both values finite)
    double rmse = 0.0;            // sqrt(mean (a - b)^2)
    double relativeMse = 0.0;     // mean (a - b)^2 / (b^2 + 1e-2)  (b: the reference)
    double meanAbsError = 0.0;    // mean |a - b|
    double maxError = 0.0;        // max |a - b|
    size_t nonFiniteA = 0;        // NaN/inf RGB channels in a (excluded from the metrics)
    size_t nonFiniteB = 0;        // ... in b
};

// a and b must have the same size (throws std::invalid_argument otherwise).
ImageDifference compareImages(const core::ImageRgba32f& a, const core::ImageRgba32f& b);

// PSNR in dB with peak 1 over the RGB channels compared: -10 log10(rmse^2); +infinity for identical images.
double psnr(const ImageDifference& d);

// The diff image of `idk compare --diff`: magenta (1, 0, 1) where any RGBA channel differs by more than `epsilon`
// (NaN against a number counts as a difference, NaN against NaN not), elsewhere the reference as a dimmed grey
// (a quarter of its luminance) so the changes stand out; alpha 1. changedPixels counts the magenta ones.
struct DiffImage {
    core::ImageRgba32f image;
    size_t changedPixels = 0;
};
DiffImage diffImage(const core::ImageRgba32f& a, const core::ImageRgba32f& b, float epsilon);

}  // namespace idk::app
