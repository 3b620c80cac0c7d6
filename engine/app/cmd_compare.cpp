// cmd_compare.cpp: `idk compare A B [--json]`: reads two images (EXR keeps linear floats; PNG is sRGB-decoded) and
// prints how far A is from the reference B (app/image_compare.hpp). The path-tracer benchmarks
// (scripts/bench_pathtrace.sh) measure error against time with it. No IDKEngine counterpart.
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <stdexcept>

#include "app/commands.hpp"
#include "app/image_compare.hpp"
#include "core/cli.hpp"
#include "core/log.hpp"

namespace idk::app {

const char* const kCompareHelp =
    "usage: idk compare A B [--json]\n"
    "  A        the image to measure (.exr, .png, ... anything OpenImageIO reads)\n"
    "  B        the reference image, same size\n"
    "  --json   machine-readable output\n"
    "Prints over the RGB channels: RMSE, relative MSE = mean (a-b)^2 / (b^2 + 0.01), mean absolute error, maximum\n"
    "absolute error, and the NaN/inf channel count of each image (those channels are left out of the metrics).\n"
    "Exits 1 naming the file when an image is missing or unreadable or the sizes differ.\n";

ImageDifference compareImages(const core::ImageRgba32f& a, const core::ImageRgba32f& b) {
    if (a.width != b.width || a.height != b.height)
        throw std::invalid_argument(core::concat("image sizes differ: ", a.width, "x", a.height, " vs ", b.width, "x",
                                                 b.height));
    ImageDifference d;
    double sumSq = 0.0, sumRel = 0.0, sumAbs = 0.0;
    const size_t pixels = size_t(a.width) * a.height;
    for (size_t p = 0; p < pixels; ++p)
        for (size_t c = 0; c < 3; ++c) {
            const double va = a.pixels[p * 4 + c], vb = b.pixels[p * 4 + c];
            const bool finiteA = std::isfinite(va), finiteB = std::isfinite(vb);
            d.nonFiniteA += finiteA ? 0 : 1;
            d.nonFiniteB += finiteB ? 0 : 1;
            if (!finiteA || !finiteB) continue;
            const double e = va - vb;
            sumSq += e * e;
            sumRel += e * e / (vb * vb + 1e-2);
            sumAbs += std::fabs(e);
            d.maxError = std::max(d.maxError, std::fabs(e));
            ++d.channels;
        }
    if (d.channels > 0) {
        d.rmse = std::sqrt(sumSq / double(d.channels));
        d.relativeMse = sumRel / double(d.channels);
        d.meanAbsError = sumAbs / double(d.channels);
    }
    return d;
}

int runCompare(const std::vector<std::string>& args) {
    core::CliArgs cli = core::parseCli(args, {{"--json", "--help"}, {}});
    if (cli.has("--help")) {
        std::fputs(kCompareHelp, stdout);
        return 0;
    }
    if (cli.positional.size() != 2) throw core::CliError("expected two images: A and the reference B");
    const std::string& pathA = cli.positional[0];
    const std::string& pathB = cli.positional[1];
    const core::ImageRgba32f a = core::readImage(pathA);  // throws naming the file
    const core::ImageRgba32f b = core::readImage(pathB);
    ImageDifference d;
    try {
        d = compareImages(a, b);
    } catch (const std::invalid_argument& e) {
        throw std::runtime_error(core::concat(pathA, " vs ", pathB, ": ", e.what()));
    }
    if (cli.has("--json")) {
        nlohmann::json j;
        j["a"] = pathA;
        j["b"] = pathB;
        j["width"] = a.width;
        j["height"] = a.height;
        j["channels"] = d.channels;
        j["rmse"] = d.rmse;
        j["relMse"] = d.relativeMse;
        j["meanAbsError"] = d.meanAbsError;
        j["maxError"] = d.maxError;
        j["nanCount"] = d.nonFiniteA + d.nonFiniteB;
        j["nonFiniteA"] = d.nonFiniteA;
        j["nonFiniteB"] = d.nonFiniteB;
        std::cout << j.dump(2) << "\n";
        return 0;
    }
    std::printf("%s vs reference %s (%ux%u, %zu RGB channels)\n", pathA.c_str(), pathB.c_str(), a.width, a.height,
                d.channels);
    std::printf("  RMSE            %.6g\n", d.rmse);
    std::printf("  relative MSE    %.6g\n", d.relativeMse);
    std::printf("  mean abs error  %.6g\n", d.meanAbsError);
    std::printf("  max error       %.6g\n", d.maxError);
    std::printf("  NaN/inf         %zu in A, %zu in B\n", d.nonFiniteA, d.nonFiniteB);
    return 0;
}

}  // namespace idk::app
