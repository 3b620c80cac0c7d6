// image_file.hpp: writing and reading images through OpenImageIO. PNG gets 8-bit sRGB-encoded values,
// EXR keeps linear 32-bit floats; the format follows the file extension.
#pragma once
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace idk::core {

// Linear RGBA float pixels, row-major, top row first.
struct ImageRgba32f {
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<float> pixels;  // width * height * 4
};

// Writes .png (sRGB-encoded, clamped to [0,1]) or .exr (linear half-free float), atomically (core/atomic_file.hpp:
// a failed or interrupted write leaves no file, or the older one, under `path`). Throws std::runtime_error naming
// the path and OpenImageIO's message on failure or an unsupported extension.
void writeImage(const std::filesystem::path& path, const ImageRgba32f& image);

// Reads any format OpenImageIO knows into linear RGBA float (8-bit files are sRGB-decoded). Throws naming the path.
ImageRgba32f readImage(const std::filesystem::path& path);

float srgbToLinear(float c);
float linearToSrgb(float c);

}  // namespace idk::core
