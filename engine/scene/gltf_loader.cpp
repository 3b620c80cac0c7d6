// gltf_loader.cpp: glTF 2.0 (.gltf/.glb) -> Scene through tinygltf. Ports IDKEngine's ModelLoader at a basic
// level: triangle geometry (any accessor component type, sparse accessors, KHR_mesh_quantization), core PBR
// factors, KHR_materials_emissive_strength, base-colour texture references, the default scene's hierarchy,
// cameras and KHR_lights_punctual. Hostile input never crashes: every index and byte range is checked first.
#include "scene/gltf_loader.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <numeric>
#include <span>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <nlohmann/json.hpp>

#include "scene/tinygltf_include.hpp"

// Warnings also go to the engine log when idk_core provides it.
#if __has_include("core/log.hpp")
#include "core/log.hpp"
#define IDK_SCENE_HAS_CORE_LOG 1
#endif

namespace idk::scene {

LoadError::LoadError(const std::filesystem::path& file, const std::string& cause)
    : std::runtime_error(file.string() + ": " + cause), file_(file), cause_(cause) {}

bool isSupportedExtension(const std::string& name) {
    static const std::array<const char*, 4> kSupported = {"KHR_mesh_quantization", "KHR_lights_punctual",
                                                          "KHR_materials_emissive_strength", "KHR_texture_transform"};
    return std::any_of(kSupported.begin(), kSupported.end(), [&](const char* s) { return name == s; });
}

namespace {

constexpr uint32_t kGlbMagic = 0x46546C67;                 // "glTF"
constexpr uint32_t kGlbChunkJson = 0x4E4F534A;             // "JSON"
constexpr size_t kMaxFileBytes = size_t{0xFFFFFFFFu};      // tinygltf takes 32-bit sizes
constexpr size_t kMaxZeroAccessorCount = size_t{1} << 26;  // accessors without bufferView allocate count
constexpr int kMaxJsonDepth = 128;                         // glTF itself needs < 10; extras may nest a little

struct Ctx {
    const std::filesystem::path& file;
    const tinygltf::Model& model;
    Scene& scene;

    [[noreturn]] void fail(const std::string& cause) const { throw LoadError(file, cause); }

    void warn(const std::string& message) const {
        scene.warnings.push_back(message);
#ifdef IDK_SCENE_HAS_CORE_LOG
        core::logMessage(core::LogLevel::Warning, file.string() + ": " + message);
#endif
    }
};

std::string str(size_t v) {
    return std::to_string(v);
}

std::vector<uint8_t> readWholeFile(const std::filesystem::path& path) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) throw LoadError(path, "file not found");
    if (!std::filesystem::is_regular_file(path, ec)) throw LoadError(path, "not a regular file");
    const auto size = std::filesystem::file_size(path, ec);
    if (ec) throw LoadError(path, "cannot read file size: " + ec.message());
    if (size > kMaxFileBytes) throw LoadError(path, "file larger than 4 GiB");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw LoadError(path, "cannot open file");
    std::vector<uint8_t> bytes(static_cast<size_t>(size));
    if (size > 0 && !in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(size)))
        throw LoadError(path, "cannot read file");
    return bytes;
}

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

// Checks the JSON text before any parser builds a tree from it: nesting deeper than kMaxJsonDepth is rejected
// (tinygltf converts extras/extensions recursively, so a hostile file could overflow the stack), and a file that
// requires an extension we do not implement is rejected by name (tinygltf would otherwise fail on the
// extension's data, e.g. Draco primitives, with a less useful message).
void precheckJson(const std::filesystem::path& path, std::span<const uint8_t> bytes, bool binary) {
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
    if (json.is_discarded() || !json.is_object()) return;  // tinygltf reports the parse error
    const auto it = json.find("extensionsRequired");
    if (it == json.end() || !it->is_array()) return;
    for (const auto& ext : *it)
        if (ext.is_string() && !isSupportedExtension(ext.get<std::string>()))
            throw LoadError(path, "requires unsupported extension " + ext.get<std::string>());
}

// --- accessors ------------------------------------------------------------------------------------------

size_t componentSize(int componentType) {
    switch (componentType) {
        case TINYGLTF_COMPONENT_TYPE_BYTE:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
        case TINYGLTF_COMPONENT_TYPE_SHORT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
        default: return 0;  // INT (5124) and DOUBLE are not valid in glTF 2.0
    }
}

int componentCount(int type) {
    switch (type) {
        case TINYGLTF_TYPE_SCALAR: return 1;
        case TINYGLTF_TYPE_VEC2: return 2;
        case TINYGLTF_TYPE_VEC3: return 3;
        case TINYGLTF_TYPE_VEC4: return 4;
        default: return 0;  // matrices are never read as vertex data here
    }
}

// Elements of `count` items of `elementSize` bytes, `stride` apart, inside a validated byte range.
struct ByteRange {
    const uint8_t* base = nullptr;
    size_t stride = 0;
};

