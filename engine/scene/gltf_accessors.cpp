// gltf_accessors.cpp: validated reading of glTF accessors for the loader (IDKEngine's ModelLoader reads them
// through SharpGLTF): byte ranges checked against bufferViews and buffers, every component type with normalized
// and unnormalized integers (KHR_mesh_quantization), sparse substitution, MAT4; plus the JSON value helpers for
// extension objects and the load context's warn().
#include <algorithm>
#include <cstring>

#include "scene/gltf_internal.hpp"

// Warnings also go to the engine log when idk_core provides it.
#if __has_include("core/log.hpp")
#include "core/log.hpp"
#define IDK_SCENE_HAS_CORE_LOG 1
#endif

namespace idk::scene::gltf {

void Ctx::warn(const std::string& message) const {
    scene.warnings.push_back(message);
#ifdef IDK_SCENE_HAS_CORE_LOG
    core::logMessage(core::LogLevel::Warning, file.string() + ": " + message);
#endif
}

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
        case TINYGLTF_TYPE_MAT4: return 16;
        default: return 0;  // MAT2/MAT3 (column padding) are never vertex or animation data
    }
}

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

namespace {

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

}  // namespace

const tinygltf::Accessor& accessorAt(const Ctx& ctx, int index, const std::string& what) {
    if (index < 0 || size_t(index) >= ctx.model.accessors.size())
        ctx.fail(what + ": accessor " + std::to_string(index) + " out of range (file has " +
                 str(ctx.model.accessors.size()) + " accessors)");
    return ctx.model.accessors[size_t(index)];
}

std::vector<float> readAnyFloats(const Ctx& ctx, int index, const std::string& usage, int* components) {
    const std::string what = usage + " (accessor " + std::to_string(index) + ")";
    const auto& acc = accessorAt(ctx, index, usage);
    const int comps = componentCount(acc.type);
    if (comps == 0) ctx.fail(what + ": unsupported accessor type " + std::to_string(acc.type));
    const size_t compSize = componentSize(acc.componentType);
    if (compSize == 0) ctx.fail(what + ": unsupported componentType " + std::to_string(acc.componentType));
    if (comps == 16 && acc.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT)
        ctx.fail(what + ": MAT4 accessors must be FLOAT");
    *components = comps;
    const size_t n = size_t(comps);
    const size_t elementSize = compSize * n;

    std::vector<float> out;
    if (acc.bufferView < 0) {
        if (acc.count > kMaxZeroAccessorCount) ctx.fail(what + ": count " + str(acc.count) + " is too large");
        ctx.charge(uint64_t(acc.count) * n * sizeof(float), what);
        out.assign(acc.count * n, 0.0f);  // glTF: an accessor without bufferView is all zeros
    } else {
        const ByteRange range = checkedRange(ctx, acc.bufferView, acc.byteOffset, acc.count, elementSize, true, what);
        ctx.charge(uint64_t(acc.count) * n * sizeof(float), what);
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

std::vector<float> readFloats(const Ctx& ctx, int index, int components, const std::string& usage) {
    const auto& acc = accessorAt(ctx, index, usage);
    if (componentCount(acc.type) != components)
        ctx.fail(usage + " (accessor " + std::to_string(index) + "): type must have " + std::to_string(components) +
                 " components");
    int comps = 0;
    return readAnyFloats(ctx, index, usage, &comps);
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
        ctx.charge(uint64_t(acc.count) * sizeof(uint32_t), what);
        return std::vector<uint32_t>(acc.count, 0u);
    }
    const size_t size = componentSize(ct);
    const ByteRange range = checkedRange(ctx, acc.bufferView, acc.byteOffset, acc.count, size, true, what);
    ctx.charge(uint64_t(acc.count) * sizeof(uint32_t), what);
    std::vector<uint32_t> out(acc.count);
    for (size_t i = 0; i < acc.count; ++i) out[i] = decodeUint(range.base + i * range.stride, ct);
    return out;
}


// --- JSON values ----------------------------------------------------------------------------------------------

double numberOr(const tinygltf::Value& object, const char* key, double fallback) {
    if (!object.IsObject() || !object.Has(key)) return fallback;
    const auto& v = object.Get(key);
    return v.IsNumber() ? v.GetNumberAsDouble() : fallback;
}

namespace {
template <int N>
glm::vec<N, float> vecOr(const tinygltf::Value& object, const char* key, glm::vec<N, float> fallback) {
    if (!object.IsObject() || !object.Has(key)) return fallback;
    const auto& v = object.Get(key);
    if (!v.IsArray() || v.ArrayLen() != size_t(N)) return fallback;
    glm::vec<N, float> out;
    for (int i = 0; i < N; ++i) {
        if (!v.Get(i).IsNumber()) return fallback;
        out[i] = float(v.Get(i).GetNumberAsDouble());
    }
    return out;
}
}  // namespace

glm::vec2 vec2Or(const tinygltf::Value& object, const char* key, glm::vec2 fallback) {
    return vecOr<2>(object, key, fallback);
}
glm::vec3 vec3Or(const tinygltf::Value& object, const char* key, glm::vec3 fallback) {
    return vecOr<3>(object, key, fallback);
}

std::optional<uint32_t> indexOr(const Ctx& ctx, const tinygltf::Value& object, const char* key,
                                const std::string& where) {
    if (!object.IsObject() || !object.Has(key)) return std::nullopt;
    const auto& v = object.Get(key);
    const double d = v.IsNumber() ? v.GetNumberAsDouble() : -1.0;
    if (!(d >= 0.0 && d < 4294967296.0) || d != double(uint64_t(d)))
        ctx.fail(where + ": '" + key + "' is not a valid index");
    return uint32_t(d);
}

const tinygltf::Value* extension(const tinygltf::ExtensionMap& map, const char* name) {
    const auto it = map.find(name);
    return it == map.end() ? nullptr : &it->second;
}

}  // namespace idk::scene::gltf
