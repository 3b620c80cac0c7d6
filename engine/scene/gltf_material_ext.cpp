// gltf_material_ext.cpp: the BSDF material extensions of the loader: KHR_materials_specular, _clearcoat, _sheen,
// _anisotropy, _iridescence (iridescenceTexture R, iridescenceThicknessTexture G; factor [0, 1], film IOR [1, 4],
// thicknesses in nanometres [0, 1e5]), _diffuse_transmission, _dispersion.
// Untrusted input: every factor is checked for type and finiteness and clamped to the range the specification
// gives (out-of-range values warn, naming the material). Their textures (specularTexture A, specularColorTexture
// sRGB RGB, clearcoatTexture R, clearcoatRoughnessTexture G, sheenColorTexture sRGB RGB, sheenRoughnessTexture A)
// become TextureRefs with texCoord and KHR_texture_transform like the core ones; a reference without an index or
// out of range warns and is dropped (the factor alone is used). clearcoatNormalTexture (with its scale) gives the
// coat its own shading normal. anisotropyTexture: RG the direction in tangent space ([0, 1] -> [-1, 1], turned by
// anisotropyRotation), B scales the strength.
// KHR_materials_diffuse_transmission: diffuseTransmissionFactor and
// diffuseTransmissionColorFactor clamped to [0, 1]; diffuseTransmissionTexture A, diffuseTransmissionColorTexture
// sRGB RGB. KHR_materials_dispersion: dispersion (20 / Abbe number) >= 0, capped at 100 (an Abbe number of 0.2,
// far beyond any real glass) so that hostile values keep the IOR formula finite.
#include <algorithm>
#include <cmath>

#include "scene/gltf_internal.hpp"