// Validates that bufferView `viewIndex` lies inside its buffer and that `count` elements starting at
// `byteOffset` with the given stride fit inside the view; returns a pointer to the first element.
ByteRange checkedRange(const Ctx& ctx, int viewIndex, size_t byteOffset, size_t count, size_t elementSize,
                       bool allowViewStride, const std::string& what) {
    const auto& model = ctx.model;
    if (viewIndex < 0 || size_t(viewIndex) >= model.bufferViews.size())
        ctx.fail(what + ": bufferView " + std::to_string(viewIndex) + " out of range (file has " +
                 str(model.bufferViews.size()) + ")");
    const auto& view = model.bufferViews[size_t(viewIndex)];
    if (view.buffer < 0 || size_t(view.buffer) >= model.buffers.size())
        ctx.fail(what + ": bufferView " + std::to_string(viewIndex) + " references buffer " +
                 std::to_string(view.buffer) + " out of range (file has " + str(model.buffers.size()) + ")");
    const auto& buffer = model.buffers[size_t(view.buffer)];
    if (view.byteOffset > buffer.data.size() || view.byteLength > buffer.data.size() - view.byteOffset)
        ctx.fail(what + ": bufferView " + std::to_string(viewIndex) + " (offset " + str(view.byteOffset) + ", length " +
                 str(view.byteLength) + ") extends past the end of buffer " + std::to_string(view.buffer) + " (" +
                 str(buffer.data.size()) + " bytes)");
    size_t stride = elementSize;
    if (allowViewStride && view.byteStride != 0) {
        if (view.byteStride < elementSize)
            ctx.fail(what + ": bufferView " + std::to_string(viewIndex) + " byteStride " + str(view.byteStride) +
                     " is smaller than the element size " + str(elementSize));
        stride = view.byteStride;
    }
    if (count > 0) {
        // Last byte read: byteOffset + (count - 1) * stride + elementSize, computed without overflow.
        const size_t limit = view.byteLength;
        const bool fits = byteOffset <= limit && elementSize <= limit - byteOffset &&
                          (count - 1) <= (limit - byteOffset - elementSize) / stride;
        if (!fits)
            ctx.fail(what + ": " + str(count) + " elements of " + str(elementSize) + " bytes (stride " + str(stride) +
                     ", offset " + str(byteOffset) + ") extend past the end of bufferView " +
                     std::to_string(viewIndex) + " (" + str(limit) + " bytes)");
    }
    return {buffer.data.data() + view.byteOffset + byteOffset, stride};
}

float decodeFloat(const uint8_t* p, int componentType, bool normalized) {
    switch (componentType) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT: {
            float f;
            std::memcpy(&f, p, 4);
            return f;
        }
        case TINYGLTF_COMPONENT_TYPE_BYTE: {
            int8_t v;
            std::memcpy(&v, p, 1);
            return normalized ? std::max(float(v) / 127.0f, -1.0f) : float(v);
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return normalized ? float(*p) / 255.0f : float(*p);
        case TINYGLTF_COMPONENT_TYPE_SHORT: {
            int16_t v;
            std::memcpy(&v, p, 2);
            return normalized ? std::max(float(v) / 32767.0f, -1.0f) : float(v);
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            uint16_t v;
            std::memcpy(&v, p, 2);
            return normalized ? float(v) / 65535.0f : float(v);
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
            uint32_t v;
            std::memcpy(&v, p, 4);
            return normalized ? float(double(v) / 4294967295.0) : float(v);
        }
        default: return 0.0f;
    }
}

uint32_t decodeUint(const uint8_t* p, int componentType) {
    switch (componentType) {
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return *p;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            uint16_t v;
            std::memcpy(&v, p, 2);
            return v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
            uint32_t v;
            std::memcpy(&v, p, 4);
            return v;
        }
        default: return 0;
    }
}

const tinygltf::Accessor& accessorAt(const Ctx& ctx, int index, const std::string& what) {
    if (index < 0 || size_t(index) >= ctx.model.accessors.size())
        ctx.fail(what + ": accessor " + std::to_string(index) + " out of range (file has " +
                 str(ctx.model.accessors.size()) + " accessors)");
    return ctx.model.accessors[size_t(index)];
}

