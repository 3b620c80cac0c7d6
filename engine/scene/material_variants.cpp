// material_variants.cpp: KHR_materials_variants, the loader half (the file's variant names and each primitive's
// (variant, material) mappings, untrusted: bad indices warn and are skipped) and applyMaterialVariant, which
// `idk render --variant NAME` calls before rendering.
#include <stdexcept>

#include "scene/gltf_internal.hpp"

namespace idk::scene {

void applyMaterialVariant(Scene& scene, const std::string& name) {
    uint32_t variant = 0;
    while (variant < scene.variantNames.size() && scene.variantNames[variant] != name) ++variant;
    if (variant == scene.variantNames.size()) {
        std::string list;
        for (const std::string& v : scene.variantNames) list += (list.empty() ? "'" : ", '") + v + "'";
        throw std::invalid_argument("no material variant '" + name + "' in " + scene.sourcePath.string() +
                                    (list.empty() ? " (the file defines no KHR_materials_variants)"
                                                  : "; its variants: " + list));
    }
    for (Mesh& mesh : scene.meshes)
        for (Primitive& prim : mesh.primitives)
            for (const auto& [v, material] : prim.variantMaterials)
                if (v == variant && material < scene.materials.size()) prim.material = material;
}

namespace gltf {

void loadVariantNames(const Ctx& ctx) {
    const auto* ext = extension(ctx.model.extensions, "KHR_materials_variants");
    if (ext == nullptr || !ext->IsObject() || !ext->Has("variants")) return;
    const tinygltf::Value& list = ext->Get("variants");
    if (!list.IsArray()) {
        ctx.warn("KHR_materials_variants: variants is not an array; ignored");
        return;
    }
    for (size_t i = 0; i < list.ArrayLen(); ++i) {
        const tinygltf::Value& v = list.Get(int(i));
        const bool named = v.IsObject() && v.Has("name") && v.Get("name").IsString();
        if (!named) ctx.warn("KHR_materials_variants: variant " + str(i) + " has no name; called 'variant " + str(i) + "'");
        ctx.scene.variantNames.push_back(named ? v.Get("name").Get<std::string>() : "variant " + str(i));
    }
}

void loadVariantMappings(const Ctx& ctx, const tinygltf::ExtensionMap& extensions, Primitive& prim,
                         const std::string& where) {
    const auto* ext = extension(extensions, "KHR_materials_variants");
    if (ext == nullptr || !ext->IsObject() || !ext->Has("mappings")) return;
    const tinygltf::Value& mappings = ext->Get("mappings");
    const std::string w = where + " KHR_materials_variants";
    if (!mappings.IsArray()) {
        ctx.warn(w + ": mappings is not an array; ignored");
        return;
    }
    for (size_t i = 0; i < mappings.ArrayLen(); ++i) {
        const tinygltf::Value& m = mappings.Get(int(i));
        const auto material = m.IsObject() ? indexOr(ctx, m, "material", w) : std::nullopt;
        if (!material || *material >= ctx.model.materials.size() || !m.Has("variants") ||
            !m.Get("variants").IsArray()) {
            ctx.warn(w + ": mapping " + str(i) + " has no valid material and variants; ignored");
            continue;
        }
        const tinygltf::Value& variants = m.Get("variants");
        for (size_t k = 0; k < variants.ArrayLen(); ++k) {
            const tinygltf::Value& v = variants.Get(int(k));
            const double index = v.IsNumber() ? v.GetNumberAsDouble() : -1.0;
            if (!(index >= 0.0) || index >= double(ctx.scene.variantNames.size()) || index != double(uint32_t(index))) {
                ctx.warn(w + ": mapping " + str(i) + " names variant " + (v.IsNumber() ? std::to_string(index) : "?") +
                         " but the file has " + str(ctx.scene.variantNames.size()) + "; ignored");
                continue;
            }
            prim.variantMaterials.emplace_back(uint32_t(index), *material);
        }
    }
}

}  // namespace gltf
}  // namespace idk::scene
