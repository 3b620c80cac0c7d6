// image_bomb_test.cpp: decompression bombs (a few hundred bytes declaring 65535 x 65535 texels: PNG, baseline and
// progressive JPEG) are refused from the declared size before anything is decoded. The proof is the decoding
// process's peak resident set (getrusage ru_maxrss in a forked child): it stays flat for a bomb, while the same
// measurement sees a real 2048 x 2048 decode grow by more than its 16 MiB of texels (the control). Also the
// memory-budget and device-dimension limits of ImageLimits, named in the warning.
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <OpenImageIO/imageio.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "scene/texture_decode.hpp"

namespace idk::scene {
namespace {

namespace fs = std::filesystem;

std::vector<uint8_t> encode(const std::string& extension, uint32_t w, uint32_t h, bool progressive = false) {
    const fs::path path = fs::temp_directory_path() / ("idk_bomb_" + std::to_string(::getpid()) + extension);
    std::vector<uint8_t> pixels(size_t(w) * h * 3, 128);
    auto out = OIIO::ImageOutput::create(path.string());
    OIIO::ImageSpec spec(int(w), int(h), 3, OIIO::TypeDesc::UINT8);
    if (progressive) spec.attribute("jpeg:progressive", 1);
    EXPECT_TRUE(out->open(path.string(), spec) && out->write_image(OIIO::TypeDesc::UINT8, pixels.data()));
    out->close();
    std::ifstream in(path, std::ios::binary);
    std::vector<uint8_t> bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    fs::remove(path);
    return bytes;
}

uint32_t crc32(const uint8_t* data, size_t n) {
    uint32_t c = 0xFFFFFFFFu;
    for (size_t i = 0; i < n; ++i) {
        c ^= data[i];
        for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
    }
    return c ^ 0xFFFFFFFFu;
}

// A valid PNG whose IHDR declares w x h (CRC fixed up), with the tiny IDAT of a 1x1 image.
std::vector<uint8_t> pngDeclaring(uint32_t w, uint32_t h) {
    std::vector<uint8_t> png = encode(".png", 1, 1);
    auto put = [&](size_t at, uint32_t v) {
        for (int i = 0; i < 4; ++i) png[at + size_t(i)] = uint8_t(v >> (24 - 8 * i));
    };
    put(16, w);
    put(20, h);
    put(29, crc32(png.data() + 12, 17));
    return png;
}

// A JPEG whose frame header (SOFn) declares w x h.
std::vector<uint8_t> jpegDeclaring(uint32_t w, uint32_t h, bool progressive) {
    std::vector<uint8_t> jpeg = encode(".jpg", 16, 16, progressive);
    const uint8_t sof = progressive ? 0xC2 : 0xC0;
    for (size_t i = 2; i + 9 < jpeg.size(); ++i)
        if (jpeg[i] == 0xFF && jpeg[i + 1] == sof) {
            jpeg[i + 5] = uint8_t(h >> 8), jpeg[i + 6] = uint8_t(h);
            jpeg[i + 7] = uint8_t(w >> 8), jpeg[i + 8] = uint8_t(w);
            return jpeg;
        }
    ADD_FAILURE() << "no SOF marker " << int(sof);
    return jpeg;
}

struct ChildDecode {
    long peakGrowthKiB = -1;  // ru_maxrss after - before, measured inside the child
    bool placeholder = false;
    std::string warning;
};

// Decodes in a forked child so the peak RSS belongs to this decode alone.
ChildDecode decodeInChild(const std::vector<uint8_t>& bytes, const ImageLimits& limits = {}) {
    int fds[2];
    EXPECT_EQ(::pipe(fds), 0);
    const pid_t pid = ::fork();
    if (pid == 0) {
        ::close(fds[0]);
        rusage before{}, after{};
        ::getrusage(RUSAGE_SELF, &before);
        Image image;
        image.encoded = bytes;
        const DecodedTexture t = decodeImage(image, true, "bomb", limits);
        ::getrusage(RUSAGE_SELF, &after);
        const std::string report = std::to_string(after.ru_maxrss - before.ru_maxrss) + " " +
                                   std::to_string(int(t.placeholder)) + " " + t.warning;
        (void)!::write(fds[1], report.data(), report.size());
        ::_exit(0);
    }
    ::close(fds[1]);
    std::string report;
    char buffer[512];
    for (ssize_t n; (n = ::read(fds[0], buffer, sizeof(buffer))) > 0;) report.append(buffer, size_t(n));
    ::close(fds[0]);
    int status = 0;
    ::waitpid(pid, &status, 0);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "child status " << status;
    ChildDecode r;
    const size_t a = report.find(' '), b = report.find(' ', a + 1);
    if (a == std::string::npos || b == std::string::npos) return r;
    r.peakGrowthKiB = std::stol(report.substr(0, a));
    r.placeholder = report.substr(a + 1, b - a - 1) == "1";
    r.warning = report.substr(b + 1);
    return r;
}

constexpr long kBombBudgetKiB = 8 * 1024;  // a refused bomb may not grow the peak RSS by 8 MiB

TEST(ImageBomb, TheMeasurementSeesARealDecode) {
    const ChildDecode control = decodeInChild(encode(".png", 2048, 2048));
    EXPECT_FALSE(control.placeholder) << control.warning;
    EXPECT_GT(control.peakGrowthKiB, 16 * 1024) << "2048 x 2048 RGBA8 is 16 MiB before mips";
    std::printf("control 2048x2048 PNG decode: peak RSS +%ld KiB\n", control.peakGrowthKiB);
}

TEST(ImageBomb, PngAndJpegBombsAreRefusedBeforeAllocation) {
    struct Case {
        const char* name;
        std::vector<uint8_t> bytes;
    };
    const Case cases[] = {{"PNG", pngDeclaring(65535, 65535)},
                          {"baseline JPEG", jpegDeclaring(65535, 65535, false)},
                          {"progressive JPEG", jpegDeclaring(65535, 65535, true)}};
    for (const Case& c : cases) {
        EXPECT_LT(c.bytes.size(), 1024u) << c.name;
        const ChildDecode r = decodeInChild(c.bytes);
        EXPECT_TRUE(r.placeholder) << c.name;
        EXPECT_NE(r.warning.find("65535x65535 exceeds the 16384 texel limit (refused before decoding)"),
                  std::string::npos)
            << c.name << ": " << r.warning;
        EXPECT_GE(r.peakGrowthKiB, 0) << c.name;
        EXPECT_LT(r.peakGrowthKiB, kBombBudgetKiB) << c.name;
        std::printf("%s bomb (%zu bytes declaring 65535x65535): peak RSS +%ld KiB\n", c.name, c.bytes.size(),
                    r.peakGrowthKiB);
    }
}

TEST(ImageBomb, BudgetAndDeviceLimitsAreNamed) {
    ImageLimits budget;
    budget.maxDecodedBytes = 1 << 20;  // 1 MiB: a 1024 x 1024 image needs 5.3 MiB with mips
    const ChildDecode overBudget = decodeInChild(pngDeclaring(1024, 1024), budget);
    EXPECT_TRUE(overBudget.placeholder);
    EXPECT_NE(overBudget.warning.find("decodes to 5 MiB, more than the 1 MiB memory budget (--max-memory"),
              std::string::npos)
        << overBudget.warning;
    EXPECT_LT(overBudget.peakGrowthKiB, kBombBudgetKiB);

    ImageLimits device;
    device.maxDimension = 512;
    device.dimensionLimit = "texel device limit (maxImageDimension2D)";
    Image image;
    image.encoded = jpegDeclaring(1024, 16, false);
    const DecodedTexture t = decodeImage(image, false, "wide", device);
    EXPECT_TRUE(t.placeholder);
    EXPECT_NE(t.warning.find("wide: size 1024x16 exceeds the 512 texel device limit (maxImageDimension2D)"),
              std::string::npos)
        << t.warning;
    // Within every limit the same kind of image decodes.
    image.encoded = encode(".jpg", 64, 32);
    EXPECT_FALSE(decodeImage(image, false, "small", device).placeholder);
    EXPECT_EQ(decodedTextureBytes(4, 2), uint64_t(4 * 2 * 4 + 2 * 1 * 4 + 1 * 1 * 4));
}

}  // namespace
}  // namespace idk::scene
