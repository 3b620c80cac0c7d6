// gltf_materials.cpp: glTF images, textures and materials for the loader (the material half of IDKEngine's
// ModelLoader): images recorded (never decoded) with missing files and unknown formats flagged for the magenta
// placeholder; the full metallic-roughness material (every texture with texCoord and KHR_texture_transform,
// normal scale, occlusion strength) and KHR_materials_emissive_strength, _unlit, _transmission, _ior, _volume
// (the BSDF extensions: gltf_material_ext.cpp).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <fstream>

#include "scene/asset_uri.hpp"
#include "scene/gltf_internal.hpp"
#include "scene/texture_decode.hpp"

namespace idk::scene::gltf {

namespace {

// The glTF fields of a texture reference, from a tinygltf TextureInfo struct or from an extension's JSON.
struct TextureFields {
    int index = -1;
    int texCoord = 0;
    const tinygltf::Value* transform = nullptr;  // KHR_texture_transform object, if any
};

template <class Info>
TextureFields fieldsOf(const Info& info) {
    return {info.index, info.texCoord, extension(info.extensions, "KHR_texture_transform")};
}

std::optional<TextureFields> fieldsOf(const Ctx& ctx, const tinygltf::Value& object, const char* key,
                                      const std::string& where) {
    if (!object.IsObject() || !object.Has(key)) return std::nullopt;
    const auto& info = object.Get(key);
    if (!info.IsObject()) ctx.fail(where + ": " + key + " is not an object");
    const auto index = indexOr(ctx, info, "index", where + " " + key);
    if (!index) ctx.fail(where + ": " + key + " has no index");
    TextureFields f;
    f.index = int(std::min<uint32_t>(*index, uint32_t(INT32_MAX)));
    f.texCoord = int(indexOr(ctx, info, "texCoord", where + " " + key).value_or(0) & 0xFFFFu);
    if (info.Has("extensions") && info.Get("extensions").IsObject() &&
        info.Get("extensions").Has("KHR_texture_transform"))
        f.transform = &info.Get("extensions").Get("KHR_texture_transform");
    return f;
}

std::optional<TextureRef> textureRef(const Ctx& ctx, const TextureFields& f, const std::string& where) {
    if (f.index < 0) return std::nullopt;
    if (size_t(f.index) >= ctx.model.textures.size())
        ctx.fail(where + ": texture " + std::to_string(f.index) + " out of range (file has " +
                 str(ctx.model.textures.size()) + ")");
    TextureRef ref;
    ref.texture = uint32_t(f.index);
    ref.texCoord = uint32_t(std::max(f.texCoord, 0));
    if (f.transform != nullptr) {
        const auto& t = *f.transform;
        ref.offset = vec2Or(t, "offset", glm::vec2(0.0f));
        ref.scale = vec2Or(t, "scale", glm::vec2(1.0f));
        ref.rotation = float(numberOr(t, "rotation", 0.0));
        const double texCoord = numberOr(t, "texCoord", double(ref.texCoord));
        ref.texCoord = texCoord >= 0.0 && texCoord < 8.0 ? uint32_t(texCoord) : ref.texCoord;
    }
    if (ref.texCoord > 1) {
        ctx.warn(where + " uses TEXCOORD_" + std::to_string(ref.texCoord) +
                 "; only TEXCOORD_0 and TEXCOORD_1 are loaded, using TEXCOORD_0");
        ref.texCoord = 0;
    }
    return ref;
}

float finiteOr(double v, float fallback) {
    return std::isfinite(v) ? float(v) : fallback;
}

// Whether the first bytes are an image format a decoder can know (not a guarantee that it decodes).
bool knownImageSignature(const uint8_t* b, size_t n) {
    auto starts = [&](std::initializer_list<uint8_t> sig) {
        return n >= sig.size() && std::equal(sig.begin(), sig.end(), b);
    };
    return starts({0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A}) || starts({0xFF, 0xD8, 0xFF}) ||
           starts({0xAB, 'K', 'T', 'X', ' ', '2', '0', 0xBB}) || starts({0xAB, 'K', 'T', 'X', ' ', '1', '1', 0xBB}) ||
           (starts({'R', 'I', 'F', 'F'}) && n >= 12 && std::memcmp(b + 8, "WEBP", 4) == 0) ||
           starts({'G', 'I', 'F', '8'}) || starts({'B', 'M'}) || starts({'#', '?'}) ||
           starts({0x76, 0x2F, 0x31, 0x01}) || starts({'D', 'D', 'S', ' '});
}

void checkImage(const Ctx& ctx, Image& img, size_t index) {
    const std::string what = "image " + str(index) + (img.name.empty() ? "" : " '" + img.name + "'");
    if (!img.path.empty()) {
        std::array<uint8_t, 16> head{};
        std::ifstream in(img.path, std::ios::binary);
        std::error_code ec;
        if (!in || !std::filesystem::is_regular_file(img.path, ec)) {
            img.status = ImageStatus::Missing;
            ctx.warn(what + ": file " + img.path.string() + " not found; it will be drawn as the magenta placeholder");
            return;
        }
        in.read(reinterpret_cast<char*>(head.data()), std::streamsize(head.size()));
        const auto got = size_t(in.gcount());
        const std::string ext = img.path.extension().string();
        if (!knownImageSignature(head.data(), got) && ext != ".tga" && ext != ".TGA")
            img.status = ImageStatus::UnknownFormat;
    } else if (!knownImageSignature(img.encoded.data(), img.encoded.size())) {
        img.status = ImageStatus::UnknownFormat;
    }
    if (img.status == ImageStatus::UnknownFormat)
        ctx.warn(what + ": not a known image format; it will be drawn as the magenta placeholder");
}

// LoadOptions::maxMemoryBytes: a PNG/JPEG image is charged its decoded size (RGBA8 with mips) from the size
// its header declares, so a scene whose images would not fit fails here, before any is decoded. Other formats
// are not charged (their decoder still refuses sizes above the texel limit).
void chargeDecodedSize(const Ctx& ctx, const Image& img, size_t index) {
    if (ctx.options.maxMemoryBytes == 0 || img.status != ImageStatus::Ok) return;
    std::vector<uint8_t> head;
    if (!img.path.empty()) {
        head.resize(size_t{1} << 20);  // a JPEG frame header may follow large EXIF/ICC segments
        std::ifstream in(img.path, std::ios::binary);
        in.read(reinterpret_cast<char*>(head.data()), std::streamsize(head.size()));
        head.resize(size_t(in.gcount()));
    }
    const auto size = declaredImageSize(img.path.empty() ? img.encoded : head);
    if (!size) return;
    ctx.charge(decodedTextureBytes(size->width, size->height),
               "image " + str(index) + " (" + std::to_string(size->width) + "x" + std::to_string(size->height) +
                   " texels, decoded with mips)");
}

}  // namespace

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
            if (isDataUri(src.uri))
                img.status = ImageStatus::UnknownFormat;  // a data URI tinygltf could not decode
            else
                img.path = resolveAssetUri(ctx.file, src.uri, ctx.options.allowExternalUris, "image " + str(i));
        }
        if (img.status == ImageStatus::Ok) {
            checkImage(ctx, img, i);
            chargeDecodedSize(ctx, img, i);
        }
        else
            ctx.warn("image " + str(i) + ": undecodable data URI; it will be drawn as the magenta placeholder");
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
        if (const auto* ext = extension(src.extensions, "KHR_materials_emissive_strength"))
            mat.emissiveStrength = std::max(finiteOr(numberOr(*ext, "emissiveStrength", 1.0), 1.0f), 0.0f);
        mat.emissive = factor<3>(src.emissiveFactor, glm::vec3(0.0f)) * mat.emissiveStrength;
        if (src.alphaMode == "MASK")
            mat.alphaMode = AlphaMode::Mask;
        else if (src.alphaMode == "BLEND")
            mat.alphaMode = AlphaMode::Blend;
        else if (src.alphaMode != "OPAQUE")
            ctx.warn(where + ": unknown alphaMode '" + src.alphaMode + "', using OPAQUE");
        mat.alphaCutoff = float(src.alphaCutoff);
        mat.doubleSided = src.doubleSided;
        mat.baseColorTexture = textureRef(ctx, fieldsOf(pbr.baseColorTexture), where + " baseColorTexture");
        mat.metallicRoughnessTexture =
            textureRef(ctx, fieldsOf(pbr.metallicRoughnessTexture), where + " metallicRoughnessTexture");
        mat.normalTexture = textureRef(ctx, fieldsOf(src.normalTexture), where + " normalTexture");
        mat.normalScale = finiteOr(src.normalTexture.scale, 1.0f);
        mat.occlusionTexture = textureRef(ctx, fieldsOf(src.occlusionTexture), where + " occlusionTexture");
        mat.occlusionStrength = std::clamp(finiteOr(src.occlusionTexture.strength, 1.0f), 0.0f, 1.0f);
        mat.emissiveTexture = textureRef(ctx, fieldsOf(src.emissiveTexture), where + " emissiveTexture");

        mat.unlit = extension(src.extensions, "KHR_materials_unlit") != nullptr;
        if (const auto* ext = extension(src.extensions, "KHR_materials_transmission")) {
            const std::string w = where + " KHR_materials_transmission";
            mat.transmission = std::clamp(finiteOr(numberOr(*ext, "transmissionFactor", 0.0), 0.0f), 0.0f, 1.0f);
            if (const auto f = fieldsOf(ctx, *ext, "transmissionTexture", w))
                mat.transmissionTexture = textureRef(ctx, *f, w + " transmissionTexture");
        }
        if (const auto* ext = extension(src.extensions, "KHR_materials_ior")) {
            mat.ior = finiteOr(numberOr(*ext, "ior", 1.5), 1.5f);
            if (mat.ior != 0.0f && mat.ior < 1.0f) {  // 0 is allowed by the spec (infinite IOR, a mirror)
                ctx.warn(where + ": KHR_materials_ior ior " + std::to_string(mat.ior) + " < 1; using 1.5");
                mat.ior = 1.5f;
            }
        }
        if (const auto* ext = extension(src.extensions, "KHR_materials_volume")) {
            const std::string w = where + " KHR_materials_volume";
            mat.thickness = std::max(finiteOr(numberOr(*ext, "thicknessFactor", 0.0), 0.0f), 0.0f);
            if (const auto f = fieldsOf(ctx, *ext, "thicknessTexture", w))
                mat.thicknessTexture = textureRef(ctx, *f, w + " thicknessTexture");
            const double distance = numberOr(*ext, "attenuationDistance", 0.0);
            if (distance > 0.0 && std::isfinite(distance)) mat.attenuationDistance = float(distance);
            mat.attenuationColor = glm::clamp(vec3Or(*ext, "attenuationColor", glm::vec3(1.0f)), 0.0f, 1.0f);
        }
        loadMaterialExtensions(ctx, src, where + (src.name.empty() ? "" : " '" + src.name + "'"), mat);
        ctx.scene.materials.push_back(std::move(mat));
    }
}

std::optional<TextureRef> extensionTextureRef(const Ctx& ctx, const tinygltf::Value& object, const char* key,
                                              const std::string& where) {
    const auto f = fieldsOf(ctx, object, key, where);
    return f ? textureRef(ctx, *f, where + " " + key) : std::nullopt;
}

}  // namespace idk::scene::gltf
