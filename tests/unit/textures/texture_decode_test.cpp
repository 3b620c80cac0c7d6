// texture_decode_test.cpp: the CPU half of texture streaming (scene/texture_decode): OpenImageIO decoding of
// embedded and file images against OIIO's own decode of the same bytes, channel/bit-depth expansion, the mip
// chain against a brute-force area-overlap oracle (exact bytes), sRGB-correct filtering, hostile images
// (placeholder + one warning naming the image) and colour-space derivation from materials.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <unistd.h>

#include "scene/gltf_loader.hpp"
#include "scene/texture_decode.hpp"

namespace idk::scene {
namespace {

namespace fs = std::filesystem;

fs::path sharedScene(const std::string& relative) { return fs::path(IDK_SHARED_DIR) / "scenes" / relative; }

class TempDir {
public:
    TempDir() {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        path_ = fs::temp_directory_path() / ("idk_textures_" + std::to_string(::getpid()) + "_" + info->name());
        fs::remove_all(path_);
        fs::create_directories(path_);
    }
    ~TempDir() {
        std::error_code ec;
        fs::remove_all(path_, ec);
    }
    fs::path operator/(const std::string& name) const { return path_ / name; }

private:
    fs::path path_;
};

std::vector<uint8_t> readBytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}
void writeBytes(const fs::path& path, const std::vector<uint8_t>& bytes) {
    std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

// Writes an image file with OpenImageIO (format from the extension).
void writeImage(const fs::path& path, int w, int h, int nch, OIIO::TypeDesc type, const void* pixels) {
    auto out = OIIO::ImageOutput::create(path.string());
    ASSERT_TRUE(out) << OIIO::geterror();
    OIIO::ImageSpec spec(w, h, nch, type);
    spec.attribute("oiio:UnassociatedAlpha", 1);  // the pixels are straight alpha: write them unchanged
    ASSERT_TRUE(out->open(path.string(), spec)) << out->geterror();
    ASSERT_TRUE(out->write_image(type, pixels)) << out->geterror();
    out->close();
}

// OIIO's own decode of a file as RGBA8 (straight alpha), the oracle for level 0.
std::vector<uint8_t> oiioRgba8(const fs::path& path, uint32_t& w, uint32_t& h) {
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    auto in = OIIO::ImageInput::open(path.string(), &config);
    EXPECT_TRUE(in) << OIIO::geterror();
    if (!in) return {};
    const OIIO::ImageSpec& spec = in->spec();
    w = uint32_t(spec.width);
    h = uint32_t(spec.height);
    std::vector<uint8_t> raw(size_t(w) * h * size_t(spec.nchannels));
    EXPECT_TRUE(in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, raw.data()));
    std::vector<uint8_t> rgba(size_t(w) * h * 4, 255);
    for (size_t p = 0; p < size_t(w) * h; ++p)
        for (int c = 0; c < std::min(spec.nchannels, 4); ++c) rgba[p * 4 + size_t(c)] = raw[p * size_t(spec.nchannels) + size_t(c)];
    return rgba;
}

std::vector<uint8_t> level(const DecodedTexture& t, size_t i) {
    const MipLevel& m = t.mips.at(i);
    return {t.texels.begin() + std::ptrdiff_t(m.offset), t.texels.begin() + std::ptrdiff_t(m.offset + m.size)};
}

// ---- the brute-force oracle: every source texel's area overlap with every destination texel ----
double oracleSrgbToLinear(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

std::vector<uint8_t> oracleDownsample(const std::vector<uint8_t>& src, uint32_t sw, uint32_t sh, uint32_t dw,
                                      uint32_t dh, bool srgb) {
    // In units of 1/dw source texels, source texel s spans [s dw, (s+1) dw] and destination texel d spans
    // [d sw, (d+1) sw]; weights are the integer overlap lengths, over sw * sh in total.
    auto overlap = [](uint64_t s, uint64_t d, uint64_t srcN, uint64_t dstN) -> uint64_t {
        const uint64_t lo = std::max(s * dstN, d * srcN), hi = std::min((s + 1) * dstN, (d + 1) * srcN);
        return hi > lo ? hi - lo : 0;
    };
    std::vector<uint8_t> dst(size_t(dw) * dh * 4);
    const uint64_t den = uint64_t(sw) * sh;
    for (uint32_t dy = 0; dy < dh; ++dy)
        for (uint32_t dx = 0; dx < dw; ++dx)
            for (int c = 0; c < 4; ++c) {
                uint64_t num = 0;
                double lin = 0.0;
                for (uint32_t sy = 0; sy < sh; ++sy)
                    for (uint32_t sx = 0; sx < sw; ++sx) {
                        const uint64_t wgt = overlap(sx, dx, sw, dw) * overlap(sy, dy, sh, dh);
                        const uint8_t v = src[(size_t(sy) * sw + sx) * 4 + size_t(c)];
                        num += wgt * v;
                        lin += double(wgt) * oracleSrgbToLinear(v / 255.0);
                    }
                uint8_t out;
                if (srgb && c < 3) {
                    const double mean = lin / double(den);
                    int code = 0;  // round(255 * linearToSrgb(mean)), ties up, via the inverse's thresholds
                    while (code < 255 && mean >= oracleSrgbToLinear((code + 0.5) / 255.0)) ++code;
                    out = uint8_t(code);
                } else {
                    out = uint8_t((2 * num + den) / (2 * den));  // floor(mean + 1/2)
                }
                dst[(size_t(dy) * dw + dx) * 4 + size_t(c)] = out;
            }
    return dst;
}

std::vector<uint8_t> randomImage(uint32_t w, uint32_t h, uint32_t seed) {
    std::mt19937 rng(seed);
    std::vector<uint8_t> v(size_t(w) * h * 4);
    for (uint8_t& b : v) b = uint8_t(rng() & 255);
    return v;
}

TEST(TextureDecode, EmbeddedPngEqualsOiioDirectDecode) {
    const Scene scene = loadGltf(sharedScene("BoxTextured/glTF-Binary/BoxTextured.glb"));
    ASSERT_EQ(scene.images.size(), 1u);
    const Image& image = scene.images[0];
    ASSERT_FALSE(image.encoded.empty());
    const DecodedTexture t = decodeImage(image, true, imageLabel(scene, 0));
    EXPECT_FALSE(t.placeholder) << t.warning;
    EXPECT_TRUE(t.warning.empty());
    TempDir dir;
    writeBytes(dir / "box.png", image.encoded);
    uint32_t w = 0, h = 0;
    const std::vector<uint8_t> direct = oiioRgba8(dir / "box.png", w, h);
    ASSERT_EQ(t.width, w);
    ASSERT_EQ(t.height, h);
    EXPECT_TRUE(level(t, 0) == direct);
    const uint32_t expectedLevels = uint32_t(std::floor(std::log2(double(std::max(w, h))))) + 1;
    EXPECT_EQ(t.mips.size(), expectedLevels);
    EXPECT_EQ(t.mips.back().width, 1u);
    EXPECT_EQ(t.mips.back().height, 1u);
}

TEST(TextureDecode, EmbeddedJpegEqualsOiioDirectDecode) {
    const Scene scene = loadGltf(sharedScene("DamagedHelmet/glTF-Binary/DamagedHelmet.glb"));
    ASSERT_GE(scene.images.size(), 1u);
    const DecodedTexture t = decodeImage(scene.images[1], false);
    EXPECT_FALSE(t.placeholder) << t.warning;
    TempDir dir;
    writeBytes(dir / "mr.jpg", scene.images[1].encoded);
    uint32_t w = 0, h = 0;
    const std::vector<uint8_t> direct = oiioRgba8(dir / "mr.jpg", w, h);
    ASSERT_EQ(t.width, w);
    EXPECT_TRUE(level(t, 0) == direct);
}

TEST(TextureDecode, FileImageEqualsEmbeddedDecode) {
    const Scene scene = loadGltf(sharedScene("BoxTextured/glTF-Binary/BoxTextured.glb"));
    TempDir dir;
    writeBytes(dir / "box.png", scene.images[0].encoded);
    Image file;
    file.path = dir / "box.png";
    const DecodedTexture a = decodeImage(file, true), b = decodeImage(scene.images[0], true);
    EXPECT_FALSE(a.placeholder) << a.warning;
    EXPECT_TRUE(a.texels == b.texels);
}

TEST(TextureDecode, ExpandsChannelsAndBitDepths) {
    TempDir dir;
    const uint8_t grey[4] = {0, 100, 200, 255};
    const uint8_t greyAlpha[8] = {10, 0, 20, 64, 30, 128, 40, 255};
    const uint8_t rgb[12] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12};
    const uint16_t deep[4] = {0, 257 * 100 + 128, 65535, 32767};  // 1-channel 16-bit
    const float linear[4] = {0.0f, 0.5f, 1.0f, 2.0f};               // 1-channel float EXR
    writeImage(dir / "g.png", 2, 2, 1, OIIO::TypeDesc::UINT8, grey);
    writeImage(dir / "ga.png", 2, 2, 2, OIIO::TypeDesc::UINT8, greyAlpha);
    writeImage(dir / "rgb.png", 2, 2, 3, OIIO::TypeDesc::UINT8, rgb);
    writeImage(dir / "d.png", 2, 2, 1, OIIO::TypeDesc::UINT16, deep);
    writeImage(dir / "f.exr", 2, 2, 1, OIIO::TypeDesc::FLOAT, linear);
    auto decode = [&](const char* name, bool srgb) {
        Image image;
        image.path = dir / name;
        DecodedTexture t = decodeImage(image, srgb);
        EXPECT_FALSE(t.placeholder) << t.warning;
        return level(t, 0);
    };
    EXPECT_EQ(decode("g.png", true), (std::vector<uint8_t>{0, 0, 0, 255, 100, 100, 100, 255, 200, 200, 200, 255,
                                                           255, 255, 255, 255}));
    EXPECT_EQ(decode("ga.png", true), (std::vector<uint8_t>{10, 10, 10, 0, 20, 20, 20, 64, 30, 30, 30, 128, 40, 40,
                                                            40, 255}));
    EXPECT_EQ(decode("rgb.png", true),
              (std::vector<uint8_t>{1, 2, 3, 255, 4, 5, 6, 255, 7, 8, 9, 255, 10, 11, 12, 255}));
    // 16 bit: round(x * 255 / 65535) (32767 -> 127.498 -> 127).
    EXPECT_EQ(decode("d.png", false), (std::vector<uint8_t>{0, 0, 0, 255, 100, 100, 100, 255, 255, 255, 255, 255,
                                                            127, 127, 127, 255}));
    // Float inputs are linear: clamped for data, sRGB-encoded for colour (0.5 linear -> 188).
    EXPECT_EQ(decode("f.exr", false), (std::vector<uint8_t>{0, 0, 0, 255, 128, 128, 128, 255, 255, 255, 255, 255,
                                                            255, 255, 255, 255}));
    EXPECT_EQ(decode("f.exr", true), (std::vector<uint8_t>{0, 0, 0, 255, 188, 188, 188, 255, 255, 255, 255, 255,
                                                           255, 255, 255, 255}));
}

TEST(TextureDecode, StraightAlphaIsKept) {
    TempDir dir;
    const uint8_t rgba[4] = {200, 100, 50, 10};  // premultiplying would darken the colour
    writeImage(dir / "a.png", 1, 1, 4, OIIO::TypeDesc::UINT8, rgba);
    Image image;
    image.path = dir / "a.png";
    EXPECT_EQ(level(decodeImage(image, true), 0), (std::vector<uint8_t>{200, 100, 50, 10}));
}

TEST(TextureMips, MatchBruteForceOracleOnOddAndEvenSizes) {
    const std::pair<uint32_t, uint32_t> sizes[] = {{8, 8}, {7, 5}, {13, 1}, {1, 9}, {6, 11}, {17, 16},
                                                   {3, 3}, {2, 2}, {64, 33}, {1, 1}, {5, 2}, {31, 9}};
    uint32_t seed = 1;
    for (auto [w, h] : sizes)
        for (bool srgb : {false, true}) {
            SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h) + (srgb ? " sRGB" : " linear"));
            std::vector<uint8_t> texels = randomImage(w, h, seed++);
            const DecodedTexture t = buildMipChain(texels, w, h, srgb);
            std::vector<uint8_t> expected = texels;
            uint32_t ew = w, eh = h;
            ASSERT_EQ(level(t, 0), expected);
            for (size_t i = 1; i < t.mips.size(); ++i) {
                const uint32_t dw = std::max(1u, ew / 2), dh = std::max(1u, eh / 2);
                ASSERT_EQ(t.mips[i].width, dw);
                ASSERT_EQ(t.mips[i].height, dh);
                expected = oracleDownsample(expected, ew, eh, dw, dh, srgb);
                ASSERT_EQ(level(t, i), expected) << "level " << i;
                ew = dw;
                eh = dh;
            }
            EXPECT_EQ(ew, 1u);
            EXPECT_EQ(eh, 1u);
        }
}

