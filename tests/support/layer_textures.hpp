// layer_textures.hpp: scenes/material_spheres.gltf with the factors of KHR_materials_specular, _clearcoat and
// _sheen moved into constant PNG textures (encoded in memory), for the tests of the extension textures in the
// rasterizer and the path tracers. quantizedSpheres(): the factors rounded to what an 8-bit texel holds (linear
// channels: code / 255; colours: the sRGB decode of the code), the factor-only reference; texturedSpheres(): the
// same materials with every such factor 1 and a 1x1 texture holding the code in the channel the extension
// reads, the other channels set to a decoy value so that reading the wrong channel shows. coatHalfSpheres():
// the clearcoat sphere's coat scaled by a 2x1 clearcoat texture (by default R 0 | 255: off on its -x half) over
// UVs made from the normals.
#pragma once
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <vector>

#include "scene/gltf_loader.hpp"
#include "scene/texture_decode.hpp"

namespace idk::test::layer_textures {

constexpr uint8_t kDecoy = 13;  // texel channels the extension must not read

inline std::vector<uint8_t> encodePng(uint32_t width, const std::vector<uint8_t>& rgba) {
    std::vector<unsigned char> encoded;
    OIIO::Filesystem::IOVecOutput memory(encoded);
    auto out = OIIO::ImageOutput::create("texture.png");
    if (!out || !out->set_ioproxy(&memory)) throw std::runtime_error("cannot encode a PNG in memory");
    OIIO::ImageSpec spec(int(width), 1, 4, OIIO::TypeDesc::UINT8);
    spec.attribute("oiio:UnassociatedAlpha", 1);  // straight alpha: the writer must not divide RGB by the decoy A
    bool ok = out->open("texture.png", spec) && out->write_image(OIIO::TypeDesc::UINT8, rgba.data());
    ok = out->close() && ok;
    if (!ok) throw std::runtime_error("PNG encoding failed: " + out->geterror());
    return encoded;
}

// A width x 1 RGBA8 texture (nearest, clamp-to-edge) appended to `s`; the reference to it.
inline scene::TextureRef addTexture(scene::Scene& s, const std::vector<std::array<uint8_t, 4>>& texels) {
    std::vector<uint8_t> rgba;
    for (const auto& t : texels) rgba.insert(rgba.end(), t.begin(), t.end());
    scene::Image image;
    image.name = "layer texture " + std::to_string(s.images.size());
    image.mimeType = "image/png";
    image.encoded = encodePng(uint32_t(texels.size()), rgba);
    s.images.push_back(std::move(image));
    scene::Texture texture;
    texture.image = uint32_t(s.images.size() - 1);
    texture.sampler = {9728, 9728, 33071, 33071};
    s.textures.push_back(texture);
    scene::TextureRef ref;
    ref.texture = uint32_t(s.textures.size() - 1);
    return ref;
}

inline uint8_t linearCode(float v) { return uint8_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)); }
inline float linearOf(uint8_t code) { return float(code) / 255.0f; }
inline uint8_t srgbCode(float v) {
    const double c = std::clamp(double(v), 0.0, 1.0);
    const double e = c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
    return uint8_t(std::lround(e * 255.0));
}
inline float srgbOf(uint8_t code) { return float(scene::srgbToLinearD(code / 255.0)); }

inline scene::Scene materialSpheres() {
    return scene::loadGltf(std::filesystem::path(IDK_SOURCE_DIR) / "scenes/material_spheres.gltf");
}

// The extension factors of material_spheres rounded to 8-bit texel values (colours through sRGB).
inline scene::Scene quantizedSpheres() {
    scene::Scene s = materialSpheres();
    for (scene::Material& m : s.materials) {
        m.specular = linearOf(linearCode(m.specular));
        for (int c = 0; c < 3; ++c) {
            m.specularColor[c] = srgbOf(srgbCode(m.specularColor[c]));
            m.sheenColor[c] = srgbOf(srgbCode(m.sheenColor[c]));
        }
        m.clearcoat = linearOf(linearCode(m.clearcoat));
        m.clearcoatRoughness = linearOf(linearCode(m.clearcoatRoughness));
        m.sheenRoughness = linearOf(linearCode(m.sheenRoughness));
    }
    return s;
}

// quantizedSpheres() with the factors of every material that uses an extension in textures (factors 1).
inline scene::Scene texturedSpheres() {
    scene::Scene s = quantizedSpheres();
    const scene::Scene source = materialSpheres();
    for (size_t i = 0; i < s.materials.size(); ++i) {
        scene::Material& m = s.materials[i];
        const scene::Material& f = source.materials[i];
        if (f.specular != 1.0f || f.specularColor != glm::vec3(1.0f)) {
            m.specularTexture = addTexture(s, {{kDecoy, kDecoy, kDecoy, linearCode(f.specular)}});
            m.specularColorTexture = addTexture(s, {{srgbCode(f.specularColor.r), srgbCode(f.specularColor.g),
                                                     srgbCode(f.specularColor.b), kDecoy}});
            m.specular = 1.0f;
            m.specularColor = glm::vec3(1.0f);
        }
        if (f.clearcoat > 0.0f) {
            m.clearcoatTexture = addTexture(s, {{linearCode(f.clearcoat), kDecoy, kDecoy, kDecoy}});
            m.clearcoatRoughnessTexture = addTexture(s, {{kDecoy, linearCode(f.clearcoatRoughness), kDecoy, kDecoy}});
            m.clearcoat = 1.0f;
            m.clearcoatRoughness = 1.0f;
        }
        if (f.sheenColor != glm::vec3(0.0f)) {
            m.sheenColorTexture = addTexture(
                s, {{srgbCode(f.sheenColor.r), srgbCode(f.sheenColor.g), srgbCode(f.sheenColor.b), kDecoy}});
            m.sheenRoughnessTexture = addTexture(s, {{kDecoy, kDecoy, kDecoy, linearCode(f.sheenRoughness)}});
            m.sheenColor = glm::vec3(1.0f);
            m.sheenRoughness = 1.0f;
        }
    }
    return s;
}

constexpr uint32_t kCoatMaterial = 2;  // clearcoat_paint

// UVs from the normals on the meshes of `material`: u = 0.25 on the -x side, 0.75 on the +x side.
inline void sideUvs(scene::Scene& s, uint32_t material) {
    for (scene::Mesh& mesh : s.meshes)
        for (scene::Primitive& p : mesh.primitives) {
            if (p.material != material) continue;
            p.uv0.resize(p.positions.size());
            for (size_t v = 0; v < p.positions.size(); ++v)
                p.uv0[v] = glm::vec2(p.normals[v].x < 0.0f ? 0.25f : 0.75f, 0.5f);
        }
}

// The clearcoat sphere's coat scaled by a 2x1 clearcoat texture (R = left | right) at the side UVs: by default
// coated on its +x half only.
inline scene::Scene coatHalfSpheres(uint8_t left = 0, uint8_t right = 255) {
    scene::Scene s = materialSpheres();
    sideUvs(s, kCoatMaterial);
    s.materials[kCoatMaterial].clearcoatTexture =
        addTexture(s, {{left, kDecoy, kDecoy, kDecoy}, {right, kDecoy, kDecoy, kDecoy}});
    return s;
}

}  // namespace idk::test::layer_textures
