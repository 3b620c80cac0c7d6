// scene_options.hpp: the command-line options every program that loads a glTF file shares (`idk render`,
// `idk bvh`, idk-viewer), so an untrusted scene is handled the same everywhere:
//   --allow-external-uris  buffer/image URIs may leave the asset's folder (trusted content only)
// parsed into scene::LoadOptions.
#pragma once
#include "core/cli.hpp"
#include "scene/gltf_loader.hpp"

namespace idk::app {

inline const char* const kSceneOptionsHelp =
    "  --allow-external-uris  let buffer and image URIs point outside the scene's folder (absolute paths, '..',\n"
    "                   symlinks); without it such a scene is refused: use it only for content you trust\n";

// `spec` plus the shared scene options.
inline core::CliSpec withSceneOptions(core::CliSpec spec) {
    spec.flags.insert("--allow-external-uris");
    return spec;
}

inline scene::LoadOptions loadOptionsFromCli(const core::CliArgs& args) {
    scene::LoadOptions options;
    options.allowExternalUris = args.has("--allow-external-uris");
    return options;
}

}  // namespace idk::app