TEST(TextureMips, SrgbAveragesInLinearLight) {
    // Black and white: the mean is 0.5 linear, which is sRGB 188 (not the encoded mean 128); alpha is linear.
    const std::vector<uint8_t> bw = {0, 0, 0, 0, 255, 255, 255, 255, 255, 255, 255, 255, 0, 0, 0, 0};
    EXPECT_EQ(level(buildMipChain(bw, 2, 2, true), 1), (std::vector<uint8_t>{188, 188, 188, 128}));
    EXPECT_EQ(level(buildMipChain(bw, 2, 2, false), 1), (std::vector<uint8_t>{128, 128, 128, 128}));
    // Odd width 3 -> 1: equal thirds.
    const std::vector<uint8_t> row = {0, 0, 0, 0, 30, 30, 30, 30, 60, 60, 60, 60};
    EXPECT_EQ(level(buildMipChain(row, 3, 1, false), 1), (std::vector<uint8_t>{30, 30, 30, 30}));
    EXPECT_EQ(encodeSrgb8(0.5), 188);
    EXPECT_EQ(encodeSrgb8(0.0), 0);
    EXPECT_EQ(encodeSrgb8(1.0), 255);
    for (int k = 0; k < 256; ++k) EXPECT_EQ(encodeSrgb8(srgbToLinearD(k / 255.0)), k);
}

