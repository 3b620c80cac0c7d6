// image_file_test.cpp: PNG and EXR writing round-trips through OpenImageIO; errors name the path.
#include <gtest/gtest.h>

#include <filesystem>

#include "core/image_file.hpp"

namespace idk::core {
namespace {

ImageRgba32f gradient() {
    ImageRgba32f img{5, 3, {}};
    for (uint32_t y = 0; y < 3; ++y)
        for (uint32_t x = 0; x < 5; ++x) img.pixels.insert(img.pixels.end(), {x / 4.0f, y / 2.0f, 2.5f, 1.0f});
    return img;
}

TEST(ImageFile, ExrKeepsLinearHdrValues) {
    auto path = std::filesystem::temp_directory_path() / "idk_image_test.exr";
    ImageRgba32f img = gradient();
    writeImage(path, img);
    ImageRgba32f back = readImage(path);
    ASSERT_EQ(back.width, 5u);
    ASSERT_EQ(back.height, 3u);
    for (size_t i = 0; i < img.pixels.size(); ++i) EXPECT_FLOAT_EQ(back.pixels[i], img.pixels[i]) << i;
}

TEST(ImageFile, PngIsSrgbEncodedAndClamped) {
    auto path = std::filesystem::temp_directory_path() / "idk_image_test.png";
    ImageRgba32f img = gradient();
    writeImage(path, img);
    ImageRgba32f back = readImage(path);
    for (size_t i = 0; i < img.pixels.size(); ++i) {
        float expected = std::min(img.pixels[i], 1.0f);
        EXPECT_NEAR(back.pixels[i], expected, 0.01f) << i;  // 8-bit sRGB quantisation
    }
}

TEST(ImageFile, SrgbTransferFunctionsInvertEachOther) {
    for (float v = 0.0f; v <= 1.0f; v += 0.01f) EXPECT_NEAR(srgbToLinear(linearToSrgb(v)), v, 1e-5f);
    EXPECT_FLOAT_EQ(linearToSrgb(0.0f), 0.0f);
    EXPECT_FLOAT_EQ(linearToSrgb(1.0f), 1.0f);
}

TEST(ImageFile, ErrorsNameThePath) {
    try {
        writeImage("/tmp/x.bmpx", gradient());
        FAIL();
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("/tmp/x.bmpx"), std::string::npos);
    }
    try {
        readImage("/nonexistent/dir/img.png");
        FAIL();
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("/nonexistent/dir/img.png"), std::string::npos);
    }
}

}  // namespace
}  // namespace idk::core
