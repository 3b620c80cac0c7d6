// image_resample.hpp: resampling of RGBA float images for the references of temporal passes: the k x k box filter
// that turns a k-times-larger render into the supersampled reference, plain bilinear upscaling (what the temporal
// upscaler is compared with), and the display compression c / (1 + c) under which their errors are measured.
#pragma once
#include <cstdint>

#include "core/image_file.hpp"

namespace idk::core {

// Each output pixel is the mean of its k x k block of `big` (width and height cut to multiples of k).
ImageRgba32f boxDownsample(const ImageRgba32f& big, uint32_t k);

// Bilinear resampling of `small` to width x height (pixel centres aligned, edges clamped).
ImageRgba32f bilinearUpscale(const ImageRgba32f& small, uint32_t width, uint32_t height);

// Each colour channel c (not alpha) becomes max(c, 0) / (1 + max(c, 0)) (Reinhard): errors as a display shows them,
// so a bright light's edge counts like any other edge.
ImageRgba32f compressed(const ImageRgba32f& image);

}  // namespace idk::core
