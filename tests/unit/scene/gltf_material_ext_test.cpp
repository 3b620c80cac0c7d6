// gltf_material_ext_test.cpp: the loader's BSDF material extensions (scene/gltf_material_ext.cpp): the factors of
// KHR_materials_specular, _clearcoat, _sheen, _anisotropy, _iridescence, _diffuse_transmission land in
// scene::Material; hostile values (out of range, non-finite, wrong types) are clamped or replaced with a warning
// naming the material (a diffuse-transmission factor of 0 leaves its textures undecoded); extension textures load
// as TextureRefs with texCoord and KHR_texture_transform (bad references warn and are dropped;
// clearcoatNormalTexture loads with its scale, anisotropyTexture loads); ToyCar's clearcoat
// texture loads without a warning; materials without the extensions keep the neutral defaults; the
// authored scenes/material_spheres.gltf loads with its four extension materials and no warnings;
// KHR_materials_variants: mappings select materials by variant name, bad mappings warn, unknown names throw
// listing the variants.
#include <filesystem>
#include <stdexcept>

#include <gtest/gtest.h>

#include "scene/gltf_loader.hpp"
#include "scene/texture_decode.hpp"
#include "test_files.hpp"
#include "test_gltf.hpp"

namespace idk::scene {
namespace {

using test::json;
using test::TempDir;
using test::triangle;

bool anyWarningHas(const Scene& s, const std::string& a, const std::string& b) {
    for (const std::string& w : s.warnings)
        if (w.find(a) != std::string::npos && w.find(b) != std::string::npos) return true;
    return false;
}

TEST(GltfMaterialExt, FactorsAreLoaded) {
    TempDir dir;
    auto f = triangle();
    f.doc["meshes"][0]["primitives"][0]["material"] = 0;
    f.doc["materials"] = json::parse(R"([{"name": "layered", "extensions": {
        "KHR_materials_specular": {"specularFactor": 0.25, "specularColorFactor": [2.0, 0.5, 0.0]},
        "KHR_materials_clearcoat": {"clearcoatFactor": 0.75, "clearcoatRoughnessFactor": 0.125},
        "KHR_materials_sheen": {"sheenColorFactor": [0.5, 0.25, 1.0], "sheenRoughnessFactor": 0.5}}},
        {"name": "plain"}])");
    const Scene s = loadGltf(f.write(dir));
    const Material& m = s.materials[0];
    EXPECT_EQ(m.specular, 0.25f);
    EXPECT_EQ(m.specularColor, glm::vec3(2.0f, 0.5f, 0.0f));  // above 1 is legal for the specular colour
    EXPECT_EQ(m.clearcoat, 0.75f);
    EXPECT_EQ(m.clearcoatRoughness, 0.125f);
    EXPECT_EQ(m.sheenColor, glm::vec3(0.5f, 0.25f, 1.0f));
    EXPECT_EQ(m.sheenRoughness, 0.5f);
    EXPECT_TRUE(s.warnings.empty());
    const Material& plain = s.materials[1];
    EXPECT_EQ(plain.specular, 1.0f);
    EXPECT_EQ(plain.specularColor, glm::vec3(1.0f));
    EXPECT_EQ(plain.clearcoat, 0.0f);
    EXPECT_EQ(plain.sheenColor, glm::vec3(0.0f));
}

TEST(GltfMaterialExt, HostileValuesAreClampedWithWarnings) {
    TempDir dir;
    auto f = triangle();
    f.doc["meshes"][0]["primitives"][0]["material"] = 0;
    f.doc["textures"] = json::parse(R"([{}])");
    f.doc["materials"] = json::parse(R"([{"name": "hostile", "extensions": {
        "KHR_materials_specular": {"specularFactor": 7, "specularColorFactor": [1, "red", 1]},
        "KHR_materials_clearcoat": {"clearcoatFactor": -3, "clearcoatRoughnessFactor": "rough",
                                    "clearcoatTexture": {"index": 0}, "clearcoatNormalTexture": {"index": 9}},
        "KHR_materials_sheen": {"sheenColorFactor": [1e30, -1, 0.5, 4], "sheenRoughnessFactor": 1e300}}}])");
    const Scene s = loadGltf(f.write(dir));
    const Material& m = s.materials[0];
    EXPECT_EQ(m.specular, 1.0f);
    EXPECT_EQ(m.specularColor, glm::vec3(1.0f));  // a non-number component: the default colour
    EXPECT_EQ(m.clearcoat, 0.0f);
    EXPECT_EQ(m.clearcoatRoughness, 0.0f);
    EXPECT_EQ(m.sheenColor, glm::vec3(0.0f));      // 4 components: not a colour
    EXPECT_EQ(m.sheenRoughness, 1.0f);             // a finite double far out of range: clamped
    EXPECT_TRUE(anyWarningHas(s, "'hostile'", "specularFactor"));
    EXPECT_TRUE(anyWarningHas(s, "'hostile'", "specularColorFactor"));
    EXPECT_TRUE(anyWarningHas(s, "'hostile'", "clearcoatFactor"));
    EXPECT_TRUE(anyWarningHas(s, "'hostile'", "clearcoatRoughnessFactor"));
    EXPECT_TRUE(anyWarningHas(s, "'hostile'", "sheenColorFactor"));
    EXPECT_TRUE(m.clearcoatTexture.has_value());  // texture 0 exists: loaded even though the factor is clamped
    EXPECT_FALSE(anyWarningHas(s, "clearcoatTexture", "not supported"));
    EXPECT_TRUE(anyWarningHas(s, "clearcoatNormalTexture", "texture 9"));
}