// Reads an accessor as `components` floats per element (normalized integers are mapped to [0,1]/[-1,1],
// plain integers converted as is, as KHR_mesh_quantization allows), applying sparse substitution.
std::vector<float> readFloats(const Ctx& ctx, int index, int components, const std::string& usage) {
    const std::string what = usage + " (accessor " + std::to_string(index) + ")";
    const auto& acc = accessorAt(ctx, index, usage);
    if (componentCount(acc.type) != components)
        ctx.fail(what + ": type must have " + std::to_string(components) + " components");
    const size_t compSize = componentSize(acc.componentType);
    if (compSize == 0) ctx.fail(what + ": unsupported componentType " + std::to_string(acc.componentType));
    const size_t elementSize = compSize * size_t(components);
    const size_t n = size_t(components);

    std::vector<float> out;
    if (acc.bufferView < 0) {
        if (acc.count > kMaxZeroAccessorCount) ctx.fail(what + ": count " + str(acc.count) + " is too large");
        out.assign(acc.count * n, 0.0f);  // glTF: an accessor without bufferView is all zeros
    } else {
        const ByteRange range = checkedRange(ctx, acc.bufferView, acc.byteOffset, acc.count, elementSize, true, what);
        out.resize(acc.count * n);
        for (size_t i = 0; i < acc.count; ++i) {
            const uint8_t* e = range.base + i * range.stride;
            for (size_t c = 0; c < n; ++c)
                out[i * n + c] = decodeFloat(e + c * compSize, acc.componentType, acc.normalized);
        }
    }

    if (acc.sparse.isSparse) {
        const auto& sp = acc.sparse;
        if (sp.count < 0 || size_t(sp.count) > acc.count)
            ctx.fail(what + ": sparse count " + std::to_string(sp.count) + " exceeds the accessor count " +
                     str(acc.count));
        const size_t idxSize = componentSize(sp.indices.componentType);
        if (idxSize == 0 || sp.indices.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT ||
            sp.indices.componentType == TINYGLTF_COMPONENT_TYPE_BYTE ||
            sp.indices.componentType == TINYGLTF_COMPONENT_TYPE_SHORT)
            ctx.fail(what + ": sparse indices componentType " + std::to_string(sp.indices.componentType) +
                     " is invalid");
        if (sp.indices.byteOffset < 0 || sp.values.byteOffset < 0) ctx.fail(what + ": negative sparse byteOffset");
        const size_t count = size_t(sp.count);
        const ByteRange idx = checkedRange(ctx, sp.indices.bufferView, size_t(sp.indices.byteOffset), count, idxSize,
                                           false, what + " sparse indices");
        const ByteRange val = checkedRange(ctx, sp.values.bufferView, size_t(sp.values.byteOffset), count, elementSize,
                                           false, what + " sparse values");
        for (size_t i = 0; i < count; ++i) {
            const uint32_t target = decodeUint(idx.base + i * idx.stride, sp.indices.componentType);
            if (target >= acc.count)
                ctx.fail(what + ": sparse index " + std::to_string(target) + " out of range (count " + str(acc.count) +
                         ")");
            for (size_t c = 0; c < n; ++c)
                out[size_t(target) * n + c] =
                    decodeFloat(val.base + i * val.stride + c * compSize, acc.componentType, acc.normalized);
        }
    }
    return out;
}

std::vector<uint32_t> readIndices(const Ctx& ctx, int index, const std::string& usage) {
    const std::string what = usage + " (accessor " + std::to_string(index) + ")";
    const auto& acc = accessorAt(ctx, index, usage);
    if (acc.type != TINYGLTF_TYPE_SCALAR) ctx.fail(what + ": indices must be SCALAR");
    const int ct = acc.componentType;
    if (ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
        ctx.fail(what + ": indices componentType " + std::to_string(ct) + " is not an unsigned integer type");
    if (acc.sparse.isSparse) {
        // Rare for indices; reuse the float path (exact for values below 2^24) and convert.
        const auto values = readFloats(ctx, index, 1, usage);
        std::vector<uint32_t> out(values.size());
        for (size_t i = 0; i < values.size(); ++i) out[i] = uint32_t(values[i]);
        return out;
    }
    if (acc.bufferView < 0) {
        if (acc.count > kMaxZeroAccessorCount) ctx.fail(what + ": count " + str(acc.count) + " is too large");
        return std::vector<uint32_t>(acc.count, 0u);
    }
    const size_t size = componentSize(ct);
    const ByteRange range = checkedRange(ctx, acc.bufferView, acc.byteOffset, acc.count, size, true, what);
    std::vector<uint32_t> out(acc.count);
    for (size_t i = 0; i < acc.count; ++i) out[i] = decodeUint(range.base + i * range.stride, ct);
    return out;
}

template <int N>
std::vector<glm::vec<N, float>> toVectors(const std::vector<float>& flat) {
    std::vector<glm::vec<N, float>> out(flat.size() / N);
    for (size_t i = 0; i < out.size(); ++i)
        for (int c = 0; c < N; ++c) out[i][c] = flat[i * N + size_t(c)];
    return out;
}

// --- meshes ---------------------------------------------------------------------------------------------

const char* modeName(int mode) {
    switch (mode) {
        case TINYGLTF_MODE_POINTS: return "POINTS";
        case TINYGLTF_MODE_LINE: return "LINES";
        case TINYGLTF_MODE_LINE_LOOP: return "LINE_LOOP";
        case TINYGLTF_MODE_LINE_STRIP: return "LINE_STRIP";
        case TINYGLTF_MODE_TRIANGLES: return "TRIANGLES";
        case TINYGLTF_MODE_TRIANGLE_STRIP: return "TRIANGLE_STRIP";
        case TINYGLTF_MODE_TRIANGLE_FAN: return "TRIANGLE_FAN";
        default: return "unknown mode";
    }
}

// Turns strips and fans into a triangle list, with the vertex order the glTF spec gives (keeps the winding).
std::vector<uint32_t> triangulate(const std::vector<uint32_t>& v, int mode) {
    std::vector<uint32_t> out;
    if (mode == TINYGLTF_MODE_TRIANGLES) {
        out.assign(v.begin(), v.begin() + std::ptrdiff_t(v.size() - v.size() % 3));
    } else if (v.size() >= 3) {
        out.reserve((v.size() - 2) * 3);
        for (size_t i = 0; i + 2 < v.size(); ++i) {
            if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
                const bool odd = (i % 2) == 1;
                out.insert(out.end(), {v[i], v[odd ? i + 2 : i + 1], v[odd ? i + 1 : i + 2]});
            } else {  // fan
                out.insert(out.end(), {v[i + 1], v[i + 2], v[0]});
            }
        }
    }
    return out;
}

