// texture_decode.cpp: OpenImageIO decoding (in-memory IOProxy for embedded bytes, the file otherwise) to RGBA8,
// the exact area-weighted mip filter (integer arithmetic for linear channels, double in linear light for sRGB
// ones) and the magenta checker placeholder. Port of the decode step of IDKEngine's AsyncTextureLoader.
#include "scene/texture_decode.hpp"
#include "scene/jpeg_markers.hpp"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <cctype>
#include <cmath>
#include <fstream>
#include <iterator>
#include <optional>
#include <memory>
#include <stdexcept>
#include <system_error>

namespace idk::scene {
namespace {

void mergeSpace(TextureColorSpace& slot, TextureColorSpace use) {
    if (slot == TextureColorSpace::Unused || slot == use) slot = use;
    else slot = TextureColorSpace::Both;
}

// The extension OpenImageIO picks its reader by, from the leading bytes (then the MIME type).
std::string formatHint(const std::vector<uint8_t>& b, const std::string& mimeType, const std::string& extension) {
    auto starts = [&](std::initializer_list<uint8_t> sig) {
        return b.size() >= sig.size() && std::equal(sig.begin(), sig.end(), b.begin());
    };
    if (starts({0x89, 'P', 'N', 'G'})) return "png";
    if (starts({0xFF, 0xD8, 0xFF})) return "jpg";
    if (starts({'G', 'I', 'F', '8'})) return "gif";
    if (starts({'B', 'M'})) return "bmp";
    if (starts({'#', '?'})) return "hdr";
    if (starts({0x76, 0x2F, 0x31, 0x01})) return "exr";
    if (starts({'D', 'D', 'S', ' '})) return "dds";
    if (starts({'I', 'I', 0x2A, 0x00}) || starts({'M', 'M', 0x00, 0x2A})) return "tif";
    if (b.size() >= 12 && starts({'R', 'I', 'F', 'F'}) && std::equal(b.begin() + 8, b.begin() + 12, "WEBP"))
        return "webp";
    if (mimeType == "image/jpeg") return "jpg";
    if (mimeType == "image/webp") return "webp";
    if (!extension.empty()) return extension;
    return "png";
}

// Walks the chunk list of data that starts with the PNG signature. A truncated PNG must not reach OpenImageIO 2.4: its libpng read callback leaks
// a string when it longjmps out at the end of the data (LeakSanitizer reports it), and prints to stderr.
std::optional<std::string> pngStructureError(const std::vector<uint8_t>& b) {
    size_t pos = 8;  // after the signature
    bool first = true;
    for (;;) {
        if (b.size() - pos < 12)
            return "truncated PNG: " + std::to_string(b.size()) + " bytes end before the IEND chunk";
        const uint32_t length = uint32_t(b[pos]) << 24 | uint32_t(b[pos + 1]) << 16 | uint32_t(b[pos + 2]) << 8 | b[pos + 3];
        const std::string type(reinterpret_cast<const char*>(b.data() + pos + 4), 4);
        if (first && type != "IHDR") return std::string("malformed PNG: the first chunk is not IHDR");
        first = false;
        if (length > 0x7FFFFFFFu || b.size() - pos - 12 < length)
            return "truncated PNG: chunk at byte " + std::to_string(pos) + " (" + std::to_string(length) +
                   " bytes) runs past the end of the " + std::to_string(b.size()) + " bytes";
        pos += 12 + size_t(length);
        if (type == "IEND") return std::nullopt;
    }
}

std::string firstLine(std::string message) {
    if (auto nl = message.find('\n'); nl != std::string::npos) message.resize(nl);
    if (message.size() > 300) message = message.substr(0, 300) + "...";
    return message.empty() ? "no further detail" : message;
}

// Why a width x height image may not be decoded under `limits`, if it may not.
std::optional<std::string> limitError(uint64_t width, uint64_t height, const ImageLimits& limits) {
    if (width > limits.maxDimension || height > limits.maxDimension)
        return "size " + std::to_string(width) + "x" + std::to_string(height) + " exceeds the " +
               std::to_string(limits.maxDimension) + " " + limits.dimensionLimit + " (refused before decoding)";
    const uint64_t bytes = decodedTextureBytes(uint32_t(width), uint32_t(height));
    if (bytes > limits.maxDecodedBytes)
        return "size " + std::to_string(width) + "x" + std::to_string(height) + " decodes to " +
               std::to_string(bytes >> 20) + " MiB, more than the " + std::to_string(limits.maxDecodedBytes >> 20) +
               " MiB memory budget (--max-memory; refused before decoding)";
    return std::nullopt;
}

DecodedTexture failed(std::string_view label, const std::string& cause, bool srgb, bool reportedByLoader = false) {
    DecodedTexture t = placeholderTexture(srgb);
    t.warning = std::string(label) + ": " + cause + "; using the magenta placeholder";
    t.reportedByLoader = reportedByLoader;
    return t;
}

// Per axis: the source texels and integer weights (over `denominator`) of one destination texel.
struct AxisTaps {
    uint32_t first = 0;
    uint32_t count = 0;
    std::array<uint32_t, 3> weight{};
};

std::vector<AxisTaps> axisTaps(uint32_t src, uint32_t dst, uint32_t& denominator) {
    std::vector<AxisTaps> taps(dst);
    if (src == 1) {
        denominator = 1;
        taps[0] = {0, 1, {1, 0, 0}};
    } else if (src % 2 == 0) {
        denominator = 2;
        for (uint32_t x = 0; x < dst; ++x) taps[x] = {2 * x, 2, {1, 1, 0}};
    } else {  // src = 2n + 1 -> n: the box [x (2n+1)/n, (x+1)(2n+1)/n] covers three texels partially
        const uint32_t n = dst;
        denominator = src;
        for (uint32_t x = 0; x < dst; ++x) taps[x] = {2 * x, 3, {n - x, n, x + 1}};
    }
    return taps;
}

const std::array<double, 256>& decodeTable() {
    static const std::array<double, 256> table = [] {
        std::array<double, 256> t{};
        for (int i = 0; i < 256; ++i) t[size_t(i)] = srgbToLinearD(i / 255.0);
        return t;
    }();
    return table;
}

void downsample(const uint8_t* src, uint32_t sw, uint32_t sh, uint8_t* dst, uint32_t dw, uint32_t dh, bool srgb) {
    uint32_t denX = 1, denY = 1;
    const std::vector<AxisTaps> tx = axisTaps(sw, dw, denX), ty = axisTaps(sh, dh, denY);
    const uint64_t den = uint64_t(denX) * denY;
    const double invDen = 1.0 / double(den);
    const std::array<double, 256>& lin = decodeTable();
    for (uint32_t y = 0; y < dh; ++y) {
        const AxisTaps& ay = ty[y];
        for (uint32_t x = 0; x < dw; ++x) {
            const AxisTaps& ax = tx[x];
            uint64_t sum[4] = {0, 0, 0, 0};
            double lsum[3] = {0.0, 0.0, 0.0};
            for (uint32_t j = 0; j < ay.count; ++j) {
                const uint8_t* row = src + (size_t(ay.first + j) * sw) * 4;
                for (uint32_t i = 0; i < ax.count; ++i) {
                    const uint32_t w = ay.weight[j] * ax.weight[i];
                    const uint8_t* p = row + size_t(ax.first + i) * 4;
                    for (int c = 0; c < 4; ++c) sum[c] += uint64_t(w) * p[c];
                    if (srgb)
                        for (int c = 0; c < 3; ++c) lsum[c] += double(w) * lin[p[c]];
                }
            }
            uint8_t* out = dst + (size_t(y) * dw + x) * 4;
            for (int c = 0; c < 4; ++c) {
                if (srgb && c < 3) out[c] = encodeSrgb8(lsum[c] * invDen);
                else out[c] = uint8_t((2 * sum[c] + den) / (2 * den));
            }
        }
    }
}

// Converts `rows` rows of `nch`-channel pixels of type `type` to RGBA8.
void toRgba8(const void* raw, OIIO::TypeDesc type, int nch, size_t pixels, bool srgb, uint8_t* out) {
    auto value = [&](size_t p, int c) -> uint8_t {
        const size_t i = p * size_t(nch) + size_t(c);
        if (type == OIIO::TypeDesc::UINT8) return static_cast<const uint8_t*>(raw)[i];
        if (type == OIIO::TypeDesc::UINT16)
            return uint8_t((uint32_t(static_cast<const uint16_t*>(raw)[i]) * 255u + 32767u) / 65535u);
        float v = static_cast<const float*>(raw)[i];
        if (!(v > 0.0f)) return 0;  // negative and NaN
        const bool colour = srgb && c < 3 && !(nch == 2 && c == 1);
        if (colour) return encodeSrgb8(double(v));
        return uint8_t(std::floor(std::min(v, 1.0f) * 255.0f + 0.5f));
    };
    for (size_t p = 0; p < pixels; ++p) {
        uint8_t* o = out + p * 4;
        if (nch == 1) {
            o[0] = o[1] = o[2] = value(p, 0);
            o[3] = 255;
        } else if (nch == 2) {
            o[0] = o[1] = o[2] = value(p, 0);
            o[3] = value(p, 1);
        } else {
            for (int c = 0; c < 3; ++c) o[c] = value(p, c);
            o[3] = nch >= 4 ? value(p, 3) : 255;
        }
    }
}

}  // namespace

double srgbToLinearD(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

uint8_t encodeSrgb8(double linear) {
    static const std::array<double, 255> thresholds = [] {
        std::array<double, 255> t{};
        for (int k = 0; k < 255; ++k) t[size_t(k)] = srgbToLinearD((k + 0.5) / 255.0);
        return t;
    }();
    if (!(linear > 0.0)) return 0;
    return uint8_t(std::upper_bound(thresholds.begin(), thresholds.end(), linear) - thresholds.begin());
}

std::vector<TextureColorSpace> textureColorSpaces(const Scene& scene) {
    std::vector<TextureColorSpace> spaces(scene.textures.size(), TextureColorSpace::Unused);
    auto use = [&](const std::optional<TextureRef>& ref, TextureColorSpace space) {
        if (ref && ref->texture < spaces.size()) mergeSpace(spaces[ref->texture], space);
    };
    for (const Material& m : scene.materials) {
        use(m.baseColorTexture, TextureColorSpace::Srgb);
        use(m.emissiveTexture, TextureColorSpace::Srgb);
        use(m.metallicRoughnessTexture, TextureColorSpace::Linear);
        use(m.normalTexture, TextureColorSpace::Linear);
        use(m.occlusionTexture, TextureColorSpace::Linear);
        use(m.transmissionTexture, TextureColorSpace::Linear);
        use(m.thicknessTexture, TextureColorSpace::Linear);
        use(m.specularTexture, TextureColorSpace::Linear);
        use(m.specularColorTexture, TextureColorSpace::Srgb);
        use(m.clearcoatTexture, TextureColorSpace::Linear);
        use(m.clearcoatRoughnessTexture, TextureColorSpace::Linear);
        use(m.sheenColorTexture, TextureColorSpace::Srgb);
        use(m.sheenRoughnessTexture, TextureColorSpace::Linear);
        use(m.iridescenceTexture, TextureColorSpace::Linear);
        use(m.iridescenceThicknessTexture, TextureColorSpace::Linear);
        use(m.clearcoatNormalTexture, TextureColorSpace::Linear);
        use(m.anisotropyTexture, TextureColorSpace::Linear);
        if (!m.unlit && m.diffuseTransmission > 0.0f) {  // a factor of 0 never reads them: not decoded
            use(m.diffuseTransmissionTexture, TextureColorSpace::Linear);
            use(m.diffuseTransmissionColorTexture, TextureColorSpace::Srgb);
        }
    }
    return spaces;
}

std::string imageLabel(const Scene& scene, uint32_t imageIndex) {
    if (imageIndex >= scene.images.size()) return "image " + std::to_string(imageIndex) + " (out of range)";
    const Image& image = scene.images[imageIndex];
    const std::string named = image.name.empty() ? "" : " ('" + image.name + "')";
    if (!image.path.empty()) return "image " + std::to_string(imageIndex) + named + " file " + image.path.string();
    std::string asset = scene.sourcePath.filename().string();
    return "embedded image " + std::to_string(imageIndex) + named + " of " + (asset.empty() ? "<memory>" : asset);
}

std::optional<DeclaredSize> declaredImageSize(const std::vector<uint8_t>& b) {
    static constexpr uint8_t kPng[8] = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
    if (b.size() >= 24 && std::equal(kPng, kPng + 8, b.begin()) && std::memcmp(b.data() + 12, "IHDR", 4) == 0) {
        auto be32 = [&](size_t at) {
            return uint32_t(b[at]) << 24 | uint32_t(b[at + 1]) << 16 | uint32_t(b[at + 2]) << 8 | b[at + 3];
        };
        return DeclaredSize{be32(16), be32(20)};
    }
    return jpegDeclaredSize(b);
}

uint64_t decodedTextureBytes(uint32_t width, uint32_t height) {
    uint64_t total = 0;
    for (uint64_t w = std::max(width, 1u), h = std::max(height, 1u);; w = std::max<uint64_t>(1, w / 2), h = std::max<uint64_t>(1, h / 2)) {
        total += w * h * 4;
        if (w == 1 && h == 1) return total;
    }
}

DecodedTexture buildMipChain(std::vector<uint8_t> level0, uint32_t width, uint32_t height, bool srgb) {
    if (width == 0 || height == 0 || level0.size() != size_t(width) * height * 4)
        throw std::invalid_argument("buildMipChain: " + std::to_string(level0.size()) + " bytes for a " +
                                    std::to_string(width) + "x" + std::to_string(height) + " RGBA8 image");
    DecodedTexture t;
    t.width = width;
    t.height = height;
    t.srgb = srgb;
    size_t total = 0;
    for (uint32_t w = width, h = height;; w = std::max(1u, w / 2), h = std::max(1u, h / 2)) {
        t.mips.push_back({w, h, total, size_t(w) * h * 4});
        total += size_t(w) * h * 4;
        if (w == 1 && h == 1) break;
    }
    t.texels = std::move(level0);
    t.texels.resize(total);
    for (size_t i = 1; i < t.mips.size(); ++i) {
        const MipLevel& s = t.mips[i - 1];
        const MipLevel& d = t.mips[i];
        downsample(t.texels.data() + s.offset, s.width, s.height, t.texels.data() + d.offset, d.width, d.height,
                   srgb);
    }
    return t;
}

DecodedTexture placeholderTexture(bool srgb) {
    std::vector<uint8_t> texels(size_t(kPlaceholderSize) * kPlaceholderSize * 4);
    for (uint32_t y = 0; y < kPlaceholderSize; ++y)
        for (uint32_t x = 0; x < kPlaceholderSize; ++x) {
            const bool magenta = (x + y) % 2 == 0;
            uint8_t* p = texels.data() + (size_t(y) * kPlaceholderSize + x) * 4;
            p[0] = p[2] = magenta ? 255 : 0;
            p[1] = 0;
            p[3] = 255;
        }
    DecodedTexture t = buildMipChain(std::move(texels), kPlaceholderSize, kPlaceholderSize, srgb);
    t.placeholder = true;
    return t;
}

namespace {

DecodedTexture decodeImageUnguarded(const Image& image, bool srgb, const std::string& label, const ImageLimits& limits) {
    if (image.status == ImageStatus::Missing) return failed(label, "file not found", srgb, true);
    if (image.status == ImageStatus::UnknownFormat) return failed(label, "not a known image format", srgb, true);

    // OpenImageIO associates (premultiplies) PNG alpha unless asked not to; glTF colours are straight alpha.
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    // Files are read into memory too, so both sources take the same checked path.
    std::vector<uint8_t> fileBytes;
    const std::vector<uint8_t>* bytes = &image.encoded;
    std::string extension;
    if (image.encoded.empty()) {
        if (image.path.empty()) return failed(label, "no image data (neither a file nor embedded bytes)", srgb);
        std::error_code ec;
        if (!std::filesystem::is_regular_file(image.path, ec)) return failed(label, "file not found", srgb);
        std::ifstream file(image.path, std::ios::binary);
        fileBytes.assign(std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>());
        if (!file && !file.eof()) return failed(label, "cannot read the file", srgb);
        bytes = &fileBytes;
        extension = image.path.extension().string();
        if (!extension.empty()) extension.erase(0, 1);
        std::transform(extension.begin(), extension.end(), extension.begin(),
                       [](unsigned char c) { return char(std::tolower(c)); });
    }
    if (bytes->empty()) return failed(label, "empty image data (0 bytes)", srgb);
    std::vector<uint8_t> withoutProfiles;
    if (bytes->size() >= 2 && (*bytes)[0] == 0xFF && (*bytes)[1] == 0xD8) {
        size_t removed = 0;
        withoutProfiles = withoutJpegIccProfiles(*bytes, removed);  // see jpeg_markers.hpp
        if (removed > 0) bytes = &withoutProfiles;
    }
    const std::string hint = formatHint(*bytes, image.mimeType, extension);
    static constexpr uint8_t kPngSignature[8] = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
    if (bytes->size() >= 8 && std::equal(kPngSignature, kPngSignature + 8, bytes->begin())) {
        if (auto error = pngStructureError(*bytes)) return failed(label, *error, srgb);
        // IHDR (checked to be the first chunk): width and height, big-endian, at bytes 16..23.
        auto be32 = [&](size_t at) {
            return uint32_t((*bytes)[at]) << 24 | uint32_t((*bytes)[at + 1]) << 16 | uint32_t((*bytes)[at + 2]) << 8 |
                   (*bytes)[at + 3];
        };
        if (auto error = limitError(be32(16), be32(20), limits)) return failed(label, *error, srgb);
    } else if (const auto size = jpegDeclaredSize(*bytes)) {
        if (auto error = limitError(size->width, size->height, limits)) return failed(label, *error, srgb);
    } else if (bytes->size() < 16) {
        return failed(label, "cannot decode " + std::to_string(bytes->size()) + " bytes", srgb);
    }
    // OIIO 2.4 ignores open()'s ioproxy argument when a config is given: pass the proxy inside the config.
    OIIO::Filesystem::IOMemReader reader(bytes->data(), bytes->size());
    void* proxy = &reader;
    config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
    std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::open("image." + hint, &config);
    if (!in) return failed(label, "cannot decode: " + firstLine(OIIO::geterror()), srgb);

    auto fail = [&](const std::string& cause) {
        std::string detail = in->geterror();
        OIIO::geterror();  // clear this thread's pending message too
        in->close();
        return failed(label, detail.empty() ? cause : cause + ": " + firstLine(detail), srgb);
    };
    in->threads(1);  // the streamer already decodes one image per worker thread
    const OIIO::ImageSpec spec = in->spec();
    if (spec.width <= 0 || spec.height <= 0 || spec.depth > 1)
        return fail("unsupported image dimensions " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                    "x" + std::to_string(spec.depth));
    if (auto error = limitError(uint64_t(spec.width), uint64_t(spec.height), limits)) return fail(*error);
    if (spec.nchannels < 1 || spec.nchannels > 64) return fail(std::to_string(spec.nchannels) + " channels");

    const OIIO::TypeDesc base(OIIO::TypeDesc::BASETYPE(spec.format.basetype));
    OIIO::TypeDesc type = OIIO::TypeDesc::FLOAT;
    if (base == OIIO::TypeDesc::UINT8 || base == OIIO::TypeDesc::INT8) type = OIIO::TypeDesc::UINT8;
    if (base == OIIO::TypeDesc::UINT16 || base == OIIO::TypeDesc::INT16) type = OIIO::TypeDesc::UINT16;
    const auto w = uint32_t(spec.width), h = uint32_t(spec.height);
    const int nch = spec.nchannels;
    std::vector<uint8_t> rgba(size_t(w) * h * 4);
    // Strips bound the temporary at 64 rows of the source format (a 16384^2 float RGBA image would be 4 GiB);
    // tiled files (EXR, TIFF) are read whole.
    if (spec.tile_width != 0) {
        std::vector<uint8_t> raw(size_t(w) * h * size_t(nch) * type.size());
        if (!in->read_image(0, 0, 0, nch, type, raw.data())) return fail("cannot decode");
        toRgba8(raw.data(), type, nch, size_t(w) * h, srgb, rgba.data());
    }
    constexpr uint32_t kStrip = 64;
    std::vector<uint8_t> raw(spec.tile_width != 0 ? 0 : size_t(w) * kStrip * size_t(nch) * type.size());
    for (uint32_t y = 0; spec.tile_width == 0 && y < h; y += kStrip) {
        const uint32_t rows = std::min(kStrip, h - y);
        if (!in->read_scanlines(0, 0, spec.y + int(y), spec.y + int(y + rows), 0, 0, nch, type, raw.data()))
            return fail("cannot decode");
        toRgba8(raw.data(), type, nch, size_t(w) * rows, srgb, rgba.data() + size_t(y) * w * 4);
    }
    if (in->has_error()) return fail("cannot decode");
    in->close();
    return buildMipChain(std::move(rgba), w, h, srgb);
}

}  // namespace

DecodedTexture decodeImage(const Image& image, bool srgb, std::string_view labelIn, const ImageLimits& limits) {
    std::string label(labelIn);
    if (label.empty())
        label = !image.path.empty() ? image.path.string()
                                    : "embedded image" + (image.name.empty() ? "" : " '" + image.name + "'");
    // OpenImageIO's readers may throw on hostile headers (its GIF reader throws std::length_error for a huge
    // logical screen: found by tests/fuzz/fuzz_image.cpp); the contract is a placeholder, never an exception.
    try {
        return decodeImageUnguarded(image, srgb, label, limits);
    } catch (const std::exception& e) {
        return failed(label, std::string("cannot decode: ") + e.what(), srgb);
    }
}

}  // namespace idk::scene
