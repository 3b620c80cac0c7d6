// scene_options.hpp: the command-line options every program that loads a glTF file shares (`idk render`,
// `idk bvh`, idk-viewer), so an untrusted scene is handled the same everywhere:
//   --allow-external-uris  buffer/image URIs may leave the asset's folder (trusted content only)
//   --max-memory SIZE      what loading may allocate in all (file, buffers, geometry, decoded images)
// parsed into scene::LoadOptions.
#pragma once
#include <cctype>
#include <cmath>
#include <cstdint>
#include <string>

#include "core/cli.hpp"
#include "scene/gltf_loader.hpp"

namespace idk::app {

inline const char* const kSceneOptionsHelp =
    "  --allow-external-uris  let buffer and image URIs point outside the scene's folder (absolute paths, '..',\n"
    "                   symlinks); without it such a scene is refused: use it only for content you trust\n"
    "  --max-memory SIZE  refuse a scene whose loading would allocate more than SIZE bytes in all (file, buffers,\n"
    "                   geometry, decoded PNG/JPEG images), before allocating; K/M/G suffixes (default: no limit)\n";

// `spec` plus the shared scene options.
inline core::CliSpec withSceneOptions(core::CliSpec spec) {
    spec.flags.insert("--allow-external-uris");
    spec.options.insert("--max-memory");
    return spec;
}

// "4096", "512K", "64M", "2G" (binary multiples) -> bytes; throws CliError naming the text.
inline uint64_t parseByteSize(const std::string& option, const std::string& text) {
    std::string digits = text;
    double scale = 1.0;
    if (!digits.empty()) {
        const char unit = char(std::toupper(static_cast<unsigned char>(digits.back())));
        if (unit == 'K' || unit == 'M' || unit == 'G') {
            scale = unit == 'K' ? 1024.0 : unit == 'M' ? 1024.0 * 1024.0 : 1024.0 * 1024.0 * 1024.0;
            digits.pop_back();
        }
    }
    const double value = core::parseNumber(option, digits) * scale;
    if (!(value >= 1.0 && value < 1.8e19))
        throw core::CliError(option + " '" + text + "': give a size in bytes, e.g. 512M or 4G");
    return uint64_t(value);
}

inline scene::LoadOptions loadOptionsFromCli(const core::CliArgs& args) {
    scene::LoadOptions options;
    options.allowExternalUris = args.has("--allow-external-uris");
    if (const auto size = args.get("--max-memory")) options.maxMemoryBytes = parseByteSize("--max-memory", *size);
    return options;
}

}  // namespace idk::app