TEST(GltfMaterialExt, AnisotropyIsLoadedAndChecked) {
    TempDir dir;
    auto f = triangle();
    f.doc["meshes"][0]["primitives"][0]["material"] = 0;
    f.doc["textures"] = json::parse(R"([{}])");
    f.doc["materials"] = json::parse(R"([{"name": "brushed", "extensions": {
        "KHR_materials_anisotropy": {"anisotropyStrength": 0.6, "anisotropyRotation": 1.25}}},
        {"name": "hostile", "extensions": {"KHR_materials_anisotropy": {"anisotropyStrength": 7,
            "anisotropyRotation": "north", "anisotropyTexture": {"index": 0}}}}, {"name": "plain"}])");
    const Scene s = loadGltf(f.write(dir));
    EXPECT_EQ(s.materials[0].anisotropyStrength, 0.6f);
    EXPECT_EQ(s.materials[0].anisotropyRotation, 1.25f);
    EXPECT_EQ(s.materials[1].anisotropyStrength, 1.0f);  // clamped
    EXPECT_EQ(s.materials[1].anisotropyRotation, 0.0f);  // not a number: the default
    EXPECT_EQ(s.materials[2].anisotropyStrength, 0.0f);
    EXPECT_TRUE(anyWarningHas(s, "'hostile'", "anisotropyStrength"));
    EXPECT_TRUE(anyWarningHas(s, "'hostile'", "anisotropyRotation"));
    EXPECT_FALSE(anyWarningHas(s, "anisotropyTexture", "not supported"));
    ASSERT_TRUE(s.materials[1].anisotropyTexture);  // read now
    EXPECT_EQ(s.materials[1].anisotropyTexture->texture, 0u);
    EXPECT_FALSE(anyWarningHas(s, "'brushed'", "anisotropy"));
}

