// jpeg_markers.hpp: reads the declared frame size, and removes embedded ICC colour profiles (APP2 "ICC_PROFILE" segments) from JPEG bytes before
// they reach OpenImageIO. glTF fixes the colour space of every texture slot (sRGB or linear), so the profile is
// never used; and OpenImageIO 2.4's ICC parser (decode_icc_profile, called from JpgInput::open) crashed the
// process intermittently on TransmissionTest.glb's profiles. Hostile profiles never reach it either.
#pragma once
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

namespace idk::scene {

// A copy of `jpeg` without its ICC APP2 segments; every other byte is kept in order. Input that is not a JPEG, or
// whose marker structure ends early or is malformed, is copied from that point on unchanged (the decoder then
// reports the damage). `removed` receives the number of segments dropped.
std::vector<uint8_t> withoutJpegIccProfiles(const std::vector<uint8_t>& jpeg, size_t& removed);

struct DeclaredSize {
    uint32_t width = 0;
    uint32_t height = 0;
};
// The size a JPEG's frame header (SOF0..SOF15) declares, read without decoding; empty when the markers end or
// break before one. Lets the decoder refuse a "decompression bomb" before libjpeg allocates anything (a
// progressive JPEG's coefficient buffers cover the whole declared image).
std::optional<DeclaredSize> jpegDeclaredSize(const std::vector<uint8_t>& jpeg);

}  // namespace idk::scene
