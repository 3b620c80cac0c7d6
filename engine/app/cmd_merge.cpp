// cmd_merge.cpp: `idk merge PART.exr... --out F.exr [--raw]`: combines the raw accumulations that
// `idk render --pathtrace --sample-range a:b` tasks wrote (RGB = radiance sum, A = sample count, per pixel) into
// the image one machine renders with all their samples: the sums and counts are added in fp32 in the order the
// parts are given (the farm gives them in sample order), then the mean is taken as the GPU's resolve pass does
// (sum * (1 / count), alpha 1). --raw writes the merged accumulation instead, so merges compose.
//
// What holds against a single `idk render --pathtrace --spp N --seed S` (the same samples on one machine): the
// same expected value always. One part (a:b = 0:N) is bit-identical. Several parts differ only by fp32 rounding:
// one machine adds the samples one by one into one sum, the merge adds per-part sums, and fp32 addition is not
// associative; per pixel the difference is bounded by about N * 2^-24 of the summed magnitudes (tests/farm: within
// 1e-5 relative for a few dozen samples). No IDKEngine counterpart.
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "app/commands.hpp"
#include "core/cli.hpp"
#include "core/image_file.hpp"

namespace idk::app {

const char* const kMergeHelp =
    "usage: idk merge PART.exr [PART.exr ...] --out FILE.exr [--raw]\n"
    "  PART.exr   raw accumulations of `idk render --pathtrace --sample-range a:b --out PART.exr` of the same scene,\n"
    "             camera, size and --seed (RGB = radiance sum, A = sample count); added in the order given\n"
    "  --out F    the merged image: mean radiance (alpha 1), as `idk render --pathtrace --spp N` writes it\n"
    "  --raw      write the merged accumulation (sum, count) instead, to merge it again later\n"
    "Equal in expectation to one render with all the samples; bit-identical for a single part, otherwise within fp32\n"
    "rounding of the summation order (about N * 6e-8 relative for N samples). Exit 1 when a part is unreadable, of\n"
    "another size, or its alpha is not a whole positive sample count (the message names the file).\n";

namespace {

// The sample count a part stores in its alpha channel: a whole number >= 1 at every pixel.
void checkCounts(const std::filesystem::path& file, const core::ImageRgba32f& part) {
    for (size_t i = 3; i < part.pixels.size(); i += 4) {
        const float n = part.pixels[i];
        if (!(n >= 1.0f) || n != std::floor(n) || n > 16777216.0f)
            throw std::runtime_error(file.string() + ": alpha " + std::to_string(n) + " at pixel " +
                                     std::to_string(i / 4) + " is not a sample count (is it an --sample-range output?)");
    }
}

}  // namespace

int runMerge(const std::vector<std::string>& argv) {
    core::CliArgs args = core::parseCli(argv, {{"--help", "--raw"}, {"--out"}});
    if (args.has("--help")) {
        std::fputs(kMergeHelp, stdout);
        return 0;
    }
    const std::optional<std::string> out = args.get("--out");
    if (!out) throw core::CliError("--out FILE.exr is required");
    if (std::filesystem::path(*out).extension() != ".exr") throw core::CliError("--out '" + *out + "': must end in .exr");
    if (args.positional.empty()) throw core::CliError("give at least one PART.exr");

    core::ImageRgba32f sum;
    for (const std::string& file : args.positional) {
        const core::ImageRgba32f part = core::readImage(file);  // throws naming the file
        checkCounts(file, part);
        if (sum.pixels.empty()) {
            sum = part;
            continue;
        }
        if (part.width != sum.width || part.height != sum.height)
            throw std::runtime_error(file + ": " + std::to_string(part.width) + "x" + std::to_string(part.height) +
                                     ", but " + args.positional[0] + " is " + std::to_string(sum.width) + "x" +
                                     std::to_string(sum.height));
        for (size_t i = 0; i < sum.pixels.size(); ++i) sum.pixels[i] += part.pixels[i];
    }
    if (!args.has("--raw")) {
        for (size_t i = 0; i < sum.pixels.size(); i += 4) {
            // The resolve pass's arithmetic (shaders_glsl/pathtrace/resolve.comp.glsl): fp32 reciprocal, then products.
            const float inv = 1.0f / sum.pixels[i + 3];
            for (int c = 0; c < 3; ++c) sum.pixels[i + c] *= inv;
            sum.pixels[i + 3] = 1.0f;
        }
    }
    core::writeImage(*out, sum);
    std::fprintf(stderr, "idk merge: wrote %s (%ux%u, %zu part(s))\n", out->c_str(), sum.width, sum.height,
                 args.positional.size());
    return 0;
}

}  // namespace idk::app