TEST(TextureMips, RejectsWrongSizes) {
    EXPECT_THROW(buildMipChain(std::vector<uint8_t>(12), 2, 2, false), std::invalid_argument);
    EXPECT_THROW(buildMipChain({}, 0, 0, false), std::invalid_argument);
}

void expectPlaceholder(const DecodedTexture& t, const std::string& mustName, const std::string& cause) {
    EXPECT_TRUE(t.placeholder);
    EXPECT_EQ(t.width, kPlaceholderSize);
    EXPECT_EQ(t.height, kPlaceholderSize);
    EXPECT_EQ(t.mips.size(), 3u);
    const std::vector<uint8_t> l0 = level(t, 0);
    EXPECT_EQ(std::vector<uint8_t>(l0.begin(), l0.begin() + 8), (std::vector<uint8_t>{255, 0, 255, 255, 0, 0, 0, 255}));
    EXPECT_NE(t.warning.find(mustName), std::string::npos) << t.warning;
    EXPECT_NE(t.warning.find(cause), std::string::npos) << t.warning;
    EXPECT_EQ(t.warning.find('\n'), std::string::npos) << "one line: " << t.warning;
}

TEST(TextureHostile, MissingFileGivesPlaceholderAndOneWarning) {
    TempDir dir;
    Image image;
    image.path = dir / "nowhere.png";
    expectPlaceholder(decodeImage(image, true), (dir / "nowhere.png").string(), "not found");
}