// Un-shares vertices so every triangle gets its own three vertices and its geometric normal.
void makeFlatNormals(Primitive& prim) {
    Primitive flat;
    flat.material = prim.material;
    const size_t n = prim.indices.size();
    flat.positions.resize(n);
    flat.normals.resize(n);
    if (!prim.uv0.empty()) flat.uv0.resize(n);
    flat.indices.resize(n);
    for (size_t t = 0; t + 2 < n; t += 3) {
        const glm::vec3 a = prim.positions[prim.indices[t]];
        const glm::vec3 b = prim.positions[prim.indices[t + 1]];
        const glm::vec3 c = prim.positions[prim.indices[t + 2]];
        const glm::vec3 cr = glm::cross(b - a, c - a);
        const float len = glm::length(cr);
        const glm::vec3 normal = (len > 0.0f && std::isfinite(len)) ? cr / len : glm::vec3(0.0f, 0.0f, 1.0f);
        for (size_t k = 0; k < 3; ++k) {
            flat.positions[t + k] = prim.positions[prim.indices[t + k]];
            flat.normals[t + k] = normal;
            if (!prim.uv0.empty()) flat.uv0[t + k] = prim.uv0[prim.indices[t + k]];
            flat.indices[t + k] = uint32_t(t + k);
        }
    }
    prim = std::move(flat);
}

void loadMeshes(const Ctx& ctx) {
    std::map<std::string, int> skippedModes;
    for (size_t m = 0; m < ctx.model.meshes.size(); ++m) {
        const auto& src = ctx.model.meshes[m];
        Mesh mesh;
        mesh.name = src.name;
        for (size_t p = 0; p < src.primitives.size(); ++p) {
            const auto& sp = src.primitives[p];
            const std::string where = "mesh " + str(m) + " primitive " + str(p);
            if (sp.mode != TINYGLTF_MODE_TRIANGLES && sp.mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
                sp.mode != TINYGLTF_MODE_TRIANGLE_FAN) {
                skippedModes[modeName(sp.mode)]++;
                continue;
            }
            const auto pos = sp.attributes.find("POSITION");
            if (pos == sp.attributes.end()) {
                ctx.warn(where + " has no POSITION attribute; skipped");
                continue;
            }
            Primitive prim;
            prim.positions = toVectors<3>(readFloats(ctx, pos->second, 3, where + " POSITION"));
            const size_t vertexCount = prim.positions.size();
            if (const auto it = sp.attributes.find("NORMAL"); it != sp.attributes.end()) {
                prim.normals = toVectors<3>(readFloats(ctx, it->second, 3, where + " NORMAL"));
                if (prim.normals.size() != vertexCount)
                    ctx.fail(where + ": NORMAL has " + str(prim.normals.size()) + " elements, POSITION has " +
                             str(vertexCount));
            }
            if (const auto it = sp.attributes.find("TEXCOORD_0"); it != sp.attributes.end()) {
                prim.uv0 = toVectors<2>(readFloats(ctx, it->second, 2, where + " TEXCOORD_0"));
                if (prim.uv0.size() != vertexCount)
                    ctx.fail(where + ": TEXCOORD_0 has " + str(prim.uv0.size()) + " elements, POSITION has " +
                             str(vertexCount));
            }
            std::vector<uint32_t> raw;
            if (sp.indices >= 0) {
                raw = readIndices(ctx, sp.indices, where + " indices");
            } else {
                raw.resize(vertexCount);
                std::iota(raw.begin(), raw.end(), 0u);
            }
            for (const uint32_t i : raw)
                if (i >= vertexCount)
                    ctx.fail(where + ": index " + std::to_string(i) + " out of range (" + str(vertexCount) +
                             " vertices)");
            if (sp.mode == TINYGLTF_MODE_TRIANGLES && raw.size() % 3 != 0)
                ctx.warn(where + ": " + str(raw.size()) + " indices is not a multiple of 3; the rest is ignored");
            prim.indices = triangulate(raw, sp.mode);
            if (sp.material >= 0) {
                if (size_t(sp.material) >= ctx.model.materials.size())
                    ctx.fail(where + ": material " + std::to_string(sp.material) + " out of range (file has " +
                             str(ctx.model.materials.size()) + ")");
                prim.material = uint32_t(sp.material);
            }
            if (prim.indices.empty()) {
                ctx.warn(where + " has no triangles; skipped");
                continue;
            }
            if (prim.normals.empty()) makeFlatNormals(prim);
            mesh.primitives.push_back(std::move(prim));
        }
        ctx.scene.meshes.push_back(std::move(mesh));
    }
    if (!skippedModes.empty()) {
        std::string list;
        for (const auto& [name, count] : skippedModes)
            list += (list.empty() ? "" : ", ") + name + " x" + std::to_string(count);
        ctx.warn("skipped primitives that are not triangles (" + list +
                 "); only triangle lists, strips and fans are loaded");
    }
}