TEST(GltfMaterialExt, DiffuseTransmissionIsLoadedAndChecked) {
    TempDir dir;
    auto f = triangle();
    f.doc["meshes"][0]["primitives"][0]["material"] = 0;
    f.doc["extensionsUsed"] = json::parse(R"(["KHR_materials_diffuse_transmission"])");
    f.doc["extensionsRequired"] = json::parse(R"(["KHR_materials_diffuse_transmission"])");
    f.doc["textures"] = json::parse(R"([{}, {}, {}, {}])");
    f.doc["materials"] = json::parse(R"([{"name": "leaf", "extensions": {"KHR_materials_diffuse_transmission": {
            "diffuseTransmissionFactor": 0.75, "diffuseTransmissionColorFactor": [0.5, 1.0, 0.25],
            "diffuseTransmissionTexture": {"index": 0},
            "diffuseTransmissionColorTexture": {"index": 1, "texCoord": 1}}}},
        {"name": "hostile", "extensions": {"KHR_materials_diffuse_transmission": {
            "diffuseTransmissionFactor": 4, "diffuseTransmissionColorFactor": [2, -1, 0.5],
            "diffuseTransmissionTexture": {"index": 9}}}},
        {"name": "off", "extensions": {"KHR_materials_diffuse_transmission": {
            "diffuseTransmissionTexture": {"index": 2}, "diffuseTransmissionColorTexture": {"index": 3}}}},
        {"name": "plain"}])");
    const Scene s = loadGltf(f.write(dir));
    const Material& leaf = s.materials[0];
    EXPECT_EQ(leaf.diffuseTransmission, 0.75f);
    EXPECT_EQ(leaf.diffuseTransmissionColor, glm::vec3(0.5f, 1.0f, 0.25f));
    ASSERT_TRUE(leaf.diffuseTransmissionTexture && leaf.diffuseTransmissionColorTexture);
    EXPECT_EQ(leaf.diffuseTransmissionTexture->texture, 0u);
    EXPECT_EQ(leaf.diffuseTransmissionColorTexture->texture, 1u);
    EXPECT_EQ(leaf.diffuseTransmissionColorTexture->texCoord, 1u);
    const Material& hostile = s.materials[1];
    EXPECT_EQ(hostile.diffuseTransmission, 1.0f);                                  // clamped
    EXPECT_EQ(hostile.diffuseTransmissionColor, glm::vec3(1.0f, 0.0f, 0.5f));     // each channel clamped
    EXPECT_FALSE(hostile.diffuseTransmissionTexture.has_value());                  // texture 9 of 4: dropped
    EXPECT_TRUE(anyWarningHas(s, "'hostile'", "diffuseTransmissionFactor 4"));
    EXPECT_TRUE(anyWarningHas(s, "'hostile'", "diffuseTransmissionColorFactor component 2"));
    EXPECT_TRUE(anyWarningHas(s, "'hostile'", "diffuseTransmissionColorFactor component -1"));
    EXPECT_TRUE(anyWarningHas(s, "'hostile'", "diffuseTransmissionTexture names texture 9"));
    EXPECT_FALSE(anyWarningHas(s, "'leaf'", "diffuseTransmission"));
    EXPECT_EQ(s.materials[2].diffuseTransmission, 0.0f);  // the default factor
    EXPECT_EQ(s.materials[3].diffuseTransmission, 0.0f);
    EXPECT_EQ(s.materials[3].diffuseTransmissionColor, glm::vec3(1.0f));
    // Textures load only for materials that use them: a factor of 0 never reads its textures.
    const std::vector<TextureColorSpace> spaces = textureColorSpaces(s);
    EXPECT_EQ(spaces[0], TextureColorSpace::Linear);
    EXPECT_EQ(spaces[1], TextureColorSpace::Srgb);
    EXPECT_EQ(spaces[2], TextureColorSpace::Unused);
    EXPECT_EQ(spaces[3], TextureColorSpace::Unused);
}

TEST(GltfMaterialExt, DispersionIsLoadedAndChecked) {
    TempDir dir;
    auto f = triangle();
    f.doc["meshes"][0]["primitives"][0]["material"] = 0;
    f.doc["extensionsUsed"] = json::parse(R"(["KHR_materials_dispersion"])");
    f.doc["extensionsRequired"] = json::parse(R"(["KHR_materials_dispersion"])");
    f.doc["materials"] = json::parse(R"([
        {"name": "flint", "extensions": {"KHR_materials_dispersion": {"dispersion": 0.5}}},
        {"name": "negative", "extensions": {"KHR_materials_dispersion": {"dispersion": -2}}},
        {"name": "huge", "extensions": {"KHR_materials_dispersion": {"dispersion": 1e9}}},
        {"name": "word", "extensions": {"KHR_materials_dispersion": {"dispersion": "lots"}}}, {"name": "plain"}])");
    const Scene s = loadGltf(f.write(dir));
    EXPECT_EQ(s.materials[0].dispersion, 0.5f);
    EXPECT_EQ(s.materials[1].dispersion, 0.0f);    // clamped to 0
    EXPECT_EQ(s.materials[2].dispersion, 100.0f);  // capped
    EXPECT_EQ(s.materials[3].dispersion, 0.0f);    // not a number: the default
    EXPECT_EQ(s.materials[4].dispersion, 0.0f);
    EXPECT_TRUE(anyWarningHas(s, "'negative'", "dispersion -2"));
    EXPECT_TRUE(anyWarningHas(s, "'huge'", "dispersion 1000000000"));
    EXPECT_TRUE(anyWarningHas(s, "'word'", "dispersion is not a number"));
    EXPECT_FALSE(anyWarningHas(s, "'flint'", "dispersion"));
}

