// gltf_extensions_test.cpp: loader completeness on Khronos assets and hand-written files: Draco vs quantized
// Duck, EXT_meshopt_compression (streams encoded here with meshoptimizer, .gltf and .glb), EXT_mesh_gpu_instancing,
// generated tangents (NormalTangentMirrorTest, a mirrored quad), the full material with its extensions, UV1 and
// vertex colours, multiple scenes, images that are missing or undecodable, Scene::features().
#include <algorithm>
#include <cmath>
#include <random>

#include <gtest/gtest.h>
#include <meshoptimizer.h>

#include "scene/gltf_loader.hpp"
#include "scene/primitive_ops.hpp"
#include "test_files.hpp"
#include "test_gltf.hpp"

namespace idk::scene {
namespace {

using test::expectLoadError;
using test::GltfFile;
using test::json;
using test::sharedScene;
using test::TempDir;
using test::triangle;

size_t triangleCount(const Scene& s) {
    size_t n = 0;
    for (const auto& m : s.meshes)
        for (const auto& p : m.primitives) n += p.indices.size() / 3;
    return n;
}

TEST(Compression, DracoDuckMatchesTheQuantizedDuck) {
    // No plain-glTF Duck is in ../shared/scenes, so the two compressed encodings are compared with each other.
    const Scene draco = loadGltf(sharedScene("Duck/glTF-Draco/Duck.gltf"));
    const Scene quantized = loadGltf(sharedScene("Duck/glTF-Quantized/Duck.gltf"));
    EXPECT_TRUE(draco.warnings.empty()) << draco.warnings.front();
    EXPECT_EQ(triangleCount(draco), 4212u);
    EXPECT_EQ(triangleCount(draco), triangleCount(quantized));
    for (int i = 0; i < 3; ++i) {
        EXPECT_NEAR(draco.bounds.min[i], quantized.bounds.min[i], 1e-3f) << i;
        EXPECT_NEAR(draco.bounds.max[i], quantized.bounds.max[i], 1e-3f) << i;
    }
    const Primitive& p = draco.meshes[0].primitives[0];
    EXPECT_EQ(p.uv0.size(), p.positions.size());
    for (size_t i = 0; i < p.normals.size(); i += 31) EXPECT_NEAR(glm::length(p.normals[i]), 1.0f, 0.02f);
    EXPECT_EQ(p.material, 0u);
}

TEST(Compression, CorruptDracoDataIsALoadError) {
    TempDir dir;
    auto doc = json::parse(test::readBytes(sharedScene("Duck/glTF-Draco/Duck.gltf")));
    auto bin = test::readBytes(sharedScene("Duck/glTF-Draco/Duck.bin"));
    std::filesystem::copy_file(sharedScene("Duck/glTF-Draco/DuckCM.png"), dir / "DuckCM.png");
    const size_t dracoView =
        doc["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]["bufferView"];
    const size_t offset = doc["bufferViews"][dracoView].value("byteOffset", 0);
    const size_t length = doc["bufferViews"][dracoView]["byteLength"];
    test::writeBytes(dir / "Duck.bin", bin.data(), bin.size());
    auto truncated = doc;
    truncated["bufferViews"][dracoView]["byteLength"] = length / 3;
    test::writeText(dir / "truncated.gltf", truncated.dump());
    expectLoadError(dir / "truncated.gltf", "Draco");
    auto wrongId = doc;
    wrongId["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]["attributes"]["NORMAL"] = 9;
    test::writeText(dir / "wrong_id.gltf", wrongId.dump());
    expectLoadError(dir / "wrong_id.gltf", "attribute NORMAL (unique id 9) is not in the Draco data");
    // Random byte edits inside the Draco stream: a Scene or a LoadError, never a crash (also under ASan).
    test::writeText(dir / "mutated.gltf", doc.dump());
    std::mt19937 rng(99);
    for (int iteration = 0; iteration < 40; ++iteration) {
        auto mutated = bin;
        for (int e = 0; e < 1 + iteration % 3; ++e) mutated[offset + rng() % length] = uint8_t(rng());
        test::writeBytes(dir / "Duck.bin", mutated.data(), mutated.size());
        try {
            const Scene s = loadGltf(dir / "mutated.gltf");
            for (const auto& p : s.meshes[0].primitives)
                for (const uint32_t i : p.indices) ASSERT_LT(i, p.positions.size());
        } catch (const LoadError&) {
        }
    }
    std::fill(bin.begin() + std::ptrdiff_t(offset), bin.begin() + std::ptrdiff_t(offset + 16), uint8_t(0x5A));
    test::writeBytes(dir / "Duck.bin", bin.data(), bin.size());
    test::writeText(dir / "header.gltf", doc.dump());
    expectLoadError(dir / "header.gltf", "Draco");
}

// A 4 x 4 vertex grid in the XY plane (18 triangles) with EXT_meshopt_compression: positions (plain vertex codec),
// normals (octahedral filter, 8-bit), indices (triangle codec); buffer 1 is the fallback buffer without data.
GltfFile meshoptGrid(std::vector<float>* positionsOut) {
    std::vector<float> positions;
    std::vector<float> normals;
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) {
            positions.insert(positions.end(), {float(x), float(y), 0.1f * float(x * y)});
            const glm::vec3 n = glm::normalize(glm::vec3(0.1f * float(x), -0.2f * float(y), 1.0f));
            normals.insert(normals.end(), {n.x, n.y, n.z, 0.0f});
        }
    std::vector<uint16_t> indices;
    for (uint16_t y = 0; y < 3; ++y)
        for (uint16_t x = 0; x < 3; ++x) {
            const uint16_t a = uint16_t(y * 4 + x), b = uint16_t(a + 1), c = uint16_t(a + 4), d = uint16_t(a + 5);
            indices.insert(indices.end(), {a, b, d, a, d, c});
        }
    *positionsOut = positions;
    std::vector<uint8_t> octahedral(16 * 4);
    meshopt_encodeFilterOct(octahedral.data(), 16, 4, 8, normals.data());
    auto encodeVertices = [](const void* data, size_t count, size_t stride) {
        std::vector<uint8_t> out(meshopt_encodeVertexBufferBound(count, stride));
        out.resize(meshopt_encodeVertexBuffer(out.data(), out.size(), data, count, stride));
        return out;
    };
    const auto pos = encodeVertices(positions.data(), 16, 12);
    const auto nrm = encodeVertices(octahedral.data(), 16, 4);
    std::vector<uint8_t> idx(meshopt_encodeIndexBufferBound(indices.size(), 16));
    idx.resize(meshopt_encodeIndexBuffer(idx.data(), idx.size(), indices.data(), indices.size()));

    GltfFile f;
    const size_t posAt = f.append(pos), nrmAt = f.append(nrm), idxAt = f.append(idx);
    auto ext = [](size_t at, size_t length, size_t stride, size_t count, const char* mode, const char* filter) {
        return json{{"EXT_meshopt_compression",
                     {{"buffer", 0}, {"byteOffset", at}, {"byteLength", length}, {"byteStride", stride},
                      {"count", count}, {"mode", mode}, {"filter", filter}}}};
    };
    f.doc = json::parse(R"({
      "asset": {"version": "2.0"},
      "extensionsUsed": ["EXT_meshopt_compression"], "extensionsRequired": ["EXT_meshopt_compression"],
      "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2}]}],
      "accessors": [
        {"bufferView": 0, "componentType": 5126, "count": 16, "type": "VEC3", "min": [0,0,0], "max": [3,3,0.9]},
        {"bufferView": 1, "componentType": 5120, "normalized": true, "count": 16, "type": "VEC3"},
        {"bufferView": 2, "componentType": 5123, "count": 54, "type": "SCALAR"}],
      "buffers": [{}, {"byteLength": 372, "extensions": {"EXT_meshopt_compression": {"fallback": true}}}]
    })");
    f.doc["bufferViews"] = json::array();
    f.doc["bufferViews"].push_back({{"buffer", 1}, {"byteOffset", 0}, {"byteLength", 192}, {"byteStride", 12},
                                    {"extensions", ext(posAt, pos.size(), 12, 16, "ATTRIBUTES", "NONE")}});
    f.doc["bufferViews"].push_back({{"buffer", 1}, {"byteOffset", 192}, {"byteLength", 64}, {"byteStride", 4},
                                    {"extensions", ext(nrmAt, nrm.size(), 4, 16, "ATTRIBUTES", "OCTAHEDRAL")}});
    f.doc["bufferViews"].push_back({{"buffer", 1}, {"byteOffset", 256}, {"byteLength", 108},
                                    {"extensions", ext(idxAt, idx.size(), 2, 54, "TRIANGLES", "NONE")}});
    return f;
}

void expectGrid(const Scene& s, const std::vector<float>& positions) {
    ASSERT_EQ(s.meshes.size(), 1u);
    const Primitive& p = s.meshes[0].primitives[0];
    EXPECT_EQ(p.indices.size(), 54u);
    ASSERT_EQ(p.positions.size(), 16u);
    for (size_t v = 0; v < 16; ++v) {
        EXPECT_EQ(p.positions[v], glm::vec3(positions[v * 3], positions[v * 3 + 1], positions[v * 3 + 2]));
        const int x = int(v % 4), y = int(v / 4);
        const glm::vec3 n = glm::normalize(glm::vec3(0.1f * float(x), -0.2f * float(y), 1.0f));
        EXPECT_GT(glm::dot(glm::normalize(p.normals[v]), n), 0.999f) << v;  // 8-bit octahedral
    }
    EXPECT_EQ(p.indices[10], 6u);  // triangle 3 = (a, d, c) of cell (1, 0) = (1, 6, 5)
}

TEST(Compression, MeshoptRoundTripGltfAndGlb) {
    TempDir dir;
    std::vector<float> positions;
    auto f = meshoptGrid(&positions);
    expectGrid(loadGltf(f.write(dir)), positions);
    expectGrid(loadGltf(f.writeGlb(dir)), positions);

    auto bad = f;
    bad.doc["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["byteStride"] = 6;
    expectLoadError(bad.write(dir), "must be a multiple of 4");
    bad = f;
    bad.doc["bufferViews"][2]["extensions"]["EXT_meshopt_compression"]["count"] = 55;
    expectLoadError(bad.write(dir), "not a multiple of 3");
    bad = f;
    bad.doc["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["byteLength"] = 5;
    expectLoadError(bad.write(dir), "meshopt ATTRIBUTES data is corrupt");
    bad = f;
    bad.doc["bufferViews"][1]["extensions"]["EXT_meshopt_compression"]["filter"] = "QUATERNION";
    expectLoadError(bad.write(dir), "does not allow byteStride 4");
    bad = f;
    bad.doc["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["byteOffset"] = 100000;
    expectLoadError(bad.write(dir), "extends past the end of buffer 0");
}

TEST(Instancing, SimpleInstancingPlacesOneInstancePerTransform) {
    const Scene s = loadGltf(sharedScene("SimpleInstancing/glTF-Binary/SimpleInstancing.glb"));
    EXPECT_TRUE(s.warnings.empty());
    ASSERT_EQ(s.nodes[0].instanceMatrices.size(), 125u);
    ASSERT_EQ(s.instances.size(), 125u);
    for (uint32_t i = 0; i < s.instances.size(); ++i) {
        EXPECT_EQ(s.instances[i].gpuInstance, i);
        EXPECT_EQ(s.instances[i].node, 0u);
        EXPECT_EQ(s.instances[i].world, s.nodes[0].world * s.nodes[0].instanceMatrices[i]);
    }
    EXPECT_NE(s.instances[0].world, s.instances[124].world);
    EXPECT_TRUE(s.features().hasGpuInstancing);
}

TEST(Tangents, MirroredQuadIsSplitAtTheSeam) {
    // Two unit squares side by side in the XY plane (normal +Z), UVs with glTF's top-left origin (v = 1 - y); the
    // right square mirrors u (u = 2 - x), as a symmetric model reusing one half of its texture does.
    Primitive p;
    p.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}, {1, 1, 0}, {2, 1, 0}};
    p.normals.assign(6, glm::vec3(0, 0, 1));
    p.uv0 = {{0, 1}, {1, 1}, {0, 1}, {0, 0}, {1, 0}, {0, 0}};
    p.indices = {0, 1, 4, 0, 4, 3, 1, 2, 5, 1, 5, 4};
    EXPECT_EQ(generateTangents(p), 2u);  // the two seam vertices (1 and 4) are duplicated
    ASSERT_EQ(p.positions.size(), 8u);
    ASSERT_EQ(p.tangents.size(), 8u);
    EXPECT_EQ(p.uv0.size(), 8u);
    for (size_t c = 0; c < 6; ++c) {
        // Left: T = dP/du = +X and the bitangent cross(N, T) = +Y is up the image: w = +1. Right: T = -X, w = -1.
        EXPECT_EQ(p.tangents[p.indices[c]], glm::vec4(1, 0, 0, 1)) << c;
        EXPECT_EQ(p.tangents[p.indices[6 + c]], glm::vec4(-1, 0, 0, -1)) << c;
    }
    EXPECT_TRUE(p.tangentsGenerated);
}

TEST(Tangents, NormalTangentMirrorTestGeneratedMatchTheFile) {
    const Scene s = loadGltf(sharedScene("NormalTangentMirrorTest/glTF-Binary/NormalTangentMirrorTest.glb"));
    const Primitive& file = s.meshes[0].primitives[0];
    ASSERT_EQ(file.tangents.size(), file.positions.size());
    EXPECT_FALSE(file.tangentsGenerated);
    Primitive generated = file;
    generated.tangents.clear();
    generateTangents(generated);
    ASSERT_EQ(generated.tangents.size(), generated.positions.size());
    size_t plus = 0, minus = 0, signAgrees = 0, directionAgrees = 0;
    for (size_t v = 0; v < generated.positions.size(); ++v) {
        const glm::vec4 t = generated.tangents[v];
        const glm::vec3 n = generated.normals[v];
        EXPECT_NEAR(glm::length(glm::vec3(t)), 1.0f, 1e-4f);
        EXPECT_NEAR(glm::dot(glm::vec3(t), n) / glm::length(n), 0.0f, 1e-4f);
        ASSERT_TRUE(t.w == 1.0f || t.w == -1.0f);
        (t.w > 0 ? plus : minus)++;
        if (v < file.positions.size()) {
            signAgrees += t.w == file.tangents[v].w;
            directionAgrees += glm::dot(glm::vec3(t), glm::vec3(file.tangents[v])) > std::cos(glm::radians(5.0f));
        }
    }
    EXPECT_GT(plus, 0u);
    EXPECT_GT(minus, 0u);
    // The file's tangents come from MikkTSpace; ours approximate it (here: every sign, every direction within
    // 5 degrees, when measured; the thresholds leave a little room).
    const double n = double(file.positions.size());
    EXPECT_GT(double(signAgrees) / n, 0.99) << signAgrees << " of " << n;
    EXPECT_GT(double(directionAgrees) / n, 0.98) << directionAgrees << " of " << n;
}

TEST(Materials, KhronosAssets) {
    const Scene helmet = loadGltf(sharedScene("DamagedHelmet/glTF-Binary/DamagedHelmet.glb"));
    const Material& m = helmet.materials[0];
    EXPECT_TRUE(m.baseColorTexture && m.metallicRoughnessTexture && m.normalTexture && m.occlusionTexture &&
                m.emissiveTexture);
    EXPECT_EQ(m.emissive, glm::vec3(1.0f));
    const auto f = helmet.features();
    EXPECT_TRUE(f.hasTextures && f.hasNormalMaps && f.hasEmissive);
    EXPECT_FALSE(f.hasSkins || f.hasMorphs || f.hasBlend || f.hasTransmission || f.hasShadowCastingLights);
    EXPECT_EQ(helmet.meshes[0].primitives[0].tangents.size(), helmet.meshes[0].primitives[0].positions.size());

    const Scene unlit = loadGltf(sharedScene("UnlitTest/glTF-Binary/UnlitTest.glb"));
    EXPECT_TRUE(std::all_of(unlit.materials.begin(), unlit.materials.end(), [](const Material& x) { return x.unlit; }));
    EXPECT_TRUE(unlit.features().hasUnlit);

    const Scene transmission = loadGltf(sharedScene("TransmissionTest/glTF-Binary/TransmissionTest.glb"));
    size_t withTexture = 0;
    for (const Material& x : transmission.materials) withTexture += x.transmission == 1.0f && x.transmissionTexture;
    EXPECT_GE(withTexture, 2u);
    EXPECT_TRUE(transmission.features().hasTransmission);

    const Scene car = loadGltf(sharedScene("ToyCar/glTF/ToyCar.gltf"));
    bool scaled = false;
    for (const Material& x : car.materials)
        if (x.normalTexture && x.normalTexture->scale == glm::vec2(3.0f)) scaled = true;
    EXPECT_TRUE(scaled) << "KHR_texture_transform on the Fabric normal map";

    const Scene colors = loadGltf(sharedScene("VertexColorTest/glTF-Binary/VertexColorTest.glb"));
    EXPECT_TRUE(colors.features().hasVertexColors);
    for (const auto& mesh : colors.meshes)
        for (const auto& p : mesh.primitives)
            for (const glm::vec4& c : p.colors) EXPECT_TRUE(glm::all(glm::greaterThanEqual(c, glm::vec4(0.0f))));
}

// Every material extension, texture slot, texCoord 1 and transform, UV1 and vec3 normalized colours on one file.
TEST(Materials, HandWrittenFullMaterial) {
    TempDir dir;
    auto f = triangle();
    const size_t uv1 = f.append(std::vector<float>{0, 0, 1, 0, 0, 1});
    const size_t col = f.append(std::vector<uint8_t>{255, 0, 0, 0, 0, 255, 0, 0, 0, 0, 255, 0});
    f.doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", uv1}, {"byteLength", 24}});
    f.doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", col}, {"byteLength", 12}, {"byteStride", 4}});
    f.doc["accessors"].push_back({{"bufferView", 2}, {"componentType", 5126}, {"count", 3}, {"type", "VEC2"}});
    f.doc["accessors"].push_back(
        {{"bufferView", 3}, {"componentType", 5121}, {"normalized", true}, {"count", 3}, {"type", "VEC3"}});
    auto& prim = f.doc["meshes"][0]["primitives"][0];
    prim["attributes"]["TEXCOORD_1"] = 2;
    prim["attributes"]["COLOR_0"] = 3;
    prim["material"] = 0;
    f.doc["images"] = json::parse(R"([{"uri": "missing.png"}, {"uri": "notes.png"}])");
    test::writeText(dir / "notes.png", "this is not an image");
    f.doc["textures"] = json::parse(R"([{"source": 0}, {"source": 1}])");
    f.doc["materials"] = json::parse(R"([{
      "pbrMetallicRoughness": {"baseColorTexture": {"index": 0, "texCoord": 1},
                               "metallicRoughnessTexture": {"index": 1}},
      "normalTexture": {"index": 0, "scale": 0.5, "texCoord": 1},
      "occlusionTexture": {"index": 1, "strength": 0.25, "extensions": {
                           "KHR_texture_transform": {"offset": [0.5, 0], "rotation": 1.5, "texCoord": 1}}},
      "emissiveTexture": {"index": 0}, "emissiveFactor": [1, 0.5, 0],
      "extensions": {
        "KHR_materials_emissive_strength": {"emissiveStrength": 4},
        "KHR_materials_transmission": {"transmissionFactor": 0.75, "transmissionTexture": {"index": 1, "texCoord": 1}},
        "KHR_materials_ior": {"ior": 1.33},
        "KHR_materials_volume": {"thicknessFactor": 0.2, "thicknessTexture": {"index": 0},
                                 "attenuationDistance": 3.5, "attenuationColor": [0.9, 0.8, 0.7]}}}])");
    const Scene s = loadGltf(f.write(dir));
    const Material& m = s.materials[0];
    EXPECT_EQ(m.baseColorTexture->texCoord, 1u);
    EXPECT_EQ(m.metallicRoughnessTexture->texture, 1u);
    EXPECT_EQ(m.normalScale, 0.5f);
    EXPECT_EQ(m.normalTexture->texCoord, 1u);
    EXPECT_EQ(m.occlusionStrength, 0.25f);
    EXPECT_EQ(m.occlusionTexture->offset, glm::vec2(0.5f, 0.0f));
    EXPECT_EQ(m.occlusionTexture->rotation, 1.5f);
    EXPECT_EQ(m.occlusionTexture->texCoord, 1u);
    EXPECT_EQ(m.emissive, glm::vec3(4.0f, 2.0f, 0.0f));
    EXPECT_EQ(m.emissiveStrength, 4.0f);
    EXPECT_EQ(m.transmission, 0.75f);
    EXPECT_EQ(m.transmissionTexture->texCoord, 1u);
    EXPECT_FLOAT_EQ(m.ior, 1.33f);
    EXPECT_FLOAT_EQ(m.thickness, 0.2f);
    EXPECT_TRUE(m.thicknessTexture.has_value());
    EXPECT_FLOAT_EQ(m.attenuationDistance, 3.5f);
    EXPECT_FLOAT_EQ(m.attenuationColor.z, 0.7f);
    const Primitive& p = s.meshes[0].primitives[0];
    ASSERT_EQ(p.uv1.size(), p.positions.size());
    ASSERT_EQ(p.colors.size(), p.positions.size());
    EXPECT_EQ(p.colors[0], glm::vec4(1, 0, 0, 1));  // vec3 colours get alpha 1
    // Tangents come from the UV set the normal map uses (TEXCOORD_1 here: u along +X; v runs along +Y, i.e. down
    // the image in glTF's top-left origin, so the frame is mirrored: w = -1).
    ASSERT_EQ(p.tangents.size(), p.positions.size());
    EXPECT_EQ(p.tangents[0], glm::vec4(1, 0, 0, -1));
    // The two images: recorded with the reason the decoder will draw magenta, plus one warning each.
    EXPECT_EQ(s.images[0].status, ImageStatus::Missing);
    EXPECT_EQ(s.images[0].path.filename(), "missing.png");
    EXPECT_EQ(s.images[1].status, ImageStatus::UnknownFormat);
    EXPECT_EQ(s.warnings.size(), 2u);
    const auto features = s.features();
    EXPECT_TRUE(features.hasTransmission && features.hasVolume && features.hasUv1 && features.hasVertexColors);
}

TEST(Scenes, SceneIndexSelectsWhatIsPlaced) {
    TempDir dir;
    auto f = triangle();
    f.doc["nodes"].push_back({{"mesh", 0}, {"translation", {5, 0, 0}}});
    f.doc["scenes"] = json::parse(R"([{"name": "first", "nodes": [0]}, {"name": "second", "nodes": [1]}])");
    f.doc["scene"] = 1;
    const auto path = f.write(dir);
    const Scene byDefault = loadGltf(path);
    EXPECT_EQ(byDefault.sceneIndex, 1u);
    EXPECT_EQ(byDefault.sceneNames, (std::vector<std::string>{"first", "second"}));
    ASSERT_EQ(byDefault.instances.size(), 1u);
    EXPECT_EQ(byDefault.instances[0].node, 1u);
    EXPECT_EQ(byDefault.bounds.min.x, 5.0f);
    const Scene first = loadGltf(path, LoadOptions{0});
    EXPECT_EQ(first.sceneIndex, 0u);
    EXPECT_EQ(first.instances[0].node, 0u);
    EXPECT_EQ(first.bounds.min.x, 0.0f);
    try {
        loadGltf(path, LoadOptions{2});
        FAIL() << "expected LoadError";
    } catch (const LoadError& e) {
        EXPECT_NE(std::string(e.what()).find("scene 2 requested, the file has 2 scenes"), std::string::npos);
    }
}

TEST(Features, OnlyWhatTheSceneNeeds) {
    const Scene box = loadGltf(sharedScene("Box/glTF-Binary/Box.glb"));
    const SceneFeatures f = box.features();
    EXPECT_FALSE(f.hasSkins || f.hasMorphs || f.hasAnimations || f.hasBlend || f.hasMask || f.hasTextures ||
                 f.hasShadowCastingLights || f.hasGpuInstancing);
    const Scene blend = loadGltf(sharedScene("AlphaBlendModeTest/glTF-Binary/AlphaBlendModeTest.glb"));
    EXPECT_TRUE(blend.features().hasBlend && blend.features().hasMask);
    const Scene fox = loadGltf(sharedScene("Fox/glTF-Binary/Fox.glb"));
    EXPECT_TRUE(fox.features().hasSkins && fox.features().hasAnimations);
    EXPECT_EQ(fox.features().maxJoints, 24u);
    const Scene morph = loadGltf(sharedScene("AnimatedMorphCube/glTF-Binary/AnimatedMorphCube.glb"));
    EXPECT_TRUE(morph.features().hasMorphs);
    EXPECT_EQ(morph.features().maxMorphTargets, 2u);
    const Scene cornell = loadGltf(test::sourceDir() / "scenes/cornell_box.gltf");
    EXPECT_TRUE(cornell.features().hasShadowCastingLights);
}

}  // namespace
}  // namespace idk::scene
