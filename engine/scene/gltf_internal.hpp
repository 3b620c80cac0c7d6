// gltf_internal.hpp: what the gltf_*.cpp files of the loader (the port of IDKEngine's ModelLoader) share: the
// load context (file, parsed tinygltf model, scene being filled, options; fail() and warn()), validated accessor
// reading, JSON value helpers and the per-topic entry points that loadGltfFromMemory() calls in order.
// Private to engine/scene.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "scene/gltf_loader.hpp"
#include "scene/scene.hpp"
#include "scene/tinygltf_include.hpp"

namespace idk::scene::gltf {

// LoadOptions::maxMemoryBytes: what the load has committed so far, charged before each allocation.
class MemoryBudget {
public:
    MemoryBudget(const std::filesystem::path& file, uint64_t limit) : file_(file), limit_(limit) {}
    // Throws LoadError naming `what`, its size, what is already committed and the budget, when over.
    void charge(uint64_t bytes, const std::string& what);
    uint64_t used() const { return used_; }

private:
    const std::filesystem::path& file_;
    uint64_t limit_ = 0;  // 0: none
    uint64_t used_ = 0;
};

struct Ctx {
    const std::filesystem::path& file;
    const tinygltf::Model& model;
    Scene& scene;
    const LoadOptions& options;
    MemoryBudget& budget;