// --- materials and textures -----------------------------------------------------------------------------

double numberOr(const tinygltf::Value& object, const char* key, double fallback) {
    if (!object.IsObject() || !object.Has(key)) return fallback;
    const auto& v = object.Get(key);
    return v.IsNumber() ? v.GetNumberAsDouble() : fallback;
}

glm::vec2 vec2Or(const tinygltf::Value& object, const char* key, glm::vec2 fallback) {
    if (!object.IsObject() || !object.Has(key)) return fallback;
    const auto& v = object.Get(key);
    if (!v.IsArray() || v.ArrayLen() != 2 || !v.Get(0).IsNumber() || !v.Get(1).IsNumber()) return fallback;
    return {float(v.Get(0).GetNumberAsDouble()), float(v.Get(1).GetNumberAsDouble())};
}

TextureRef textureRef(const Ctx& ctx, const tinygltf::TextureInfo& info, const std::string& where) {
    if (size_t(info.index) >= ctx.model.textures.size())
        ctx.fail(where + ": texture " + std::to_string(info.index) + " out of range (file has " +
                 str(ctx.model.textures.size()) + ")");
    TextureRef ref;
    ref.texture = uint32_t(info.index);
    ref.texCoord = uint32_t(std::max(info.texCoord, 0));
    if (const auto it = info.extensions.find("KHR_texture_transform"); it != info.extensions.end()) {
        const auto& t = it->second;
        ref.offset = vec2Or(t, "offset", glm::vec2(0.0f));
        ref.scale = vec2Or(t, "scale", glm::vec2(1.0f));
        ref.rotation = float(numberOr(t, "rotation", 0.0));
        const double texCoord = numberOr(t, "texCoord", double(ref.texCoord));
        ref.texCoord = texCoord >= 0.0 && texCoord < 8.0 ? uint32_t(texCoord) : ref.texCoord;
    }
    if (ref.texCoord != 0)
        ctx.warn(where + " uses TEXCOORD_" + std::to_string(ref.texCoord) + "; only TEXCOORD_0 is loaded");
    return ref;
}

template <int N>
glm::vec<N, float> factor(const std::vector<double>& v, glm::vec<N, float> fallback) {
    if (v.size() != size_t(N)) return fallback;
    glm::vec<N, float> out;
    for (int i = 0; i < N; ++i) out[i] = float(v[size_t(i)]);
    return out;
}

void loadMaterials(const Ctx& ctx) {
    for (size_t i = 0; i < ctx.model.materials.size(); ++i) {
        const auto& src = ctx.model.materials[i];
        const std::string where = "material " + str(i);
        Material mat;
        mat.name = src.name;
        const auto& pbr = src.pbrMetallicRoughness;
        mat.baseColorFactor = factor<4>(pbr.baseColorFactor, glm::vec4(1.0f));
        mat.metallic = float(pbr.metallicFactor);
        mat.roughness = float(pbr.roughnessFactor);
        float strength = 1.0f;
        if (const auto it = src.extensions.find("KHR_materials_emissive_strength"); it != src.extensions.end())
            strength = float(numberOr(it->second, "emissiveStrength", 1.0));
        mat.emissive = factor<3>(src.emissiveFactor, glm::vec3(0.0f)) * strength;
        if (src.alphaMode == "MASK")
            mat.alphaMode = AlphaMode::Mask;
        else if (src.alphaMode == "BLEND")
            mat.alphaMode = AlphaMode::Blend;
        else if (src.alphaMode != "OPAQUE")
            ctx.warn(where + ": unknown alphaMode '" + src.alphaMode + "', using OPAQUE");
        mat.alphaCutoff = float(src.alphaCutoff);
        mat.doubleSided = src.doubleSided;
        if (pbr.baseColorTexture.index >= 0)
            mat.baseColorTexture = textureRef(ctx, pbr.baseColorTexture, where + " baseColorTexture");
        ctx.scene.materials.push_back(std::move(mat));
    }
}

std::string percentDecode(const std::string& uri) {
    auto hex = [](char c) -> int {
        if (c >= '0' && c <= '9') return c - '0';
        if (c >= 'a' && c <= 'f') return c - 'a' + 10;
        if (c >= 'A' && c <= 'F') return c - 'A' + 10;
        return -1;
    };
    std::string out;
    for (size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] == '%' && i + 2 < uri.size() && hex(uri[i + 1]) >= 0 && hex(uri[i + 2]) >= 0) {
            out += char(hex(uri[i + 1]) * 16 + hex(uri[i + 2]));
            i += 2;
        } else {
            out += uri[i];
        }
    }
    return out;
}

