// gltf_loader.hpp: loads a glTF 2.0 file (.gltf or .glb) through tinygltf into a Scene of flat arrays.
// Ports IDKEngine's ModelLoader at a basic level (geometry, core PBR factors, base-colour texture reference,
// node hierarchy, cameras, KHR_lights_punctual). Every index and byte range is validated before it is read.
#pragma once

#include <cstdint>
#include <filesystem>
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
// Supported: KHR_mesh_quantization, KHR_lights_punctual, KHR_materials_emissive_strength, KHR_texture_transform.
bool isSupportedExtension(const std::string& name);

// Loads the file. Throws LoadError. Non-fatal problems (skipped point/line primitives, ignored attributes...)
// are appended to Scene::warnings and logged as warnings.
Scene loadGltf(const std::filesystem::path& path);

// The same for a file already in memory (e.g. a scene embedded in the binary). `name` stands for the file in
// messages and Scene::sourcePath; external URIs (buffers, images) resolve against name.parent_path().
Scene loadGltfFromMemory(std::span<const uint8_t> bytes, const std::filesystem::path& name);

}  // namespace idk::scene