TEST(GltfMaterialExt, IridescenceIsLoadedAndChecked) {
    TempDir dir;
    auto f = triangle();
    f.doc["meshes"][0]["primitives"][0]["material"] = 0;
    // A file that requires the extension loads (the loader lists it as supported).
    f.doc["extensionsUsed"] = json::parse(R"(["KHR_materials_iridescence"])");
    f.doc["extensionsRequired"] = json::parse(R"(["KHR_materials_iridescence"])");
    f.doc["textures"] = json::parse(R"([{}, {}])");
    f.doc["materials"] = json::parse(R"([{"name": "film", "extensions": {"KHR_materials_iridescence": {
            "iridescenceFactor": 0.75, "iridescenceIor": 1.6, "iridescenceThicknessMinimum": 120,
            "iridescenceThicknessMaximum": 480, "iridescenceTexture": {"index": 0},
            "iridescenceThicknessTexture": {"index": 1, "texCoord": 1}}}},
        {"name": "defaults", "extensions": {"KHR_materials_iridescence": {"iridescenceFactor": 1}}},
        {"name": "hostile", "extensions": {"KHR_materials_iridescence": {"iridescenceFactor": 3,
            "iridescenceIor": 0.5, "iridescenceThicknessMinimum": -10, "iridescenceThicknessMaximum": 1e9,
            "iridescenceTexture": {"index": 9}}}},
        {"name": "odd", "extensions": {"KHR_materials_iridescence": {"iridescenceFactor": "shiny",
            "iridescenceIor": 9}}},
        {"name": "plain"}])");
    const Scene s = loadGltf(f.write(dir));
    const Material& m = s.materials[0];
    EXPECT_EQ(m.iridescence, 0.75f);
    EXPECT_EQ(m.iridescenceIor, 1.6f);
    EXPECT_EQ(m.iridescenceThicknessMin, 120.0f);
    EXPECT_EQ(m.iridescenceThicknessMax, 480.0f);
    ASSERT_TRUE(m.iridescenceTexture && m.iridescenceThicknessTexture);
    EXPECT_EQ(m.iridescenceTexture->texture, 0u);
    EXPECT_EQ(m.iridescenceThicknessTexture->texture, 1u);
    EXPECT_EQ(m.iridescenceThicknessTexture->texCoord, 1u);
    EXPECT_FALSE(anyWarningHas(s, "'film'", "iridescence"));
    const Material& d = s.materials[1];  // the specification's defaults
    EXPECT_EQ(d.iridescence, 1.0f);
    EXPECT_EQ(d.iridescenceIor, 1.3f);
    EXPECT_EQ(d.iridescenceThicknessMin, 100.0f);
    EXPECT_EQ(d.iridescenceThicknessMax, 400.0f);
    const Material& h = s.materials[2];
    EXPECT_EQ(h.iridescence, 1.0f);  // clamped
    EXPECT_EQ(h.iridescenceIor, 1.0f);
    EXPECT_EQ(h.iridescenceThicknessMin, 0.0f);
    EXPECT_EQ(h.iridescenceThicknessMax, 1.0e5f);
    EXPECT_FALSE(h.iridescenceTexture);
    for (const char* key : {"iridescenceFactor", "iridescenceIor", "iridescenceThicknessMinimum",
                            "iridescenceThicknessMaximum", "iridescenceTexture"})
        EXPECT_TRUE(anyWarningHas(s, "'hostile'", key)) << key;
    EXPECT_EQ(s.materials[3].iridescence, 0.0f);  // not a number: the default
    EXPECT_EQ(s.materials[3].iridescenceIor, 4.0f);
    EXPECT_TRUE(anyWarningHas(s, "'odd'", "iridescenceFactor"));
    EXPECT_TRUE(anyWarningHas(s, "'odd'", "iridescenceIor"));
    EXPECT_EQ(s.materials[4].iridescence, 0.0f);
    EXPECT_FALSE(s.materials[4].iridescenceTexture);
}