TEST(TextureHostile, GarbageBytesGivePlaceholder) {
    Image image;
    image.name = "noise";
    image.encoded = randomImage(16, 16, 7);
    image.mimeType = "image/png";
    Scene scene;
    scene.sourcePath = "/x/asset.glb";
    scene.images.push_back(image);
    const DecodedTexture t = decodeImage(image, false, imageLabel(scene, 0));
    expectPlaceholder(t, "embedded image 0 ('noise') of asset.glb", "cannot decode");
    // A PNG signature followed by garbage; a few bytes; no bytes at all.
    const uint8_t signature[8] = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
    std::copy(signature, signature + 8, image.encoded.begin());
    expectPlaceholder(decodeImage(image, false, "img"), "img", "PNG");
    image.encoded.resize(5);
    expectPlaceholder(decodeImage(image, false, "img"), "img", "cannot decode 5 bytes");
    TempDir dir;
    writeBytes(dir / "empty.png", {});
    Image empty;
    empty.path = dir / "empty.png";
    expectPlaceholder(decodeImage(empty, false), "empty.png", "0 bytes");
}

TEST(TextureHostile, TruncatedPngGivesPlaceholder) {
    const Scene scene = loadGltf(sharedScene("BoxTextured/glTF-Binary/BoxTextured.glb"));
    Image image = scene.images[0];
    for (size_t keep : {image.encoded.size() / 2, size_t(60), size_t(8)}) {
        Image cut = image;
        cut.encoded.resize(keep);
        expectPlaceholder(decodeImage(cut, true, imageLabel(scene, 0)), "embedded image 0 of BoxTextured.glb",
                          "truncated PNG");
    }
}