    [[noreturn]] void fail(const std::string& cause) const { throw LoadError(file, cause); }
    void warn(const std::string& message) const;  // Scene::warnings + the engine log
    void charge(uint64_t bytes, const std::string& what) const { budget.charge(bytes, what); }
};

inline std::string str(size_t v) {
    return std::to_string(v);
}
inline std::string str(int v) {
    return std::to_string(v);
}

// --- files (gltf_files.cpp) -------------------------------------------------------------------------------

constexpr size_t kMaxFileBytes = size_t{0xFFFFFFFFu};  // tinygltf takes 32-bit sizes

// The whole file, its size checked (and charged to `budget`, when given) before anything is allocated.
std::vector<uint8_t> readWholeFile(const std::filesystem::path& path, MemoryBudget* budget = nullptr);

// Every external buffer and image URI must stay inside the asset's folder (asset_uri.hpp): checked here, before
// tinygltf reads a buffer or the image records are made, so a hostile URI is refused before any file is opened.
// Data URIs are decoded by tinygltf: their decoded size (3/4 of the base64 text) is charged first.
void checkUris(const std::filesystem::path& path, const nlohmann::json& json, const LoadOptions& options,
               MemoryBudget& budget);

// tinygltf's file system for external buffers. Defence in depth behind checkUris(): every path tinygltf
// wants to open (it also searches the working directory, "./uri") is confined again, and nothing is expanded
// or written.
struct FileAccess {
    std::filesystem::path folder;
    std::string baseDir;  // what tinygltf joins URIs onto
    bool allowExternal = false;
    MemoryBudget* budget = nullptr;
};
tinygltf::FsCallbacks fileCallbacks(FileAccess& access);  // `access` must outlive the parse

// --- accessors (gltf_accessors.cpp) -----------------------------------------------------------------------

constexpr size_t kMaxZeroAccessorCount = size_t{1} << 26;  // accessors without bufferView allocate count

size_t componentSize(int componentType);  // 0 for invalid types
int componentCount(int type);             // SCALAR 1 .. VEC4 4, MAT4 16; 0 for other types

struct ByteRange {
    const uint8_t* base = nullptr;
    size_t stride = 0;
};

// Validates that `count` elements of `elementSize` bytes from `byteOffset` (stride: the view's byteStride when
// allowed and set, else elementSize) lie inside bufferView `viewIndex`, which lies inside its buffer.
ByteRange checkedRange(const Ctx& ctx, int viewIndex, size_t byteOffset, size_t count, size_t elementSize,
                       bool allowViewStride, const std::string& what);

const tinygltf::Accessor& accessorAt(const Ctx& ctx, int index, const std::string& what);

// Floats of an accessor with its own component count (written to *components): normalized integers map to
// [0,1] / [-1,1], plain integers convert as is (KHR_mesh_quantization); sparse substitution applied.
std::vector<float> readAnyFloats(const Ctx& ctx, int index, const std::string& usage, int* components);
// The same, requiring exactly `components` per element (16: MAT4).
std::vector<float> readFloats(const Ctx& ctx, int index, int components, const std::string& usage);
// Unsigned integer SCALARs (indices).
std::vector<uint32_t> readIndices(const Ctx& ctx, int index, const std::string& usage);

template <int N>
std::vector<glm::vec<N, float>> toVectors(const std::vector<float>& flat) {
    std::vector<glm::vec<N, float>> out(flat.size() / N);
    for (size_t i = 0; i < out.size(); ++i)
        for (int c = 0; c < N; ++c) out[i][c] = flat[i * N + size_t(c)];
    return out;
}

// --- JSON values (tinygltf::Value extensions) ---------------------------------------------------------------

double numberOr(const tinygltf::Value& object, const char* key, double fallback);
glm::vec2 vec2Or(const tinygltf::Value& object, const char* key, glm::vec2 fallback);
glm::vec3 vec3Or(const tinygltf::Value& object, const char* key, glm::vec3 fallback);
// An integer index property; empty when absent, fail()s when present but not a non-negative integer.
std::optional<uint32_t> indexOr(const Ctx& ctx, const tinygltf::Value& object, const char* key,
                                const std::string& where);
const tinygltf::Value* extension(const tinygltf::ExtensionMap& map, const char* name);

template <int N>
glm::vec<N, float> factor(const std::vector<double>& v, glm::vec<N, float> fallback) {
    if (v.size() != size_t(N)) return fallback;
    glm::vec<N, float> out;
    for (int i = 0; i < N; ++i) out[i] = float(v[size_t(i)]);
    return out;
}

// --- compression (gltf_compression.cpp) ----------------------------------------------------------------------

// EXT_meshopt_compression: decodes every compressed bufferView into a new buffer appended to `model` and points
// the view at it, so accessors read plain data afterwards. ctx.model must be `model`.
void decodeMeshoptViews(const Ctx& ctx, tinygltf::Model& model);

// KHR_draco_mesh_compression: the decoded triangle list and attributes (by glTF attribute name, with their
// component count) of a primitive that has the extension; empty otherwise.
struct DecodedAttribute {
    std::vector<float> values;
    int components = 0;
};
struct DracoGeometry {
    size_t vertexCount = 0;
    std::vector<uint32_t> indices;
    std::map<std::string, DecodedAttribute> attributes;
};
std::optional<DracoGeometry> decodeDraco(const Ctx& ctx, const tinygltf::Primitive& prim, const std::string& where);

// --- per-topic stages, in the order loadGltfFromMemory() runs them -------------------------------------------

void loadTextures(const Ctx& ctx);    // gltf_materials.cpp: images (recorded, not decoded) and samplers
void loadMaterials(const Ctx& ctx);   // gltf_materials.cpp
// The texture reference `key` of an extension object (texCoord, KHR_texture_transform), as the core textures:
// fail()s on a malformed or out-of-range reference; empty when absent (gltf_materials.cpp).
std::optional<TextureRef> extensionTextureRef(const Ctx& ctx, const tinygltf::Value& object, const char* key,
                                              const std::string& where);
// KHR_materials_specular, _clearcoat, _sheen of one material and their textures (gltf_material_ext.cpp); where
// names the material.
void loadMaterialExtensions(const Ctx& ctx, const tinygltf::Material& src, const std::string& where, Material& mat);
void loadMeshes(const Ctx& ctx);      // gltf_meshes.cpp: attributes, morph targets, tangents
// KHR_materials_variants (material_variants.cpp): the file's variant names (before loadMeshes), a primitive's
// mappings (where names the primitive for warnings).
void loadVariantNames(const Ctx& ctx);
void loadVariantMappings(const Ctx& ctx, const tinygltf::ExtensionMap& extensions, Primitive& prim,
                         const std::string& where);
void loadNodes(const Ctx& ctx);       // gltf_nodes.cpp: hierarchy, TRS, EXT_mesh_gpu_instancing
void loadSkins(const Ctx& ctx);       // gltf_nodes.cpp: skins + joint index validation of skinned meshes
void loadAnimations(const Ctx& ctx);  // gltf_animation.cpp
void placeScene(const Ctx& ctx);      // gltf_nodes.cpp: world matrices, instances, cameras, lights, bounds

}  // namespace idk::scene::gltf
