// image_file.cpp: OpenImageIO-backed image files; outputs are written atomically (core/atomic_file.hpp).
#include "core/image_file.hpp"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/atomic_file.hpp"

namespace idk::core {

float srgbToLinear(float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); }
float linearToSrgb(float c) {
    c = std::clamp(c, 0.0f, 1.0f);
    return c <= 0.0031308f ? c * 12.92f : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

void writeImage(const std::filesystem::path& path, const ImageRgba32f& image) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    bool exr = ext == ".exr";
    if (!exr && ext != ".png") {
        throw std::runtime_error(path.string() + ": unsupported output format '" + ext + "' (use .png or .exr)");
    }
    if (image.pixels.size() != size_t(image.width) * image.height * 4) {
        throw std::invalid_argument(path.string() + ": pixel count does not match the image size");
    }
    // Encoded in memory, then written with checked writes: OpenImageIO's PNG writer does not report a failed
    // write (a full disk, the file-size limit), so writing through it could publish a truncated file.
    std::vector<unsigned char> encoded;
    OIIO::Filesystem::IOVecOutput memory(encoded);
    auto out = OIIO::ImageOutput::create(path.string());
    if (!out) throw std::runtime_error(path.string() + ": cannot create image writer: " + OIIO::geterror());
    if (!out->set_ioproxy(&memory)) throw std::runtime_error(path.string() + ": the image writer cannot write to memory");
    int w = static_cast<int>(image.width), h = static_cast<int>(image.height);
    bool ok;
    if (exr) {
        OIIO::ImageSpec spec(w, h, 4, OIIO::TypeDesc::FLOAT);
        ok = out->open(path.string(), spec) && out->write_image(OIIO::TypeDesc::FLOAT, image.pixels.data());
    } else {
        std::vector<uint8_t> bytes(image.pixels.size());
        for (size_t i = 0; i < bytes.size(); ++i) {
            float v = (i % 4 == 3) ? std::clamp(image.pixels[i], 0.0f, 1.0f) : linearToSrgb(image.pixels[i]);
            bytes[i] = static_cast<uint8_t>(std::lround(v * 255.0f));
        }
        OIIO::ImageSpec spec(w, h, 4, OIIO::TypeDesc::UINT8);
        ok = out->open(path.string(), spec) && out->write_image(OIIO::TypeDesc::UINT8, bytes.data());
    }
    ok = out->close() && ok;  // close() finishes the encoding
    if (!ok) throw std::runtime_error(path.string() + ": " + out->geterror());
    if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
    writeFileAtomically(path, std::string_view(reinterpret_cast<const char*>(encoded.data()), encoded.size()));
}

ImageRgba32f readImage(const std::filesystem::path& path) {
    auto in = OIIO::ImageInput::open(path.string());
    if (!in) throw std::runtime_error(path.string() + ": cannot read image: " + OIIO::geterror());
    const OIIO::ImageSpec& spec = in->spec();
    ImageRgba32f image;
    image.width = static_cast<uint32_t>(spec.width);
    image.height = static_cast<uint32_t>(spec.height);
    std::vector<float> raw(size_t(spec.width) * spec.height * spec.nchannels);
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, raw.data())) {
        throw std::runtime_error(path.string() + ": " + in->geterror());
    }
    bool srgb = spec.format == OIIO::TypeDesc::UINT8;
    image.pixels.assign(size_t(image.width) * image.height * 4, 1.0f);
    for (size_t p = 0; p < size_t(image.width) * image.height; ++p) {
        for (int c = 0; c < std::min(spec.nchannels, 4); ++c) {
            float v = raw[p * spec.nchannels + c];
            image.pixels[p * 4 + c] = (srgb && c < 3) ? srgbToLinear(v) : v;
        }
        if (spec.nchannels == 1) image.pixels[p * 4 + 1] = image.pixels[p * 4 + 2] = image.pixels[p * 4];
    }
    in->close();
    return image;
}

}  // namespace idk::core
