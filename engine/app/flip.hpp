// flip.hpp: LDR-FLIP, the perceptual image difference of Andersson et al. 2020 ("FLIP: A Difference Evaluator for
// Alternating Images", HPG 2020), written from the paper: both images are filtered with contrast sensitivity
// functions in the opponent space YyCxCz, compared as Hunt-adjusted CIELAB colours with the HyAB distance, and the
// colour error is raised to a power that grows with the difference of edges and points (first/second derivatives of
// a Gaussian on the luminance). Per-pixel errors are in [0, 1]; `idk compare --metric flip` reports their mean.
// Inputs are linear RGB, clamped to [0, 1] (LDR-FLIP; HDR-FLIP's exposure bracketing is not implemented).
// No IDKEngine counterpart.
#pragma once
#include <vector>

#include "core/image_file.hpp"

namespace idk::app {

// The paper's default viewing condition: a 0.7 m wide 4K monitor seen from 0.7 m (pixels per degree).
constexpr double kFlipDefaultPixelsPerDegree = 67.0206;

struct FlipResult {
    std::vector<float> error;  // width * height, each in [0, 1]
    double mean = 0.0;
};

// test and reference must have the same size (throws std::invalid_argument otherwise).
FlipResult computeFlip(const core::ImageRgba32f& test, const core::ImageRgba32f& reference,
                       double pixelsPerDegree = kFlipDefaultPixelsPerDegree);

}  // namespace idk::app
