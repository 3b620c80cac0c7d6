// `idk render --pathtrace --out F.png` shows radiance as the raster does: exposure, AgX, sRGB. The PNG of a render
// must equal the independent AgX oracle (tests/support/pbr_oracle.cpp) applied to the EXR of the same render
// (same seed: the GPU tracer is deterministic), within one 8-bit code.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <unistd.h>

#include "app/commands.hpp"
#include "core/image_file.hpp"
#include "support/pbr_oracle.hpp"

namespace idk::test {
namespace {

TEST(PtPngOutput, IsTheAgxDisplayTransformOfTheExr) {
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / ("idk_pt_png_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const std::string exr = (dir / "x.exr").string(), png = (dir / "x.png").string();
    const std::vector<std::string> common = {"--pathtrace", "--spp", "2", "--size", "24x24", "--seed", "5",
                                             "--max-depth", "4", "--exposure", "1.5"};
    std::vector<std::string> a = common, b = common;
    a.insert(a.end(), {"--out", exr});
    b.insert(b.end(), {"--out", png});
    ASSERT_EQ(app::runRender(a), 0);
    ASSERT_EQ(app::runRender(b), 0);
    const core::ImageRgba32f radiance = core::readImage(exr);
    const core::ImageRgba32f shown = core::readImage(png);  // decoded to linear by readImage
    ASSERT_EQ(radiance.pixels.size(), shown.pixels.size());
    int worst = 0;
    double brightest = 0.0;
    for (size_t i = 0; i < radiance.pixels.size(); i += 4) {
        const glm::dvec3 r(radiance.pixels[i], radiance.pixels[i + 1], radiance.pixels[i + 2]);
        brightest = std::max(brightest, std::max(r.x, std::max(r.y, r.z)));
        const glm::dvec3 expected = agx(1.5 * r);
        for (int c = 0; c < 3; ++c) {
            const int want = int(std::lround(255.0 * srgbEncode(expected[c])));
            const int got = int(std::lround(255.0 * srgbEncode(double(shown.pixels[i + c]))));
            worst = std::max(worst, std::abs(want - got));
        }
    }
    EXPECT_LE(worst, 1) << "8-bit codes between the PNG and AgX of the EXR";
    EXPECT_GT(brightest, 1.0) << "the test covers radiance above 1, where a clamp and a tone curve differ";
    std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace idk::test
