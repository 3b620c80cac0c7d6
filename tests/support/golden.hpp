// golden.hpp: golden-image comparison for display frames (8-bit sRGB, what `idk render --out x.png` writes),
// goldens in tests/golden/<name>.png. Test support, no IDKEngine counterpart.
#pragma once
// Metric: per pixel, the largest channel difference in 8-bit codes;
// a pixel is "bad" above kGoldenPixelTolerance codes; a frame passes when at most kGoldenBadFraction of its pixels
// are bad and the mean difference over all channels stays below kGoldenMeanTolerance codes. On failure a diff image
// (actual | golden | 8x difference) is written to <build>/golden_diff/<name>_diff.png.
// IDK_ACCEPT_GOLDENS=1 rewrites the golden instead of comparing (scripts/accept_goldens.sh).
#include <cstdint>
#include <string>
#include <vector>

namespace idk::test {

inline constexpr int kGoldenPixelTolerance = 4;      // codes of 255
inline constexpr double kGoldenBadFraction = 0.01;   // of the pixels
inline constexpr double kGoldenMeanTolerance = 0.5;  // codes of 255, mean over RGB of all pixels

struct GoldenResult {
    bool passed = false;
    bool accepted = false;  // IDK_ACCEPT_GOLDENS=1: the golden was (re)written
    double badFraction = 0.0;
    double meanDifference = 0.0;
    int maxDifference = 0;
    std::string message;  // why it failed, and where the diff image is
};

// `rgba` is width * height * 4 display-encoded bytes (FrameResult::display).
GoldenResult compareWithGolden(const std::string& name, const std::vector<uint8_t>& rgba, uint32_t width,
                               uint32_t height);

}  // namespace idk::test
