// image_compare_test.cpp: `idk compare` (engine/app/cmd_compare.cpp): the metrics against hand-computed values, the
// NaN handling, and the errors that name the file (missing, unreadable, size mismatch).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include <unistd.h>

#include "app/commands.hpp"
#include "app/image_compare.hpp"
#include "core/cli.hpp"
#include "core/image_file.hpp"

namespace idk::app {
namespace {

core::ImageRgba32f image(uint32_t w, uint32_t h, float value) {
    core::ImageRgba32f img;
    img.width = w;
    img.height = h;
    img.pixels.assign(size_t(w) * h * 4, value);
    return img;
}

TEST(ImageCompare, MetricsMatchHandComputedValues) {
    core::ImageRgba32f ref = image(2, 1, 1.0f);
    core::ImageRgba32f a = ref;
    a.pixels[0] = 2.0f;   // error 1 in one channel
    a.pixels[5] = 0.5f;   // error -0.5
    a.pixels[3] = 99.0f;  // alpha: ignored
    ImageDifference d = compareImages(a, ref);
    EXPECT_EQ(d.channels, 6u);
    EXPECT_NEAR(d.rmse, std::sqrt((1.0 + 0.25) / 6.0), 1e-12);
    EXPECT_NEAR(d.relativeMse, (1.0 + 0.25) / 1.01 / 6.0, 1e-12);
    EXPECT_NEAR(d.meanAbsError, 1.5 / 6.0, 1e-12);
    EXPECT_DOUBLE_EQ(d.maxError, 1.0);
    EXPECT_EQ(d.nonFiniteA + d.nonFiniteB, 0u);
    EXPECT_DOUBLE_EQ(compareImages(ref, ref).rmse, 0.0);
}

TEST(ImageCompare, RelativeMseWeighsDarkReferencePixelsMore) {
    core::ImageRgba32f dark = image(1, 1, 0.0f), bright = image(1, 1, 10.0f);
    core::ImageRgba32f darkPlus = image(1, 1, 0.1f), brightPlus = image(1, 1, 10.1f);
    EXPECT_NEAR(compareImages(darkPlus, dark).relativeMse, 0.01 / 0.01, 1e-6);
    EXPECT_NEAR(compareImages(brightPlus, bright).relativeMse, 0.01 / 100.01, 1e-6);
}

TEST(ImageCompare, NonFiniteChannelsAreCountedAndLeftOut) {
    core::ImageRgba32f ref = image(2, 2, 1.0f), a = ref;
    a.pixels[0] = NAN;
    a.pixels[4] = INFINITY;
    ref.pixels[9] = NAN;
    ImageDifference d = compareImages(a, ref);
    EXPECT_EQ(d.nonFiniteA, 2u);
    EXPECT_EQ(d.nonFiniteB, 1u);
    EXPECT_EQ(d.channels, 12u - 3u);
    EXPECT_DOUBLE_EQ(d.rmse, 0.0);
}

TEST(ImageCompare, SizeMismatchThrows) {
    EXPECT_THROW(compareImages(image(2, 2, 0), image(2, 3, 0)), std::invalid_argument);
}

class CompareCommand : public ::testing::Test {
protected:
    // One folder per process and test: ctest runs the tests of this fixture in parallel processes.
    std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                ("idk_compare_test_" + std::to_string(::getpid()) + "_" +
                                 ::testing::UnitTest::GetInstance()->current_test_info()->name());
    void SetUp() override { std::filesystem::create_directories(dir); }
    void TearDown() override { std::filesystem::remove_all(dir); }
    std::string expectErrorNaming(const std::vector<std::string>& args, const std::string& name) {
        try {
            runCompare(args);
        } catch (const std::runtime_error& e) {
            EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
            return e.what();
        }
        ADD_FAILURE() << "no error";
        return {};
    }
};

TEST_F(CompareCommand, ComparesTwoExrFiles) {
    core::writeImage(dir / "a.exr", image(4, 4, 0.5f));
    core::writeImage(dir / "b.exr", image(4, 4, 0.25f));
    testing::internal::CaptureStdout();
    EXPECT_EQ(runCompare({(dir / "a.exr").string(), (dir / "b.exr").string(), "--json"}), 0);
    std::string out = testing::internal::GetCapturedStdout();
    EXPECT_NE(out.find("\"rmse\": 0.25"), std::string::npos) << out;
    EXPECT_NE(out.find("\"nanCount\": 0"), std::string::npos) << out;
}

TEST_F(CompareCommand, MissingUnreadableAndMismatchedFilesAreNamed) {
    core::writeImage(dir / "a.exr", image(4, 4, 0.5f));
    core::writeImage(dir / "small.exr", image(2, 4, 0.5f));
    std::ofstream(dir / "junk.exr") << "not an image";
    const std::string a = (dir / "a.exr").string();
    expectErrorNaming({a, (dir / "missing.exr").string()}, "missing.exr");
    expectErrorNaming({(dir / "junk.exr").string(), a}, "junk.exr");
    std::string msg = expectErrorNaming({a, (dir / "small.exr").string()}, "small.exr");
    // Both files with their sizes, and the cause.
    EXPECT_NE(msg.find("a.exr (4x4) vs "), std::string::npos) << msg;
    EXPECT_NE(msg.find("small.exr (2x4)"), std::string::npos) << msg;
    EXPECT_NE(msg.find("image sizes differ"), std::string::npos) << msg;
}

TEST_F(CompareCommand, UsageErrors) {
    EXPECT_THROW(runCompare({"only_one.exr"}), core::CliError);
    EXPECT_THROW(runCompare({"a.exr", "b.exr", "--bogus"}), core::CliError);
}

}  // namespace
}  // namespace idk::app
