// gltf_loader.hpp: loads a glTF 2.0 file (.gltf or .glb) through tinygltf into a Scene of flat arrays.
// Ports IDKEngine's ModelLoader (geometry with every attribute, compressed geometry, the full metallic-roughness
// material, hierarchy, skins, morph targets, animations, cameras, lights). Every index and byte range is
// validated before it is read. Implementation: gltf_loader.cpp plus the gltf_*.cpp files by topic (material
// extensions: gltf_materials.cpp, and gltf_material_ext.cpp for KHR_materials_specular, _clearcoat, _sheen and
// _anisotropy, whose textures are reported and not read yet).
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>

#include "scene/scene.hpp"

namespace idk::scene {

// Thrown for any file that cannot be loaded. what() names the file and the cause.
class LoadError : public std::runtime_error {
public:
    LoadError(const std::filesystem::path& file, const std::string& cause);
    const std::filesystem::path& file() const { return file_; }
    const std::string& cause() const { return cause_; }

private:
    std::filesystem::path file_;
    std::string cause_;
};

// Extensions the loader understands; a file that REQUIRES any other extension is rejected with LoadError.
// Supported: KHR_mesh_quantization, KHR_draco_mesh_compression, EXT_meshopt_compression, EXT_mesh_gpu_instancing,
// KHR_lights_punctual, KHR_texture_transform, KHR_materials_emissive_strength, _unlit, _transmission, _ior,
// _volume.
bool isSupportedExtension(const std::string& name);

struct LoadOptions {
    std::optional<uint32_t> scene;  // which glTF scene to place; empty: the file's `scene`, else scene 0
    // External buffer and image URIs must resolve inside the asset's folder (see asset_uri.hpp); true lifts
    // the rule for trusted content (`--allow-external-uris`).
    bool allowExternalUris = false;
    // Total bytes the load may allocate (`--max-memory`; 0: no budget): the file, external buffers, decoded data
    // URIs, accessor data, meshopt/Draco output and the decoded size of every PNG/JPEG image (from its header),
    // each charged before it is allocated. Going over is a LoadError naming the budget and the numbers.
    uint64_t maxMemoryBytes = 0;
};

// Loads the file. Throws LoadError. Non-fatal problems (skipped point/line primitives, ignored attributes...)
// are appended to Scene::warnings and logged as warnings.
//
// Bad input, decided per case:
//   * LoadError (naming the file and the cause): going over LoadOptions::maxMemoryBytes, an external buffer or image URI that is absolute or resolves
//     outside the asset's folder (unless allowExternalUris; checked before any file is opened), malformed containers/JSON, any index or byte range out of
//     range, attribute count mismatches, undecodable Draco/meshopt data, a skin with more than kMaxJoints
//     joints, a joint index past its skin with a nonzero weight, non-finite inverse bind matrices, animation
//     sampler/node indices out of range, input/output keyframe count mismatches, decreasing or non-finite
//     keyframe times, an out-of-range LoadOptions::scene.
//   * Warning + documented substitute: NaN/infinite POSITION values drop that primitive; non-finite values in
//     other vertex attributes become 0; points/lines are skipped; a missing or unrecognised image keeps its
//     path/bytes with Image::status set (the decoder draws magenta); an unknown animation path is skipped.
//   * Accepted as is: zero-scale nodes (degenerate world matrices; their joint matrices become zero), equal
//     consecutive keyframe times (a jump at that time).
Scene loadGltf(const std::filesystem::path& path, const LoadOptions& options = {});

// The same for a file already in memory (e.g. a scene embedded in the binary). `name` stands for the file in
// messages and Scene::sourcePath; external URIs (buffers, images) resolve against name.parent_path().
Scene loadGltfFromMemory(std::span<const uint8_t> bytes, const std::filesystem::path& name,
                         const LoadOptions& options = {});

}  // namespace idk::scene
