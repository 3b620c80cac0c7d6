// cmd_compare.cpp: `idk compare A B [--metric rmse|relmse|psnr|flip] [--fail-above X | --fail-below X]
// [--diff F.png] [--json]`: reads two images (EXR keeps linear floats; PNG is sRGB-decoded) and prints how far A is
// from the reference B (app/image_compare.hpp, app/flip.hpp). With a gate it exits 1 when the chosen metric is
// above/below the threshold (golden-image tests in CI); --diff writes an image marking exactly the changed pixels.
// The path-tracer benchmarks (scripts/bench_pathtrace.sh) measure error against time with it. No IDKEngine
// counterpart.
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <limits>
#include <cstdio>
#include <iostream>
#include <stdexcept>

#include "app/commands.hpp"
#include "app/flip.hpp"
#include "app/image_compare.hpp"
#include "core/cli.hpp"
#include "core/log.hpp"

namespace idk::app {

const char* const kCompareHelp =
    "usage: idk compare A B [--metric rmse|relmse|psnr|flip] [--fail-above X | --fail-below X] [--diff F.png] [--json]\n"
    "  A        the image to measure (.exr, .png, ... anything OpenImageIO reads)\n"
    "  B        the reference image, same size (a size mismatch is an error naming both files and sizes)\n"
    "  --metric M       the metric the gate tests and the output leads with (default rmse):\n"
    "                   rmse, relmse = mean (a-b)^2 / (b^2 + 0.01), psnr = -20 log10(rmse) dB (peak 1; inf when\n"
    "                   identical), flip = mean LDR-FLIP (Andersson et al. 2020; values clamped to [0,1]; 0 = same,\n"
    "                   1 = black against white), all over the RGB channels of the linear values\n"
    "  --fail-above X   exit 1 when the metric is above X (rmse, relmse, flip)\n"
    "  --fail-below X   exit 1 when the metric is below X (psnr)\n"
    "  --diff F.png     write a diff image: magenta where any RGBA channel differs (8-bit inputs: by any amount;\n"
    "                   float inputs: by more than 1e-6), elsewhere the reference as dim grey\n"
    "  --json   machine-readable output\n"
    "Also prints the mean and maximum absolute error, and the NaN/inf channel count of each image (those channels\n"
    "are left out of the metrics). Exit codes: 0 = passed (or no gate), 1 = the gate failed or an image is missing,\n"
    "unreadable or of another size (named in the message), 2 = a usage error.\n";

namespace {

bool isEightBit(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    return ext == ".png" || ext == ".jpg" || ext == ".jpeg" || ext == ".bmp" || ext == ".tga";
}

}  // namespace

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
    core::CliArgs cli = core::parseCli(args, {{"--json", "--help"}, {"--metric", "--fail-above", "--fail-below", "--diff"}});
    if (cli.has("--help")) {
        std::fputs(kCompareHelp, stdout);
        return 0;
    }
    if (cli.positional.size() != 2) throw core::CliError("expected two images: A and the reference B");
    const std::string metric = cli.get("--metric", "rmse");
    if (metric != "rmse" && metric != "relmse" && metric != "psnr" && metric != "flip")
        throw core::CliError("--metric '" + metric + "': use rmse, relmse, psnr or flip");
    const std::optional<std::string> above = cli.get("--fail-above"), below = cli.get("--fail-below");
    if (above && below) throw core::CliError("give one of --fail-above and --fail-below");
    std::optional<double> threshold;
    if (above || below) {
        threshold = core::parseNumber(above ? "--fail-above" : "--fail-below", above ? *above : *below);
        if (std::isnan(*threshold)) throw core::CliError("the gate's threshold is NaN");
    }
    const std::optional<std::string> diffPath = cli.get("--diff");
    if (diffPath) {
        const std::string ext = std::filesystem::path(*diffPath).extension().string();
        if (ext != ".png" && ext != ".exr") throw core::CliError("--diff '" + *diffPath + "': the file must end in .png or .exr");
    }
    const std::string& pathA = cli.positional[0];
    const std::string& pathB = cli.positional[1];
    const core::ImageRgba32f a = core::readImage(pathA);  // throws naming the file
    const core::ImageRgba32f b = core::readImage(pathB);
    if (a.width != b.width || a.height != b.height)
        throw std::runtime_error(core::concat(pathA, " (", a.width, "x", a.height, ") vs ", pathB, " (", b.width, "x",
                                              b.height, "): image sizes differ; compare images of one size"));
    const ImageDifference d = compareImages(a, b);
    const double peakSnr = psnr(d);
    const double flip = metric == "flip" ? computeFlip(a, b).mean : std::numeric_limits<double>::quiet_NaN();
    const double value = metric == "rmse" ? d.rmse : metric == "relmse" ? d.relativeMse : metric == "psnr" ? peakSnr : flip;
    // A NaN value never passes a gate.
    const bool passed = !threshold || (above ? value <= *threshold : value >= *threshold);
    size_t changed = 0;
    if (diffPath) {
        // Two 8-bit files are equal exactly when their decoded values are; floats get a tiny tolerance.
        const DiffImage diff = diffImage(a, b, isEightBit(pathA) && isEightBit(pathB) ? 0.0f : 1e-6f);
        core::writeImage(*diffPath, diff.image);
        changed = diff.changedPixels;
    }
    if (cli.has("--json")) {
        auto finite = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
        nlohmann::json j;
        j["a"] = pathA;
        j["b"] = pathB;
        j["width"] = a.width;
        j["height"] = a.height;
        j["channels"] = d.channels;
        j["rmse"] = d.rmse;
        j["relMse"] = d.relativeMse;
        j["psnr"] = finite(peakSnr);  // null: identical (infinite PSNR)
        if (metric == "flip") j["flip"] = flip;
        j["meanAbsError"] = d.meanAbsError;
        j["maxError"] = d.maxError;
        j["nanCount"] = d.nonFiniteA + d.nonFiniteB;
        j["nonFiniteA"] = d.nonFiniteA;
        j["nonFiniteB"] = d.nonFiniteB;
        j["metric"] = metric;
        j["value"] = finite(value);
        if (threshold) j["gate"] = {{above ? "failAbove" : "failBelow", *threshold}, {"passed", passed}};
        if (diffPath) j["diff"] = {{"file", *diffPath}, {"changedPixels", changed}};
        std::cout << j.dump(2) << "\n";
    } else {
        std::printf("%s vs reference %s (%ux%u, %zu RGB channels)\n", pathA.c_str(), pathB.c_str(), a.width, a.height,
                    d.channels);
        std::printf("  RMSE            %.6g\n", d.rmse);
        std::printf("  relative MSE    %.6g\n", d.relativeMse);
        std::printf("  PSNR            %.6g dB\n", peakSnr);
        if (metric == "flip") std::printf("  FLIP (mean)     %.6g\n", flip);
        std::printf("  mean abs error  %.6g\n", d.meanAbsError);
        std::printf("  max error       %.6g\n", d.maxError);
        std::printf("  NaN/inf         %zu in A, %zu in B\n", d.nonFiniteA, d.nonFiniteB);
        if (diffPath) std::printf("  diff            %s (%zu changed pixels)\n", diffPath->c_str(), changed);
        if (threshold)
            std::printf("gate: %s %.6g %s %.6g: %s\n", metric.c_str(), value, above ? "<=" : ">=", *threshold,
                        passed ? "PASS" : "FAIL");
    }
    return passed ? 0 : 1;
}

}  // namespace idk::app