namespace idk::scene::gltf {

namespace {

// A number property in [lo, hi]; non-numbers, non-finite values and values outside the range warn and are
// replaced (clamped when finite).
float rangedNumber(const Ctx& ctx, const tinygltf::Value& ext, const char* key, float fallback, float lo, float hi,
                   const std::string& where) {
    if (!ext.Has(key)) return fallback;
    const tinygltf::Value& v = ext.Get(key);
    if (!v.IsNumber()) {
        ctx.warn(where + ": " + key + " is not a number; using " + std::to_string(fallback));
        return fallback;
    }
    const double d = v.GetNumberAsDouble();
    if (!std::isfinite(d)) {
        ctx.warn(where + ": " + key + " is not finite; using " + std::to_string(fallback));
        return fallback;
    }
    const double clamped = std::clamp(d, double(lo), double(hi));
    if (clamped != d) ctx.warn(where + ": " + key + " " + std::to_string(d) + " out of range; clamped");
    return float(clamped);
}

// A colour (3 numbers) with each channel clamped to [lo, hi].
glm::vec3 rangedColor(const Ctx& ctx, const tinygltf::Value& ext, const char* key, glm::vec3 fallback, float lo,
                      float hi, const std::string& where) {
    if (!ext.Has(key)) return fallback;
    const tinygltf::Value& v = ext.Get(key);
    if (!v.IsArray() || v.ArrayLen() != 3) {
        ctx.warn(where + ": " + key + " is not an array of 3 numbers; using the default");
        return fallback;
    }
    glm::vec3 out = fallback;
    for (int i = 0; i < 3; ++i) {
        const tinygltf::Value& c = v.Get(i);
        const double d = c.IsNumber() ? c.GetNumberAsDouble() : std::nan("");
        if (!std::isfinite(d)) {
            ctx.warn(where + ": " + key + " has a non-finite or non-number component; using the default");
            return fallback;
        }
        const double clamped = std::clamp(d, double(lo), double(hi));
        if (clamped != d) ctx.warn(where + ": " + key + " component " + std::to_string(d) + " out of range; clamped");
        out[i] = float(clamped);
    }
    return out;
}

// A texture reference is checked (an object with an index inside the file's textures); bad ones warn and are
// dropped, so that a broken extension texture never rejects a file whose core material is fine.
bool validTextureInfo(const Ctx& ctx, const tinygltf::Value& ext, const char* key, const std::string& where) {
    if (!ext.Has(key)) return false;
    const tinygltf::Value& info = ext.Get(key);
    const auto index = info.IsObject() ? indexOr(ctx, info, "index", where + " " + key) : std::nullopt;
    if (!index) {
        ctx.warn(where + ": " + key + " has no texture index; ignored");
        return false;
    }
    if (*index >= ctx.model.textures.size()) {
        ctx.warn(where + ": " + key + " names texture " + std::to_string(*index) + " but the file has " +
                 str(ctx.model.textures.size()) + "; ignored");
        return false;
    }
    return true;
}

std::optional<TextureRef> extTexture(const Ctx& ctx, const tinygltf::Value& ext, const char* key,
                                     const std::string& where) {
    if (!validTextureInfo(ctx, ext, key, where)) return std::nullopt;
    return extensionTextureRef(ctx, ext, key, where);
}

}  // namespace

void loadMaterialExtensions(const Ctx& ctx, const tinygltf::Material& src, const std::string& where, Material& mat) {
    if (const auto* ext = extension(src.extensions, "KHR_materials_specular"); ext && ext->IsObject()) {
        const std::string w = where + " KHR_materials_specular";
        mat.specular = rangedNumber(ctx, *ext, "specularFactor", 1.0f, 0.0f, 1.0f, w);
        // The specification allows colours above 1 (f0 is clamped to 1 after the IOR's f0 scales it); cap at a
        // value no real IOR needs so that hostile files cannot make the maths overflow.
        mat.specularColor = rangedColor(ctx, *ext, "specularColorFactor", glm::vec3(1.0f), 0.0f, 1000.0f, w);
        mat.specularTexture = extTexture(ctx, *ext, "specularTexture", w);
        mat.specularColorTexture = extTexture(ctx, *ext, "specularColorTexture", w);
    }
    if (const auto* ext = extension(src.extensions, "KHR_materials_clearcoat"); ext && ext->IsObject()) {
        const std::string w = where + " KHR_materials_clearcoat";
        mat.clearcoat = rangedNumber(ctx, *ext, "clearcoatFactor", 0.0f, 0.0f, 1.0f, w);
        mat.clearcoatRoughness = rangedNumber(ctx, *ext, "clearcoatRoughnessFactor", 0.0f, 0.0f, 1.0f, w);
        mat.clearcoatTexture = extTexture(ctx, *ext, "clearcoatTexture", w);
        mat.clearcoatRoughnessTexture = extTexture(ctx, *ext, "clearcoatRoughnessTexture", w);
        mat.clearcoatNormalTexture = extTexture(ctx, *ext, "clearcoatNormalTexture", w);
        if (mat.clearcoatNormalTexture)  // a normalTextureInfo: its scale multiplies the map's xy
            mat.clearcoatNormalScale = rangedNumber(ctx, ext->Get("clearcoatNormalTexture"), "scale", 1.0f, -1.0e4f,
                                                    1.0e4f, w + " clearcoatNormalTexture");
    }
    if (const auto* ext = extension(src.extensions, "KHR_materials_sheen"); ext && ext->IsObject()) {
        const std::string w = where + " KHR_materials_sheen";
        mat.sheenColor = rangedColor(ctx, *ext, "sheenColorFactor", glm::vec3(0.0f), 0.0f, 1.0f, w);
        mat.sheenRoughness = rangedNumber(ctx, *ext, "sheenRoughnessFactor", 0.0f, 0.0f, 1.0f, w);
        mat.sheenColorTexture = extTexture(ctx, *ext, "sheenColorTexture", w);
        mat.sheenRoughnessTexture = extTexture(ctx, *ext, "sheenRoughnessTexture", w);
    }
    if (const auto* ext = extension(src.extensions, "KHR_materials_anisotropy"); ext && ext->IsObject()) {
        const std::string w = where + " KHR_materials_anisotropy";
        mat.anisotropyStrength = rangedNumber(ctx, *ext, "anisotropyStrength", 0.0f, 0.0f, 1.0f, w);
        // Any finite angle is valid (radians); a bound keeps sin/cos accurate in float.
        mat.anisotropyRotation = rangedNumber(ctx, *ext, "anisotropyRotation", 0.0f, -1.0e4f, 1.0e4f, w);
        mat.anisotropyTexture = extTexture(ctx, *ext, "anisotropyTexture", w);
    }
    if (const auto* ext = extension(src.extensions, "KHR_materials_iridescence"); ext && ext->IsObject()) {
        const std::string w = where + " KHR_materials_iridescence";
        mat.iridescence = rangedNumber(ctx, *ext, "iridescenceFactor", 0.0f, 0.0f, 1.0f, w);
        // The specification asks for an IOR >= 1; above 4 no thin film exists and the BSDF's Fresnel maths is
        // not meant for it. Thicknesses are nanometres >= 0; 100 um bounds what hostile files can ask for.
        mat.iridescenceIor = rangedNumber(ctx, *ext, "iridescenceIor", 1.3f, 1.0f, 4.0f, w);
        mat.iridescenceThicknessMin = rangedNumber(ctx, *ext, "iridescenceThicknessMinimum", 100.0f, 0.0f, 1.0e5f, w);
        mat.iridescenceThicknessMax = rangedNumber(ctx, *ext, "iridescenceThicknessMaximum", 400.0f, 0.0f, 1.0e5f, w);
        mat.iridescenceTexture = extTexture(ctx, *ext, "iridescenceTexture", w);
        mat.iridescenceThicknessTexture = extTexture(ctx, *ext, "iridescenceThicknessTexture", w);
    }
    if (const auto* ext = extension(src.extensions, "KHR_materials_diffuse_transmission"); ext && ext->IsObject()) {
        const std::string w = where + " KHR_materials_diffuse_transmission";
        mat.diffuseTransmission = rangedNumber(ctx, *ext, "diffuseTransmissionFactor", 0.0f, 0.0f, 1.0f, w);
        mat.diffuseTransmissionColor =
            rangedColor(ctx, *ext, "diffuseTransmissionColorFactor", glm::vec3(1.0f), 0.0f, 1.0f, w);
        mat.diffuseTransmissionTexture = extTexture(ctx, *ext, "diffuseTransmissionTexture", w);
        mat.diffuseTransmissionColorTexture = extTexture(ctx, *ext, "diffuseTransmissionColorTexture", w);
    }
    if (const auto* ext = extension(src.extensions, "KHR_materials_dispersion"); ext && ext->IsObject()) {
        const std::string w = where + " KHR_materials_dispersion";
        mat.dispersion = rangedNumber(ctx, *ext, "dispersion", 0.0f, 0.0f, 100.0f, w);
    }
}

}  // namespace idk::scene::gltf
