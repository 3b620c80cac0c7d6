// golden.cpp: reads/writes tests/golden/*.png through OpenImageIO as raw 8-bit codes (no colour conversion) and
// compares them with a frame's display bytes (metric in golden.hpp).
#include "support/golden.hpp"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <sstream>

namespace idk::test {
namespace {

bool writePng(const std::filesystem::path& path, const std::vector<uint8_t>& rgba, uint32_t w, uint32_t h) {
    std::filesystem::create_directories(path.parent_path());
    auto out = OIIO::ImageOutput::create(path.string());
    if (!out) return false;
    OIIO::ImageSpec spec(int(w), int(h), 4, OIIO::TypeDesc::UINT8);
    bool ok = out->open(path.string(), spec) && out->write_image(OIIO::TypeDesc::UINT8, rgba.data());
    out->close();
    return ok;
}

bool readPng(const std::filesystem::path& path, std::vector<uint8_t>& rgba, uint32_t& w, uint32_t& h) {
    auto in = OIIO::ImageInput::open(path.string());
    if (!in) return false;
    const OIIO::ImageSpec& spec = in->spec();
    if (spec.nchannels != 4) return false;
    w = uint32_t(spec.width);
    h = uint32_t(spec.height);
    rgba.resize(size_t(w) * h * 4);
    bool ok = in->read_image(0, 0, 0, 4, OIIO::TypeDesc::UINT8, rgba.data());
    in->close();
    return ok;
}

}  // namespace

GoldenResult compareWithGolden(const std::string& name, const std::vector<uint8_t>& rgba, uint32_t width,
                               uint32_t height) {
    GoldenResult r;
    const std::filesystem::path golden = std::filesystem::path(IDK_SOURCE_DIR) / "tests" / "golden" / (name + ".png");
    const char* accept = std::getenv("IDK_ACCEPT_GOLDENS");
    if (accept && std::string(accept) == "1") {
        r.accepted = r.passed = writePng(golden, rgba, width, height);
        r.message = r.passed ? "accepted " + golden.string() : "cannot write " + golden.string();
        return r;
    }
    std::vector<uint8_t> expected;
    uint32_t ew = 0, eh = 0;
    if (!readPng(golden, expected, ew, eh)) {
        r.message = "no golden image " + golden.string() + " (run scripts/accept_goldens.sh)";
        return r;
    }
    if (ew != width || eh != height) {
        r.message = "golden " + golden.string() + " is " + std::to_string(ew) + "x" + std::to_string(eh);
        return r;
    }
    size_t pixels = size_t(width) * height, bad = 0;
    double sum = 0.0;
    std::vector<uint8_t> diff(pixels * 3 * 4, 255);
    for (size_t p = 0; p < pixels; ++p) {
        int worst = 0;
        for (int c = 0; c < 3; ++c) {
            int d = std::abs(int(rgba[p * 4 + c]) - int(expected[p * 4 + c]));
            worst = std::max(worst, d);
            sum += d;
        }
        r.maxDifference = std::max(r.maxDifference, worst);
        if (worst > kGoldenPixelTolerance) ++bad;
        size_t x = p % width, y = p / width;
        for (int c = 0; c < 3; ++c) {
            diff[(y * width * 3 + x) * 4 + c] = rgba[p * 4 + c];
            diff[(y * width * 3 + x + width) * 4 + c] = expected[p * 4 + c];
            diff[(y * width * 3 + x + 2 * width) * 4 + c] =
                uint8_t(std::min(255, 8 * std::abs(int(rgba[p * 4 + c]) - int(expected[p * 4 + c]))));
        }
    }
    r.badFraction = double(bad) / double(pixels);
    r.meanDifference = sum / double(pixels * 3);
    r.passed = r.badFraction <= kGoldenBadFraction && r.meanDifference <= kGoldenMeanTolerance;
    std::ostringstream msg;
    msg << name << ": " << r.badFraction * 100.0 << "% pixels off by more than " << kGoldenPixelTolerance
        << " codes (limit " << kGoldenBadFraction * 100.0 << "%), mean difference " << r.meanDifference
        << " codes (limit " << kGoldenMeanTolerance << "), max " << r.maxDifference;
    if (!r.passed) {
        std::filesystem::path diffPath = std::filesystem::path(IDK_BINARY_DIR) / "golden_diff" / (name + "_diff.png");
        writePng(diffPath, diff, width * 3, height);
        msg << "; diff image (actual | golden | 8x difference): " << diffPath.string();
    }
    r.message = msg.str();
    return r;
}

}  // namespace idk::test
