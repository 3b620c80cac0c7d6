// fuzz_image.cpp: libFuzzer harness for the texture decode path (scene::decodeImage on embedded bytes: format
// sniffing, the JPEG ICC-profile stripper, the PNG chunk walk, OpenImageIO's readers, RGBA8 conversion and the mip
// chain). Contract (texture_decode.hpp): never throws; either a texture within kMaxTextureSize with a complete,
// tightly packed mip chain, or the 4x4 placeholder with a warning that names the image.
#include <string>

#include "fuzz_support.hpp"
#include "scene/texture_decode.hpp"

namespace {

void checkTexture(const idk::scene::DecodedTexture& t) {
    using idk::fuzz::violation;
    if (t.placeholder != !t.warning.empty()) violation("image", "placeholder and warning disagree");
    if (t.placeholder && t.warning.find("fuzz input") == std::string::npos)
        violation("image", "warning does not name the image: " + t.warning);
    if (t.width == 0 || t.height == 0 || t.width > idk::scene::kMaxTextureSize ||
        t.height > idk::scene::kMaxTextureSize)
        violation("image", "decoded size " + std::to_string(t.width) + "x" + std::to_string(t.height));
    size_t offset = 0;
    uint32_t w = t.width, h = t.height;
    for (const auto& mip : t.mips) {
        if (mip.width != w || mip.height != h || mip.offset != offset || mip.size != size_t(w) * h * 4)
            violation("image", "mip chain layout");
        offset += mip.size;
        w = std::max(1u, w / 2);
        h = std::max(1u, h / 2);
    }
    if (t.mips.empty() || t.mips.back().width != 1 || t.mips.back().height != 1 || t.texels.size() != offset)
        violation("image", "mip chain does not end at 1x1 or texel bytes differ from the chain");
}

}  // namespace

IDK_FUZZ_TARGET(image) {
    idk::scene::Image image;
    image.name = "fuzz input";
    image.encoded.assign(data, data + size);
    const bool srgb = size > 0 && (data[size - 1] & 1) != 0;  // the last byte picks the colour space
    try {
        checkTexture(idk::scene::decodeImage(image, srgb));
    } catch (const idk::fuzz::ContractViolation&) {
        throw;
    } catch (const std::exception& e) {
        idk::fuzz::violation("image", std::string("decodeImage threw: ") + e.what());
    }
    return 0;
}
