// jpeg_markers.cpp: walks the JPEG marker segments up to the start of scan and drops ICC APP2 segments.
// Layout (ITU T.81 B.1): SOI (FF D8), then segments FF xx [len_hi len_lo payload(len - 2)]; markers 01 and
// D0..D7 stand alone; SOS (FF DA) is followed by entropy-coded data, so the walk stops there.
#include "scene/jpeg_markers.hpp"

#include <cstring>

namespace idk::scene {

std::vector<uint8_t> withoutJpegIccProfiles(const std::vector<uint8_t>& jpeg, size_t& removed) {
    removed = 0;
    if (jpeg.size() < 4 || jpeg[0] != 0xFF || jpeg[1] != 0xD8) return jpeg;
    static constexpr char kIccTag[] = "ICC_PROFILE";  // 11 characters and the terminating zero
    std::vector<uint8_t> out(jpeg.begin(), jpeg.begin() + 2);
    out.reserve(jpeg.size());
    size_t pos = 2;
    while (pos + 4 <= jpeg.size() && jpeg[pos] == 0xFF) {
        const uint8_t marker = jpeg[pos + 1];
        if (marker == 0xFF) {  // fill byte before a marker
            out.push_back(0xFF);
            ++pos;
            continue;
        }
        if (marker == 0xDA || marker == 0xD9) break;  // start of scan / end of image: copy the rest
        if (marker == 0x01 || (marker >= 0xD0 && marker <= 0xD7)) {
            out.insert(out.end(), jpeg.begin() + pos, jpeg.begin() + pos + 2);
            pos += 2;
            continue;
        }
        const size_t length = size_t(jpeg[pos + 2]) << 8 | jpeg[pos + 3];
        if (length < 2 || pos + 2 + length > jpeg.size()) break;  // malformed: leave it to the decoder
        const uint8_t* payload = jpeg.data() + pos + 4;
        const bool icc = marker == 0xE2 && length - 2 >= sizeof(kIccTag) &&
                         std::memcmp(payload, kIccTag, sizeof(kIccTag)) == 0;
        if (icc) {
            ++removed;
        } else {
            out.insert(out.end(), jpeg.begin() + pos, jpeg.begin() + pos + 2 + length);
        }
        pos += 2 + length;
    }
    out.insert(out.end(), jpeg.begin() + pos, jpeg.end());
    return out;
}

std::optional<DeclaredSize> jpegDeclaredSize(const std::vector<uint8_t>& jpeg) {
    if (jpeg.size() < 4 || jpeg[0] != 0xFF || jpeg[1] != 0xD8) return std::nullopt;
    size_t pos = 2;
    while (pos + 4 <= jpeg.size() && jpeg[pos] == 0xFF) {
        const uint8_t marker = jpeg[pos + 1];
        if (marker == 0xFF) {
            ++pos;
            continue;
        }
        if (marker == 0xDA || marker == 0xD9) return std::nullopt;
        if (marker == 0x01 || (marker >= 0xD0 && marker <= 0xD7)) {
            pos += 2;
            continue;
        }
        const size_t length = size_t(jpeg[pos + 2]) << 8 | jpeg[pos + 3];
        if (length < 2 || pos + 2 + length > jpeg.size()) return std::nullopt;
        // SOFn: C0..CF except C4 (DHT), C8 (JPG extension) and CC (DAC). Payload: precision, height, width.
        const bool frame = marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
        if (frame && length >= 7) {
            const uint8_t* p = jpeg.data() + pos + 4;
            return DeclaredSize{uint32_t(p[3]) << 8 | p[4], uint32_t(p[1]) << 8 | p[2]};
        }
        pos += 2 + length;
    }
    return std::nullopt;
}

}  // namespace idk::scene