void loadTextures(const Ctx& ctx) {
    const auto& model = ctx.model;
    for (size_t i = 0; i < model.images.size(); ++i) {
        const auto& src = model.images[i];
        Image img;
        img.name = src.name;
        img.mimeType = src.mimeType;
        if (src.bufferView >= 0) {
            const auto what = "image " + str(i);
            if (size_t(src.bufferView) >= model.bufferViews.size())
                ctx.fail(what + ": bufferView " + std::to_string(src.bufferView) + " out of range");
            const size_t length = model.bufferViews[size_t(src.bufferView)].byteLength;
            const ByteRange range = checkedRange(ctx, src.bufferView, 0, length, 1, false, what);
            img.encoded.assign(range.base, range.base + length);
        } else if (!src.image.empty()) {
            img.encoded = src.image;  // a data URI, kept encoded by the image callback
        } else if (!src.uri.empty()) {
            img.path = ctx.file.parent_path() / percentDecode(src.uri);
        }
        ctx.scene.images.push_back(std::move(img));
    }
    for (size_t i = 0; i < model.textures.size(); ++i) {
        const auto& src = model.textures[i];
        Texture tex;
        if (src.source >= 0) {
            if (size_t(src.source) >= model.images.size())
                ctx.fail("texture " + str(i) + ": image " + std::to_string(src.source) + " out of range (file has " +
                         str(model.images.size()) + ")");
            tex.image = uint32_t(src.source);
        }
        if (src.sampler >= 0) {
            if (size_t(src.sampler) >= model.samplers.size())
                ctx.fail("texture " + str(i) + ": sampler " + std::to_string(src.sampler) + " out of range (file has " +
                         str(model.samplers.size()) + ")");
            const auto& s = model.samplers[size_t(src.sampler)];
            tex.sampler = {s.magFilter, s.minFilter, s.wrapS, s.wrapT};
        }
        ctx.scene.textures.push_back(tex);
    }
}

// --- nodes, cameras, lights -----------------------------------------------------------------------------

void loadNodes(const Ctx& ctx) {
    const auto& model = ctx.model;
    auto& nodes = ctx.scene.nodes;
    nodes.resize(model.nodes.size());
    for (size_t i = 0; i < model.nodes.size(); ++i) {
        const auto& src = model.nodes[i];
        const std::string where = "node " + str(i);
        Node& node = nodes[i];
        node.name = src.name;
        if (!src.matrix.empty()) {
            if (src.matrix.size() != 16) ctx.fail(where + ": matrix must have 16 numbers");
            glm::mat4 m;
            for (int k = 0; k < 16; ++k) glm::value_ptr(m)[k] = float(src.matrix[size_t(k)]);  // column-major
            node.matrix = m;
        }
        if (!src.translation.empty()) {
            if (src.translation.size() != 3) ctx.fail(where + ": translation must have 3 numbers");
            node.translation = factor<3>(src.translation, glm::vec3(0.0f));
        }
        if (!src.rotation.empty()) {
            if (src.rotation.size() != 4) ctx.fail(where + ": rotation must have 4 numbers");
            const auto& r = src.rotation;  // glTF order x, y, z, w
            node.rotation = glm::quat(float(r[3]), float(r[0]), float(r[1]), float(r[2]));
        }
        if (!src.scale.empty()) {
            if (src.scale.size() != 3) ctx.fail(where + ": scale must have 3 numbers");
            node.scale = factor<3>(src.scale, glm::vec3(1.0f));
        }
        if (src.mesh >= 0) {
            if (size_t(src.mesh) >= model.meshes.size())
                ctx.fail(where + ": mesh " + std::to_string(src.mesh) + " out of range (file has " +
                         str(model.meshes.size()) + ")");
            node.mesh = uint32_t(src.mesh);
        }
        if (src.camera >= 0 && size_t(src.camera) >= model.cameras.size())
            ctx.fail(where + ": camera " + std::to_string(src.camera) + " out of range (file has " +
                     str(model.cameras.size()) + ")");
        for (const int child : src.children) {
            if (child < 0 || size_t(child) >= model.nodes.size())
                ctx.fail(where + ": child " + std::to_string(child) + " out of range (file has " +
                         str(model.nodes.size()) + ")");
            if (nodes[size_t(child)].parent || size_t(child) == i)
                ctx.fail(where + ": node " + std::to_string(child) +
                         " has more than one parent (the hierarchy must be a tree)");
            nodes[size_t(child)].parent = uint32_t(i);
            node.children.push_back(uint32_t(child));
        }
    }
}

glm::mat4 localMatrix(const Node& node) {
    if (node.matrix) return *node.matrix;
    return glm::translate(glm::mat4(1.0f), node.translation) * glm::mat4_cast(node.rotation) *
           glm::scale(glm::mat4(1.0f), node.scale);
}

// Visits `root` and its descendants depth-first (pre-order, children in file order) without recursion.
template <class F>
void forEachDescendant(std::vector<Node>& nodes, uint32_t root, F&& visit) {
    std::vector<uint32_t> stack{root};
    while (!stack.empty()) {
        const uint32_t n = stack.back();
        stack.pop_back();
        visit(n);
        const auto& children = nodes[n].children;
        for (auto it = children.rbegin(); it != children.rend(); ++it) stack.push_back(*it);
    }
}