TEST(TextureHostile, CorruptedPngDataGivesPlaceholder) {
    const Scene scene = loadGltf(sharedScene("BoxTextured/glTF-Binary/BoxTextured.glb"));
    Image image = scene.images[0];
    const std::string bytes(image.encoded.begin(), image.encoded.end());
    const size_t idat = bytes.find("IDAT");
    ASSERT_NE(idat, std::string::npos);
    for (size_t i = idat + 8; i < idat + 200 && i < image.encoded.size(); ++i) image.encoded[i] ^= 0x5A;
    expectPlaceholder(decodeImage(image, true, "corrupt"), "corrupt", "cannot decode");
}

uint32_t crc32(const uint8_t* data, size_t n) {
    uint32_t c = 0xFFFFFFFFu;
    for (size_t i = 0; i < n; ++i) {
        c ^= data[i];
        for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
    }
    return c ^ 0xFFFFFFFFu;
}

TEST(TextureHostile, AbsurdSizeIsRejectedBeforeDecoding) {
    TempDir dir;
    const uint8_t pixel[4] = {1, 2, 3, 4};
    writeImage(dir / "p.png", 1, 1, 4, OIIO::TypeDesc::UINT8, pixel);
    std::vector<uint8_t> png = readBytes(dir / "p.png");
    // IHDR: bytes 8..11 length, 12..15 "IHDR", 16..19 width, 20..23 height, CRC over type+data at 29..32.
    ASSERT_GE(png.size(), 33u);
    const uint32_t width = 20000;
    for (int i = 0; i < 4; ++i) png[16 + size_t(i)] = uint8_t(width >> (24 - 8 * i));
    const uint32_t crc = crc32(png.data() + 12, 17);
    for (int i = 0; i < 4; ++i) png[29 + size_t(i)] = uint8_t(crc >> (24 - 8 * i));
    Image image;
    image.encoded = png;
    expectPlaceholder(decodeImage(image, true, "huge"), "huge", "exceeds the 16384");
}

