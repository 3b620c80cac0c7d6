// gltf_loader.cpp: glTF 2.0 (.gltf/.glb) -> Scene through tinygltf, the entry points of the port of IDKEngine's
// ModelLoader: the GLB container checks, a JSON pre-pass (nesting depth, required extensions, meshopt fallback
// buffers, URI confinement from gltf_files.cpp), parsing, then the per-topic stages of gltf_*.cpp in order.
// Hostile input never crashes: every index and byte range is checked before it is read (see gltf_loader.hpp).
#include "scene/gltf_loader.hpp"

#include <algorithm>
#include <array>
#include <cstring>
#include <optional>
#include <span>

#include <nlohmann/json.hpp>

#include "scene/asset_uri.hpp"
#include "scene/gltf_internal.hpp"

namespace idk::scene {

LoadError::LoadError(const std::filesystem::path& file, const std::string& cause)
    : std::runtime_error(file.string() + ": " + cause), file_(file), cause_(cause) {}

bool isSupportedExtension(const std::string& name) {
    static const std::array<const char*, 19> kSupported = {
        "KHR_mesh_quantization",           "KHR_draco_mesh_compression", "EXT_meshopt_compression",
        "EXT_mesh_gpu_instancing",         "KHR_lights_punctual",        "KHR_texture_transform",
        "KHR_materials_emissive_strength", "KHR_materials_unlit",        "KHR_materials_transmission",
        "KHR_materials_ior",               "KHR_materials_volume",       "KHR_materials_specular",
        "KHR_materials_clearcoat",         "KHR_materials_sheen",        "KHR_materials_variants",
        "KHR_materials_anisotropy",        "KHR_materials_diffuse_transmission", "KHR_materials_dispersion",
        "KHR_materials_iridescence"};
    return std::any_of(kSupported.begin(), kSupported.end(), [&](const char* s) { return name == s; });
}

namespace {

using gltf::kMaxFileBytes;
using gltf::str;

constexpr uint32_t kGlbMagic = 0x46546C67;             // "glTF"
constexpr uint32_t kGlbChunkJson = 0x4E4F534A;         // "JSON"
constexpr int kMaxJsonDepth = 128;                     // glTF itself needs < 10; extras may nest a little

uint32_t readU32(std::span<const uint8_t> bytes, size_t offset) {
    uint32_t v = 0;
    std::memcpy(&v, bytes.data() + offset, 4);  // GLB is little-endian, as is every target we build for
    return v;
}

// Checks the GLB container (header, chunk headers and lengths) before tinygltf looks at it.
void validateGlb(const std::filesystem::path& path, std::span<const uint8_t> bytes) {
    if (bytes.size() < 20) throw LoadError(path, "truncated GLB: " + str(bytes.size()) + " bytes, header needs 20");
    const uint32_t version = readU32(bytes, 4);
    const uint32_t length = readU32(bytes, 8);
    if (version != 2) throw LoadError(path, "GLB version " + std::to_string(version) + " is not 2");
    if (length > bytes.size())
        throw LoadError(
            path, "truncated GLB: header declares " + std::to_string(length) + " bytes, file has " + str(bytes.size()));
    if (length < 20) throw LoadError(path, "GLB has no JSON chunk");
    size_t offset = 12;
    for (int chunk = 0; offset < length; ++chunk) {
        if (length - offset < 8) throw LoadError(path, "truncated GLB: chunk " + std::to_string(chunk) + " header");
        const uint32_t chunkLength = readU32(bytes, offset);
        const uint32_t chunkType = readU32(bytes, offset + 4);
        if (chunk == 0 && chunkType != kGlbChunkJson) throw LoadError(path, "GLB: first chunk is not JSON");
        if (chunkLength > length - offset - 8)
            throw LoadError(path, "truncated GLB: chunk " + std::to_string(chunk) + " declares " +
                                      std::to_string(chunkLength) + " bytes past the end of the file");
        offset += 8 + size_t{chunkLength};
    }
}

// EXT_meshopt_compression fallback buffers may have no uri (the data exists only compressed); tinygltf cannot
// load such a buffer, so it gets a 4-byte placeholder. The views that use it are rewritten after decoding.
bool replaceFallbackBuffers(nlohmann::json& json, bool binary) {
    const auto buffers = json.find("buffers");
    if (buffers == json.end() || !buffers->is_array()) return false;
    bool changed = false;
    for (size_t i = 0; i < buffers->size(); ++i) {
        auto& buffer = (*buffers)[i];
        if (!buffer.is_object() || buffer.contains("uri") || (binary && i == 0)) continue;
        const auto ext = buffer.find("extensions");
        if (ext == buffer.end() || !ext->is_object() || !ext->contains("EXT_meshopt_compression")) continue;
        buffer["uri"] = "data:application/octet-stream;base64,AAAAAA==";
        buffer["byteLength"] = 4;
        changed = true;
    }
    return changed;
}

// tinygltf requires every primitive's indices accessor to have a bufferView, which a Draco primitive's does
// not: its indices come from the Draco data, so the reference is dropped before tinygltf sees it.
bool dropDracoIndices(nlohmann::json& json) {
    const auto meshes = json.find("meshes");
    if (meshes == json.end() || !meshes->is_array()) return false;
    bool changed = false;
    for (auto& mesh : *meshes) {
        if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
        for (auto& prim : mesh["primitives"]) {
            if (!prim.is_object() || !prim.contains("indices")) continue;
            const auto ext = prim.find("extensions");
            if (ext != prim.end() && ext->is_object() && ext->contains("KHR_draco_mesh_compression")) {
                prim.erase("indices");
                changed = true;
            }
        }
    }
    return changed;
}

// Rebuilds the file with new JSON text (GLB: the same binary chunks after a new JSON chunk).
std::vector<uint8_t> withJson(std::span<const uint8_t> bytes, bool binary, std::string text) {
    if (!binary) return {text.begin(), text.end()};
    while (text.size() % 4) text += ' ';
    const size_t oldJsonEnd = 20 + size_t(readU32(bytes, 12));
    const size_t length = readU32(bytes, 8);
    const size_t rest = length > oldJsonEnd ? length - oldJsonEnd : 0;
    std::vector<uint8_t> out(20 + text.size() + rest);
    auto put = [&](size_t offset, uint32_t v) { std::memcpy(out.data() + offset, &v, 4); };
    put(0, kGlbMagic);
    put(4, 2);
    put(8, uint32_t(out.size()));
    put(12, uint32_t(text.size()));
    put(16, kGlbChunkJson);
    std::memcpy(out.data() + 20, text.data(), text.size());
    if (rest > 0) std::memcpy(out.data() + 20 + text.size(), bytes.data() + oldJsonEnd, rest);
    return out;
}


// Checks the JSON text before any parser builds a tree from it: nesting deeper than kMaxJsonDepth is rejected
// (tinygltf converts extras/extensions recursively, so a hostile file could overflow the stack), and a file that
// requires an extension we do not implement is rejected by name. Returns rewritten file bytes when meshopt
// fallback buffers or Draco index references had to be replaced for tinygltf (see below), else nothing.
std::optional<std::vector<uint8_t>> precheckJson(const std::filesystem::path& path, std::span<const uint8_t> bytes,
                                                 bool binary, const LoadOptions& options, gltf::MemoryBudget& budget) {
    const char* begin = reinterpret_cast<const char*>(bytes.data());
    size_t length = bytes.size();
    if (binary) {  // validateGlb() guarantees chunk 0 exists and fits
        begin += 20;
        length = readU32(bytes, 12);
    }
    int depth = 0;
    bool inString = false, escaped = false;
    for (size_t i = 0; i < length; ++i) {
        const char c = begin[i];
        if (inString) {
            if (escaped) escaped = false;
            else if (c == '\\') escaped = true;
            else if (c == '"') inString = false;
        } else if (c == '"') {
            inString = true;
        } else if (c == '[' || c == '{') {
            if (++depth > kMaxJsonDepth)
                throw LoadError(path, "JSON nested deeper than " + std::to_string(kMaxJsonDepth) + " levels");
        } else if (c == ']' || c == '}') {
            --depth;
        }
    }
    const auto json = nlohmann::json::parse(begin, begin + length, nullptr, /*allow_exceptions=*/false);
    if (json.is_discarded() || !json.is_object()) return std::nullopt;  // tinygltf reports the parse error
    const auto it = json.find("extensionsRequired");
    if (it != json.end() && it->is_array())
        for (const auto& ext : *it)
            if (ext.is_string() && !isSupportedExtension(ext.get<std::string>()))
                throw LoadError(path, "requires unsupported extension " + ext.get<std::string>());
    gltf::checkUris(path, json, options, budget);
    auto edited = json;
    const bool fallbacks = replaceFallbackBuffers(edited, binary);
    const bool draco = dropDracoIndices(edited);
    if (!fallbacks && !draco) return std::nullopt;
    return withJson(bytes, binary, edited.dump());
}

// tinygltf image callback: never decodes. Data-URI images keep their encoded bytes; images in buffer views
// are copied later, after their byte range has been validated (tinygltf does not check it).
bool recordImage(tinygltf::Image* image, const int, std::string*, std::string*, int, int, const unsigned char* bytes,
                 int size, void*) {
    if (image->bufferView < 0 && bytes != nullptr && size > 0) image->image.assign(bytes, bytes + size);
    return true;
}

std::string trimmed(std::string s) {
    while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
    return s;
}

}  // namespace

Scene loadGltf(const std::filesystem::path& path, const LoadOptions& options) {
    gltf::MemoryBudget fileBudget(path, options.maxMemoryBytes);
    const std::vector<uint8_t> bytes = gltf::readWholeFile(path, &fileBudget);  // refused before reading when too large
    return loadGltfFromMemory(bytes, path, options);
}

Scene loadGltfFromMemory(std::span<const uint8_t> bytes, const std::filesystem::path& path,
                         const LoadOptions& options) {
    if (bytes.empty()) throw LoadError(path, "empty file");
    if (bytes.size() > kMaxFileBytes) throw LoadError(path, "larger than 4 GiB");
    const bool binary = bytes.size() >= 4 && readU32(bytes, 0) == kGlbMagic;
    if (binary) validateGlb(path, bytes);
    gltf::MemoryBudget budget(path, options.maxMemoryBytes);
    budget.charge(bytes.size(), "file " + path.filename().string());
    const std::optional<std::vector<uint8_t>> rewritten = precheckJson(path, bytes, binary, options, budget);
    if (rewritten) bytes = std::span<const uint8_t>(*rewritten);

    tinygltf::TinyGLTF parser;
    parser.SetImageLoader(&recordImage, nullptr);
    tinygltf::Model model;
    std::string err, warn;
    const std::string baseDir = path.parent_path().string();
    gltf::FileAccess access{assetFolder(path), baseDir, options.allowExternalUris, &budget};
    parser.SetFsCallbacks(gltf::fileCallbacks(access));
    bool ok = false;
    try {
        if (binary)
            ok = parser.LoadBinaryFromMemory(&model, &err, &warn, bytes.data(), unsigned(bytes.size()), baseDir);
        else
            ok = parser.LoadASCIIFromString(&model, &err, &warn, reinterpret_cast<const char*>(bytes.data()),
                                            unsigned(bytes.size()), baseDir);
    } catch (const LoadError&) {
        throw;
    } catch (const std::exception& e) {
        throw LoadError(path, std::string("parse error: ") + e.what());
    }
    if (!ok)
        throw LoadError(path, "parse error: " + (err.empty() ? std::string("unknown tinygltf failure") : trimmed(err)));

    Scene scene;
    scene.sourcePath = path;
    const gltf::Ctx ctx{path, model, scene, options, budget};
    if (!warn.empty()) ctx.warn("tinygltf: " + trimmed(warn));
    for (const auto& ext : model.extensionsRequired)
        if (!isSupportedExtension(ext)) ctx.fail("requires unsupported extension " + ext);

    try {
        gltf::decodeMeshoptViews(ctx, model);
        gltf::loadTextures(ctx);
        gltf::loadMaterials(ctx);
        gltf::loadVariantNames(ctx);
        gltf::loadMeshes(ctx);
        gltf::loadNodes(ctx);
        gltf::loadSkins(ctx);
        gltf::loadAnimations(ctx);
        gltf::placeScene(ctx);
    } catch (const LoadError&) {
        throw;
    } catch (const std::bad_alloc&) {
        throw LoadError(path, "out of memory while reading the geometry");
    }

    std::vector<std::string> ignored;
    for (const auto& ext : model.extensionsUsed)
        if (!isSupportedExtension(ext)) ignored.push_back(ext);
    if (!ignored.empty()) {
        std::string list;
        for (const auto& s : ignored) list += (list.empty() ? "" : ", ") + s;
        ctx.warn("ignored extensions (not supported): " + list);
    }
    return scene;
}

}  // namespace idk::scene
