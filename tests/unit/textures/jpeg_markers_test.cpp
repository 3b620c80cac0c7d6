// ICC profiles are dropped from JPEG bytes before decoding (scene/jpeg_markers.hpp): exact byte-level checks on
// synthetic marker streams, malformed streams copied unchanged, and TransmissionTest.glb (whose JPEGs carry ICC
// profiles that crashed OpenImageIO's parser intermittently) decodes every image without a placeholder.
#include <gtest/gtest.h>

#include <filesystem>

#include "scene/gltf_loader.hpp"
#include "scene/jpeg_markers.hpp"
#include "scene/texture_decode.hpp"

namespace idk::scene {
namespace {

using Bytes = std::vector<uint8_t>;

// Byte by byte (GCC 12 reports false -Warray-bounds for vector::insert into small vectors).
void append(Bytes& out, const Bytes& more) {
    for (uint8_t b : more) out.push_back(b);
}

Bytes segment(uint8_t marker, const Bytes& payload) {
    const size_t length = payload.size() + 2;
    Bytes s{0xFF, marker, uint8_t(length >> 8), uint8_t(length & 0xFF)};
    append(s, payload);
    return s;
}

Bytes iccPayload() {
    Bytes p{'I', 'C', 'C', '_', 'P', 'R', 'O', 'F', 'I', 'L', 'E', 0, 1, 1};
    append(p, Bytes(40, 0xAB));
    return p;
}

Bytes concat(std::initializer_list<Bytes> parts) {
    Bytes out;
    for (const Bytes& p : parts) append(out, p);
    return out;
}

TEST(JpegMarkers, IccSegmentsAreDroppedAndEverythingElseKept) {
    const Bytes soi{0xFF, 0xD8};
    const Bytes app0 = segment(0xE0, {'J', 'F', 'I', 'F', 0, 1, 2});
    const Bytes otherApp2 = segment(0xE2, {'M', 'P', 'F', 0, 9, 9});  // APP2 but not a profile: kept
    const Bytes dqt = segment(0xDB, Bytes(65, 7));
    const Bytes scan = concat({segment(0xDA, {1, 2, 3}), Bytes{0x12, 0xFF, 0x00, 0x34, 0xFF, 0xD9}});
    const Bytes input = concat({soi, app0, segment(0xE2, iccPayload()), otherApp2, segment(0xE2, iccPayload()), dqt, scan});
    size_t removed = 99;
    const Bytes output = withoutJpegIccProfiles(input, removed);
    EXPECT_EQ(removed, 2u);
    EXPECT_EQ(output, concat({soi, app0, otherApp2, dqt, scan}));
}

TEST(JpegMarkers, NonJpegAndMalformedStreamsAreCopiedUnchanged) {
    size_t removed = 99;
    const Bytes png{0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
    EXPECT_EQ(withoutJpegIccProfiles(png, removed), png);
    EXPECT_EQ(removed, 0u);
    // A segment length running past the end: the walk stops and copies the rest as it is.
    Bytes truncated = concat({Bytes{0xFF, 0xD8}, segment(0xE2, iccPayload())});
    truncated.resize(truncated.size() - 10);
    EXPECT_EQ(withoutJpegIccProfiles(truncated, removed), truncated);
    EXPECT_EQ(removed, 0u);
    // A length below 2 is malformed too.
    const Bytes badLength{0xFF, 0xD8, 0xFF, 0xE2, 0x00, 0x01, 0x00, 0x00};
    EXPECT_EQ(withoutJpegIccProfiles(badLength, removed), badLength);
    // Just SOI.
    const Bytes soiOnly{0xFF, 0xD8};
    EXPECT_EQ(withoutJpegIccProfiles(soiOnly, removed), soiOnly);
}

TEST(JpegMarkers, TransmissionTestImagesWithProfilesDecode) {
    const std::filesystem::path file =
        std::filesystem::path(IDK_SHARED_DIR) / "scenes/TransmissionTest/glTF-Binary/TransmissionTest.glb";
    if (!std::filesystem::exists(file)) GTEST_SKIP() << file << " is not present";
    const Scene scene = loadGltf(file);
    size_t withProfiles = 0;
    for (const Image& image : scene.images) {
        size_t removed = 0;
        withoutJpegIccProfiles(image.encoded, removed);
        withProfiles += removed > 0;
        // Decode several times: the crash was intermittent.
        for (int repeat = 0; repeat < 3; ++repeat) {
            const DecodedTexture decoded = decodeImage(image, true);
            EXPECT_FALSE(decoded.placeholder) << image.name;
            EXPECT_GT(decoded.width, 1u);
        }
    }
    EXPECT_GE(withProfiles, 1u) << "the asset's JPEGs carry ICC profiles";
}

}  // namespace
}  // namespace idk::scene