TEST(GltfMaterialExt, ExtensionTexturesAreLoaded) {
    TempDir dir;
    auto f = triangle();
    f.doc["meshes"][0]["primitives"][0]["material"] = 0;
    f.doc["textures"] = json::parse(R"([{}, {}, {}])");
    f.doc["materials"] = json::parse(R"([{"name": "textured", "extensions": {
        "KHR_materials_specular": {"specularTexture": {"index": 0},
                                   "specularColorTexture": {"index": 1, "texCoord": 1}},
        "KHR_materials_clearcoat": {"clearcoatFactor": 1, "clearcoatTexture": {"index": 2},
            "clearcoatRoughnessTexture": {"index": 1, "extensions": {"KHR_texture_transform":
                {"offset": [0.5, 0.25], "scale": [2, 3], "rotation": 0.5}}},
            "clearcoatNormalTexture": {"index": 0, "scale": 0.5}},
        "KHR_materials_sheen": {"sheenColorFactor": [1, 1, 1], "sheenColorTexture": {"index": 2},
                                "sheenRoughnessTexture": {"index": 7}}}}])");
    const Scene s = loadGltf(f.write(dir));
    const Material& m = s.materials[0];
    ASSERT_TRUE(m.specularTexture && m.specularColorTexture && m.clearcoatTexture && m.clearcoatRoughnessTexture &&
                m.sheenColorTexture);
    EXPECT_EQ(m.specularTexture->texture, 0u);
    EXPECT_EQ(m.specularColorTexture->texture, 1u);
    EXPECT_EQ(m.specularColorTexture->texCoord, 1u);
    EXPECT_EQ(m.clearcoatTexture->texture, 2u);
    EXPECT_EQ(m.clearcoatRoughnessTexture->offset, glm::vec2(0.5f, 0.25f));
    EXPECT_EQ(m.clearcoatRoughnessTexture->scale, glm::vec2(2.0f, 3.0f));
    EXPECT_EQ(m.clearcoatRoughnessTexture->rotation, 0.5f);
    ASSERT_TRUE(m.clearcoatNormalTexture);  // read now: the coat's own normal, no warning
    EXPECT_EQ(m.clearcoatNormalTexture->texture, 0u);
    EXPECT_EQ(m.clearcoatNormalScale, 0.5f);
    EXPECT_FALSE(anyWarningHas(s, "'textured'", "clearcoatNormalTexture"));
    EXPECT_EQ(m.sheenColorTexture->texture, 2u);
    EXPECT_FALSE(m.sheenRoughnessTexture.has_value());  // texture 7 of 3: dropped with a warning
    EXPECT_TRUE(anyWarningHas(s, "'textured'", "sheenRoughnessTexture names texture 7"));
    EXPECT_TRUE(s.features().hasTextures);
}

TEST(GltfMaterialExt, ToyCarClearcoatTextureLoadsWithoutWarnings) {
    const Scene car = loadGltf(test::sharedScene("ToyCar/glTF/ToyCar.gltf"));
    bool coatTexture = false;
    for (const Material& m : car.materials) coatTexture |= m.clearcoat == 1.0f && m.clearcoatTexture.has_value();
    EXPECT_TRUE(coatTexture);
    for (const std::string& w : car.warnings) {
        EXPECT_EQ(w.find("KHR_materials"), std::string::npos) << w;
        EXPECT_EQ(w.find("not supported"), std::string::npos) << w;
    }
}

TEST(GltfMaterialExt, AuthoredSceneLoadsWithoutWarnings) {
    const Scene s = loadGltf(std::filesystem::path(IDK_SOURCE_DIR) / "scenes/material_spheres.gltf");
    ASSERT_EQ(s.materials.size(), 5u);
    EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
    EXPECT_EQ(s.materials[1].specular, 0.3f);
    EXPECT_EQ(s.materials[2].clearcoatRoughness, 0.1f);
    EXPECT_EQ(s.materials[3].sheenRoughness, 0.4f);
    EXPECT_EQ(s.materials[4].metallic, 1.0f);
}

}  // namespace
}  // namespace idk::scene

namespace idk::scene {
namespace {

TEST(GltfMaterialVariants, MappingsSelectMaterialsByName) {
    test::TempDir dir;
    auto f = test::triangle();
    f.doc["materials"] = test::json::parse(R"([{"name": "default"}, {"name": "blue"}])");
    f.doc["extensionsUsed"] = test::json::parse(R"(["KHR_materials_variants"])");
    f.doc["extensions"]["KHR_materials_variants"] = test::json::parse(R"({"variants": [{"name": "red"}, {"name": "blue"}]})");
    auto& prim = f.doc["meshes"][0]["primitives"][0];
    prim["material"] = 0;
    prim["extensions"]["KHR_materials_variants"] = test::json::parse(
        R"({"mappings": [{"material": 1, "variants": [1]}, {"material": 7, "variants": [0]},
                         {"material": 0, "variants": [5, 0]}]})");
    Scene s = loadGltf(f.write(dir));
    EXPECT_EQ(s.variantNames, (std::vector<std::string>{"red", "blue"}));
    // The out-of-range material and variant are reported and skipped.
    EXPECT_EQ(s.warnings.size(), 2u);
    Primitive& p = s.meshes[0].primitives[0];
    EXPECT_EQ(p.material, 0u);
    applyMaterialVariant(s, "blue");
    EXPECT_EQ(p.material, 1u);
    applyMaterialVariant(s, "red");
    EXPECT_EQ(p.material, 0u);
    try {
        applyMaterialVariant(s, "green");
        FAIL() << "an unknown variant must throw";
    } catch (const std::invalid_argument& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("'green'"), std::string::npos) << what;
        EXPECT_NE(what.find("'red', 'blue'"), std::string::npos) << what;
    }
    Scene none = loadGltf(test::triangle().write(dir));
    EXPECT_THROW(applyMaterialVariant(none, "red"), std::invalid_argument);
}

}  // namespace
}  // namespace idk::scene