TEST(TextureHostile, LoaderStatusGivesPlaceholderWithoutASecondWarning) {
    Image image;
    image.status = ImageStatus::Missing;
    image.path = "/nonexistent/a.png";
    DecodedTexture t = decodeImage(image, true, "image 0 file /nonexistent/a.png");
    expectPlaceholder(t, "/nonexistent/a.png", "not found");
    EXPECT_TRUE(t.reportedByLoader);
    image.status = ImageStatus::UnknownFormat;
    t = decodeImage(image, false, "x");
    expectPlaceholder(t, "x", "not a known image format");
    EXPECT_TRUE(t.reportedByLoader);
    // Through the loader: a glTF whose image file is missing warns once, and the decoder defers to that warning.
    TempDir dir;
    std::ofstream(dir / "m.gltf") << R"({"asset":{"version":"2.0"},"images":[{"uri":"gone.png"}],
        "textures":[{"source":0}],"materials":[{"pbrMetallicRoughness":{"baseColorTexture":{"index":0}}}]})";
    const Scene scene = loadGltf(dir / "m.gltf");
    size_t mentions = 0;
    for (const std::string& w : scene.warnings) mentions += w.find("gone.png") != std::string::npos;
    EXPECT_EQ(mentions, 1u);
    t = decodeImage(scene.images[0], true, imageLabel(scene, 0));
    expectPlaceholder(t, "gone.png", "not found");
    EXPECT_TRUE(t.reportedByLoader);
}

TEST(TextureHostile, NoSourceGivesPlaceholder) {
    expectPlaceholder(decodeImage(Image{}, true, "image 3"), "image 3", "no image data");
}

TEST(TextureColorSpaces, DamagedHelmetBaseAndEmissiveAreSrgb) {
    const Scene scene = loadGltf(sharedScene("DamagedHelmet/glTF-Binary/DamagedHelmet.glb"));
    ASSERT_EQ(scene.materials.size(), 1u);
    const Material& m = scene.materials[0];
    const std::vector<TextureColorSpace> spaces = textureColorSpaces(scene);
    ASSERT_EQ(spaces.size(), scene.textures.size());
    ASSERT_TRUE(m.baseColorTexture && m.emissiveTexture && m.metallicRoughnessTexture && m.normalTexture &&
                m.occlusionTexture);
    EXPECT_EQ(spaces[m.baseColorTexture->texture], TextureColorSpace::Srgb);
    EXPECT_EQ(spaces[m.emissiveTexture->texture], TextureColorSpace::Srgb);
    EXPECT_EQ(spaces[m.metallicRoughnessTexture->texture], TextureColorSpace::Linear);
    EXPECT_EQ(spaces[m.normalTexture->texture], TextureColorSpace::Linear);
    EXPECT_EQ(spaces[m.occlusionTexture->texture], TextureColorSpace::Linear);
    size_t srgb = 0;
    for (TextureColorSpace s : spaces) srgb += s == TextureColorSpace::Srgb;
    EXPECT_EQ(srgb, 2u);
}

TEST(TextureColorSpaces, UnusedAndBoth) {
    Scene scene;
    scene.textures.resize(3);
    Material a, b;
    a.baseColorTexture = TextureRef{0};
    b.normalTexture = TextureRef{0};
    b.occlusionTexture = TextureRef{1};
    b.transmissionTexture = TextureRef{7};  // out of range: ignored
    scene.materials = {a, b};
    EXPECT_EQ(textureColorSpaces(scene), (std::vector<TextureColorSpace>{TextureColorSpace::Both,
                                                                        TextureColorSpace::Linear,
                                                                        TextureColorSpace::Unused}));
}

}  // namespace
}  // namespace idk::scene
