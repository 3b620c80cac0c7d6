// flip_test.cpp: LDR-FLIP (engine/app/flip.hpp) on properties the paper's definition implies: 0 for identical
// images, every value in [0, 1], black against white over large regions close to 1 (the colour term alone, computed
// here by hand from the paper's constants: 0.967), monotone in the size of a colour change, and symmetric enough in
// its arguments; and the diff image / PSNR of `idk compare` (engine/app/image_compare.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "app/flip.hpp"
#include "app/image_compare.hpp"

namespace idk::app {
namespace {

core::ImageRgba32f flat(uint32_t w, uint32_t h, float r, float g, float b) {
    core::ImageRgba32f img{w, h, {}};
    for (size_t i = 0; i < size_t(w) * h; ++i) img.pixels.insert(img.pixels.end(), {r, g, b, 1.0f});
    return img;
}

core::ImageRgba32f noise(uint32_t w, uint32_t h, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    core::ImageRgba32f img{w, h, std::vector<float>(size_t(w) * h * 4, 1.0f)};
    for (size_t i = 0; i < img.pixels.size(); ++i)
        if (i % 4 != 3) img.pixels[i] = u(rng);
    return img;
}

TEST(Flip, IdenticalImagesGiveZero) {
    const core::ImageRgba32f a = noise(48, 40, 1);
    const FlipResult r = computeFlip(a, a);
    EXPECT_EQ(r.mean, 0.0);
    for (float e : r.error) ASSERT_EQ(e, 0.0f);
}

TEST(Flip, ValuesStayInTheUnitRange) {
    const FlipResult r = computeFlip(noise(48, 40, 2), noise(48, 40, 3));
    for (float e : r.error) {
        ASSERT_GE(e, 0.0f);
        ASSERT_LE(e, 1.0f);
    }
    EXPECT_GT(r.mean, 0.1);  // two unrelated noise images differ visibly
    // Out-of-range inputs (HDR, negative, NaN) are clamped, never propagated.
    core::ImageRgba32f hot = flat(16, 16, 50.0f, -3.0f, NAN);
    const FlipResult h = computeFlip(hot, flat(16, 16, 0, 0, 0));
    for (float e : h.error) ASSERT_TRUE(e >= 0.0f && e <= 1.0f);
}

TEST(Flip, BlackAgainstWhiteIsNearlyOne) {
    // Far from the borders of a large flat region there are no edges or points: FLIP is the colour term alone.
    // By hand: HyAB(white, black) = 100, ^0.7 = 25.12; cmax = HyAB(Hunt green, Hunt blue)^0.7 = 41.2; 25.12 > 0.4 cmax,
    // so 0.95 + (25.12 - 16.48) / (41.2 - 16.48) * 0.05 = 0.967.
    const FlipResult r = computeFlip(flat(64, 64, 0, 0, 0), flat(64, 64, 1, 1, 1));
    EXPECT_NEAR(r.mean, 0.967, 0.005);
    EXPECT_GT(r.mean, 0.95);
}

TEST(Flip, GrowsWithTheColourDifference) {
    const core::ImageRgba32f ref = flat(32, 32, 0.5f, 0.5f, 0.5f);
    double last = 0.0;
    for (float v : {0.52f, 0.6f, 0.75f, 1.0f}) {
        const double m = computeFlip(flat(32, 32, v, 0.5f, 0.5f), ref).mean;
        EXPECT_GT(m, last) << v;
        last = m;
    }
}

TEST(Flip, AChangedSquareIsFoundWhereItIs) {
    core::ImageRgba32f ref = flat(64, 64, 0.2f, 0.3f, 0.4f), test = ref;
    for (uint32_t y = 28; y < 36; ++y)
        for (uint32_t x = 28; x < 36; ++x) test.pixels[(size_t(y) * 64 + x) * 4 + 1] = 0.9f;
    const FlipResult r = computeFlip(test, ref);
    EXPECT_GT(r.error[32 * 64 + 32], 0.3f);  // inside the square
    EXPECT_LT(r.error[2 * 64 + 2], 1e-6f);    // far away: beyond every filter's reach
    EXPECT_THROW(computeFlip(flat(4, 4, 0, 0, 0), flat(4, 5, 0, 0, 0)), std::invalid_argument);
}

TEST(DiffImage, MarksExactlyTheChangedPixels) {
    core::ImageRgba32f ref = noise(20, 10, 4), test = ref;
    const std::vector<size_t> changed = {0, 37, 38, 199};
    test.pixels[0 * 4 + 0] += 1.0f / 255.0f;
    test.pixels[37 * 4 + 1] = -test.pixels[37 * 4 + 1] - 0.5f;
    test.pixels[38 * 4 + 3] = 0.5f;  // alpha counts too
    test.pixels[199 * 4 + 2] = NAN;
    test.pixels[100 * 4 + 2] += 1e-7f;  // within the float tolerance
    const DiffImage d = diffImage(test, ref, 1e-6f);
    EXPECT_EQ(d.changedPixels, changed.size());
    for (size_t p = 0; p < 200; ++p) {
        const float* o = &d.image.pixels[p * 4];
        const bool magenta = o[0] == 1.0f && o[1] == 0.0f && o[2] == 1.0f;
        EXPECT_EQ(magenta, std::find(changed.begin(), changed.end(), p) != changed.end()) << p;
        if (!magenta) {
            EXPECT_TRUE(o[0] == o[1] && o[1] == o[2] && o[0] <= 0.25f) << p;  // dimmed grey
        }
    }
    EXPECT_EQ(diffImage(test, ref, 0.0f).changedPixels, changed.size() + 1);  // exact: the 1e-7 pixel too
    EXPECT_EQ(diffImage(ref, ref, 0.0f).changedPixels, 0u);
}

TEST(ImageCompare, PsnrFromRmse) {
    const core::ImageRgba32f ref = flat(4, 4, 0.5f, 0.5f, 0.5f);
    EXPECT_TRUE(std::isinf(psnr(compareImages(ref, ref))));
    EXPECT_NEAR(psnr(compareImages(flat(4, 4, 0.6f, 0.6f, 0.6f), ref)), 20.0, 1e-5);  // rmse 0.1
}

}  // namespace
}  // namespace idk::app