void computeWorldMatrices(const Ctx& ctx) {
    auto& nodes = ctx.scene.nodes;
    size_t visited = 0;
    for (uint32_t i = 0; i < nodes.size(); ++i) {
        if (nodes[i].parent) continue;
        forEachDescendant(nodes, i, [&](uint32_t n) {
            const glm::mat4 parent = nodes[n].parent ? nodes[*nodes[n].parent].world : glm::mat4(1.0f);
            nodes[n].world = parent * localMatrix(nodes[n]);
            ++visited;
        });
    }
    if (visited != nodes.size()) ctx.fail("the node hierarchy contains a cycle");
}

// Rigid part of a node's world matrix: unit axes (scale removed), translation kept.
glm::mat4 rigid(const glm::mat4& m) {
    glm::mat4 r(1.0f);
    for (int c = 0; c < 3; ++c) {
        const glm::vec3 axis(m[c]);
        const float len = glm::length(axis);
        r[c] = glm::vec4(len > 0.0f ? axis / len : glm::vec3(c == 0, c == 1, c == 2), 0.0f);
    }
    r[3] = m[3];
    return r;
}

Camera makeCamera(const Ctx& ctx, const tinygltf::Camera& src, size_t index) {
    Camera cam;
    cam.name = src.name;
    const std::string where = "camera " + str(index);
    if (src.type == "orthographic") {
        const auto& o = src.orthographic;
        cam.type = CameraType::Orthographic;
        cam.xmag = float(o.xmag);
        cam.ymag = float(o.ymag);
        cam.znear = float(o.znear);
        cam.zfar = float(o.zfar);
        if (!(cam.xmag != 0.0f && cam.ymag != 0.0f && cam.znear >= 0.0f && cam.zfar > cam.znear)) {
            ctx.warn(where + ": invalid orthographic parameters; using xmag = ymag = 1, znear 0.01, zfar 100");
            cam.xmag = cam.ymag = 1.0f;
            cam.znear = 0.01f;
            cam.zfar = 100.0f;
        }
    } else {
        const auto& p = src.perspective;
        cam.yfov = float(p.yfov);
        cam.aspectRatio = float(p.aspectRatio);
        cam.znear = float(p.znear);
        cam.zfar = float(p.zfar);
        const float pi = 3.14159265f;
        if (!(cam.yfov > 0.0f && cam.yfov < pi && cam.znear > 0.0f && cam.aspectRatio >= 0.0f &&
              (cam.zfar == 0.0f || cam.zfar > cam.znear))) {
            ctx.warn(where + ": invalid perspective parameters; using yfov 45 degrees, znear 0.1, infinite far");
            cam.yfov = glm::radians(45.0f);
            cam.aspectRatio = 0.0f;
            cam.znear = 0.1f;
            cam.zfar = 0.0f;
        }
    }
    return cam;
}

bool makeLight(const Ctx& ctx, const tinygltf::Light& src, size_t index, Light& light) {
    light.name = src.name;
    if (src.type == "directional")
        light.type = LightType::Directional;
    else if (src.type == "point")
        light.type = LightType::Point;
    else if (src.type == "spot")
        light.type = LightType::Spot;
    else {
        ctx.warn("light " + str(index) + ": unknown type '" + src.type + "'; skipped");
        return false;
    }
    light.color = factor<3>(src.color, glm::vec3(1.0f));
    light.intensity = float(src.intensity);
    light.range = float(src.range);
    light.innerConeAngle = float(src.spot.innerConeAngle);
    light.outerConeAngle = float(src.spot.outerConeAngle);
    return true;
}

std::optional<size_t> nodeLightIndex(const Ctx& ctx, const tinygltf::Node& src, size_t nodeIndex) {
    const auto it = src.extensions.find("KHR_lights_punctual");
    if (it == src.extensions.end() || !it->second.IsObject() || !it->second.Has("light")) return std::nullopt;
    const auto& v = it->second.Get("light");
    const double d = v.IsNumber() ? v.GetNumberAsDouble() : -1.0;
    if (!(d >= 0.0 && d < double(ctx.model.lights.size())))
        ctx.fail("node " + str(nodeIndex) + ": KHR_lights_punctual light index out of range (file has " +
                 str(ctx.model.lights.size()) + " lights)");
    return size_t(d);
}

