// texture_decode.hpp: CPU side of texture loading: decodes a scene image (embedded bytes or file) with
// OpenImageIO into RGBA8 and builds its full mip chain (area-weighted box filter, sRGB-correct), or substitutes
// a documented placeholder with one warning. Runs on the texture streamer's worker threads; pure and
// thread-safe. Ports the decode half of IDKEngine's AsyncTextureLoader / TextureLoading (reference 2.9).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "scene/jpeg_markers.hpp"
#include "scene/scene.hpp"

namespace idk::scene {

// Images wider or taller than this are rejected (placeholder + warning), like undecodable ones.
constexpr uint32_t kMaxTextureSize = 16384;

// What one decode may allocate, checked against the size the file declares before anything is decoded (PNG
// IHDR and JPEG frame headers are read by hand, before OpenImageIO sees the bytes; other formats from the header
// OpenImageIO reads in open()). A refused image gives the placeholder and a warning naming the limit.
struct ImageLimits {
    uint32_t maxDimension = kMaxTextureSize;       // texels per axis
    std::string dimensionLimit = "texel limit";     // names maxDimension in warnings (e.g. the device's limit)
    uint64_t maxDecodedBytes = UINT64_MAX;          // RGBA8 texels with the full mip chain
};
// Bytes of a width x height RGBA8 texture with all its mips (what decodeImage allocates for the result).
uint64_t decodedTextureBytes(uint32_t width, uint32_t height);
// The size a PNG (IHDR) or JPEG (frame header) declares, read from the first bytes without decoding; empty for
// other formats or damaged headers.
std::optional<DeclaredSize> declaredImageSize(const std::vector<uint8_t>& bytes);
// The placeholder: 4x4 RGBA8, texel (x, y) is magenta (255, 0, 255, 255) when x + y is even, else opaque black.
constexpr uint32_t kPlaceholderSize = 4;

// How a material samples a texture. Base colour and emissive are sRGB; metallic-roughness, normal, occlusion,
// transmission and thickness are linear data.
enum class TextureColorSpace : uint8_t {
    Unused,  // no material references the texture
    Srgb,
    Linear,
    Both,    // referenced as colour and as data (the streamer uploads it once, as sRGB, and warns)
};

// One entry per Scene::textures, derived from the materials' texture references.
std::vector<TextureColorSpace> textureColorSpaces(const Scene& scene);

struct MipLevel {
    uint32_t width = 0;
    uint32_t height = 0;
    size_t offset = 0;  // byte offset of the level in DecodedTexture::texels
    size_t size = 0;    // width * height * 4
};

// RGBA8 texels of every mip level, tightly packed, level 0 (full size) first, each level row-major, top row
// first. Level i+1 has max(1, floor(size / 2)) texels per axis, down to 1x1.
struct DecodedTexture {
    uint32_t width = 0;
    uint32_t height = 0;
    bool srgb = false;  // the RGB channels are sRGB-encoded (upload as VK_FORMAT_R8G8B8A8_SRGB)
    std::vector<MipLevel> mips;
    std::vector<uint8_t> texels;
    bool placeholder = false;      // the image failed: texels hold the magenta/black checker
    std::string warning;           // set exactly when placeholder: "<image label>: <cause>; ..."
    bool reportedByLoader = false;  // the image's status was not Ok: loadGltf already warned about it
    size_t byteSize() const { return texels.size(); }
};

// Names an image in warnings: its file path, or "embedded image N ('name') of <asset file name>".
std::string imageLabel(const Scene& scene, uint32_t imageIndex);

// Decodes `image` to RGBA8 with its mip chain. `srgb`: the RGB channels are colour (sRGB); then mips are
// filtered in linear light and re-encoded. Inputs: 1 channel -> grey, 2 -> grey + alpha, 3 -> alpha 255,
// more than 4 -> the first 4; 16-bit channels are rounded to 8 bits; float inputs (EXR, HDR) hold linear values
// and are sRGB-encoded when `srgb`, else clamped to [0, 1]. Alpha is straight (unassociated), as glTF defines.
// Never throws for bad input: a status other than Ok, a missing file, bytes no decoder accepts, a truncated
// file (a PNG's chunk list is walked before OpenImageIO sees it), 0 bytes, or a size above kMaxTextureSize give
// the placeholder and `warning` naming `label` and the cause. Files are read into memory like embedded bytes. The
// function does not log; the caller reports each image's warning once (unless reportedByLoader).
DecodedTexture decodeImage(const Image& image, bool srgb, std::string_view label = {},
                           const ImageLimits& limits = {});

// Builds the mip chain over level-0 RGBA8 texels (width * height * 4 bytes; throws std::invalid_argument
// otherwise). Each level is filtered from the previous 8-bit level with the exact area-weighted box: per axis,
// an even size averages texel pairs; an odd size 2n+1 -> n weighs texels 2x, 2x+1, 2x+2 by (n-x, n, x+1)/(2n+1);
// size 1 stays. Rounding rule, per channel: linear channels (alpha always; RGB unless srgb) are
// floor(weighted mean + 1/2) in exact integer arithmetic; sRGB channels decode each texel to linear (double),
// take the weighted mean m and output the number of codes k in [0, 254] with m >= srgbToLinear((k + 1/2) / 255)
// (i.e. round(255 * linearToSrgb(m)), ties up).
DecodedTexture buildMipChain(std::vector<uint8_t> level0, uint32_t width, uint32_t height, bool srgb);

// The 4x4 checker with its mips (as decodeImage returns it, without a warning).
DecodedTexture placeholderTexture(bool srgb);

// Exact sRGB transfer functions in double (IEC 61966-2-1), used by the filter and by tests.
double srgbToLinearD(double c);
uint8_t encodeSrgb8(double linear);  // the rounding rule above

}  // namespace idk::scene