void placeDefaultScene(const Ctx& ctx) {
    const auto& model = ctx.model;
    auto& scene = ctx.scene;
    if (model.defaultScene >= 0 && size_t(model.defaultScene) >= model.scenes.size())
        ctx.fail("default scene " + std::to_string(model.defaultScene) + " out of range (file has " +
                 str(model.scenes.size()) + " scenes)");
    if (!model.scenes.empty()) {
        const auto& src = model.scenes[size_t(std::max(model.defaultScene, 0))];
        for (const int root : src.nodes) {
            if (root < 0 || size_t(root) >= scene.nodes.size())
                ctx.fail("scene root node " + std::to_string(root) + " out of range (file has " +
                         str(scene.nodes.size()) + ")");
            if (scene.nodes[size_t(root)].parent)
                ctx.fail("scene root node " + std::to_string(root) + " is a child of another node");
            if (std::find(scene.rootNodes.begin(), scene.rootNodes.end(), uint32_t(root)) == scene.rootNodes.end())
                scene.rootNodes.push_back(uint32_t(root));
        }
    } else {
        for (uint32_t i = 0; i < scene.nodes.size(); ++i)
            if (!scene.nodes[i].parent) scene.rootNodes.push_back(i);
    }

    for (const uint32_t root : scene.rootNodes) {
        forEachDescendant(scene.nodes, root, [&](uint32_t n) {
            Node& node = scene.nodes[n];
            const auto& src = model.nodes[n];
            if (node.mesh && !scene.meshes[*node.mesh].primitives.empty()) {
                scene.instances.push_back({*node.mesh, n, node.world});
                for (const auto& prim : scene.meshes[*node.mesh].primitives)
                    for (const auto& p : prim.positions)
                        scene.bounds.extend(glm::vec3(node.world * glm::vec4(p, 1.0f)));
            }
            if (src.camera >= 0) {
                Camera cam = makeCamera(ctx, model.cameras[size_t(src.camera)], size_t(src.camera));
                cam.world = rigid(node.world);
                cam.node = n;
                node.camera = uint32_t(scene.cameras.size());
                scene.cameras.push_back(std::move(cam));
            }
            if (const auto li = nodeLightIndex(ctx, src, n)) {
                Light light;
                if (makeLight(ctx, model.lights[*li], *li, light)) {
                    const glm::mat4 world = rigid(node.world);
                    light.position = glm::vec3(world[3]);
                    light.direction = -glm::vec3(world[2]);
                    light.node = n;
                    node.light = uint32_t(scene.lights.size());
                    scene.lights.push_back(std::move(light));
                }
            }
        });
    }
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

Scene loadGltf(const std::filesystem::path& path) {
    const std::vector<uint8_t> bytes = readWholeFile(path);
    return loadGltfFromMemory(bytes, path);
}

Scene loadGltfFromMemory(std::span<const uint8_t> bytes, const std::filesystem::path& path) {
    if (bytes.empty()) throw LoadError(path, "empty file");
    if (bytes.size() > kMaxFileBytes) throw LoadError(path, "larger than 4 GiB");
    const bool binary = bytes.size() >= 4 && readU32(bytes, 0) == kGlbMagic;
    if (binary) validateGlb(path, bytes);
    precheckJson(path, bytes, binary);

    tinygltf::TinyGLTF parser;
    parser.SetImageLoader(&recordImage, nullptr);
    tinygltf::Model model;
    std::string err, warn;
    const std::string baseDir = path.parent_path().string();
    bool ok = false;
    try {
        if (binary)
            ok = parser.LoadBinaryFromMemory(&model, &err, &warn, bytes.data(), unsigned(bytes.size()), baseDir);
        else
            ok = parser.LoadASCIIFromString(&model, &err, &warn, reinterpret_cast<const char*>(bytes.data()),
                                            unsigned(bytes.size()), baseDir);
    } catch (const std::exception& e) {
        throw LoadError(path, std::string("parse error: ") + e.what());
    }
    if (!ok)
        throw LoadError(path, "parse error: " + (err.empty() ? std::string("unknown tinygltf failure") : trimmed(err)));

    Scene scene;
    scene.sourcePath = path;
    const Ctx ctx{path, model, scene};
    if (!warn.empty()) ctx.warn("tinygltf: " + trimmed(warn));
    for (const auto& ext : model.extensionsRequired)
        if (!isSupportedExtension(ext)) ctx.fail("requires unsupported extension " + ext);

    try {
        loadTextures(ctx);
        loadMaterials(ctx);
        loadMeshes(ctx);
        loadNodes(ctx);
        computeWorldMatrices(ctx);
        placeDefaultScene(ctx);
    } catch (const LoadError&) {
        throw;
    } catch (const std::bad_alloc&) {
        throw LoadError(path, "out of memory while reading the geometry");
    }

    std::vector<std::string> ignored;
    for (const auto& ext : model.extensionsUsed)
        if (!isSupportedExtension(ext)) ignored.push_back("extension " + ext);
    if (!model.animations.empty()) ignored.push_back(str(model.animations.size()) + " animations");
    if (!model.skins.empty()) ignored.push_back(str(model.skins.size()) + " skins");
    const auto morphed = std::count_if(model.meshes.begin(), model.meshes.end(), [](const tinygltf::Mesh& m) {
        return std::any_of(m.primitives.begin(), m.primitives.end(), [](const auto& p) { return !p.targets.empty(); });
    });
    if (morphed > 0) ignored.push_back("morph targets in " + str(size_t(morphed)) + " meshes");
    if (!ignored.empty()) {
        std::string list;
        for (const auto& s : ignored) list += (list.empty() ? "" : ", ") + s;
        ctx.warn("not loaded yet: " + list);
    }
    return scene;
}

}  // namespace idk::scene
