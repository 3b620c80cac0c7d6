// gltf_loader_test.cpp: loadGltf() on the project's Cornell box (counts, bounds from the published measurements,
// emissive strength, camera, light, normals) and on Khronos sample assets (Box, BoxTextured, MeshPrimitiveModes,
// Duck quantized; Draco and the other extensions are in gltf_extensions_test.cpp).
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "scene/gltf_loader.hpp"
#include "test_files.hpp"

namespace idk::scene {
namespace {

using test::sharedScene;
using test::sourceDir;

size_t triangleCount(const Mesh& mesh) {
    size_t n = 0;
    for (const auto& p : mesh.primitives) n += p.indices.size() / 3;
    return n;
}

size_t triangleCount(const Scene& scene) {
    size_t n = 0;
    for (const auto& m : scene.meshes) n += triangleCount(m);
    return n;
}

void expectVec3Near(const glm::vec3& a, const glm::vec3& b, float tolerance) {
    EXPECT_NEAR(a.x, b.x, tolerance);
    EXPECT_NEAR(a.y, b.y, tolerance);
    EXPECT_NEAR(a.z, b.z, tolerance);
}

const Mesh& meshNamed(const Scene& scene, const std::string& name) {
    for (const auto& m : scene.meshes)
        if (m.name == name) return m;
    throw std::runtime_error("no mesh " + name);
}

// Every primitive is a consistent triangle list with one normal (unit) per vertex.
void expectWellFormed(const Scene& scene) {
    for (const auto& mesh : scene.meshes) {
        for (const auto& p : mesh.primitives) {
            EXPECT_EQ(p.indices.size() % 3, 0u);
            EXPECT_EQ(p.normals.size(), p.positions.size());
            EXPECT_TRUE(p.uv0.empty() || p.uv0.size() == p.positions.size());
            for (const uint32_t i : p.indices) ASSERT_LT(i, p.positions.size());
        }
    }
    for (const auto& inst : scene.instances) ASSERT_LT(inst.mesh, scene.meshes.size());
}

class CornellBox : public ::testing::Test {
protected:
    static void SetUpTestSuite() { scene_ = new Scene(loadGltf(sourceDir() / "scenes/cornell_box.gltf")); }
    static void TearDownTestSuite() { delete scene_; }
    static Scene* scene_;
};
Scene* CornellBox::scene_ = nullptr;

TEST_F(CornellBox, CountsMatchTheGenerator) {
    const Scene& s = *scene_;
    EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
    EXPECT_EQ(s.meshes.size(), 8u);    // floor, ceiling, back, left, right, short block, tall block, light
    EXPECT_EQ(triangleCount(s), 32u);  // 5 walls x 2 + 2 blocks x 5 faces x 2 + light 2
    EXPECT_EQ(triangleCount(meshNamed(s, "short_block")), 10u);
    EXPECT_EQ(triangleCount(meshNamed(s, "tall_block")), 10u);
    EXPECT_EQ(triangleCount(meshNamed(s, "light")), 2u);
    EXPECT_EQ(s.materials.size(), 4u);
    EXPECT_EQ(s.instances.size(), 8u);
    EXPECT_EQ(s.nodes.size(), 10u);
    EXPECT_EQ(s.rootNodes.size(), 10u);
    ASSERT_EQ(s.cameras.size(), 1u);
    ASSERT_EQ(s.lights.size(), 1u);
    EXPECT_TRUE(s.textures.empty());
    expectWellFormed(s);
}

TEST_F(CornellBox, BoundsAreThePublishedMeasurementsInMetres) {
    // Data frame (mm): x 0..556.0, y 0..548.8, z 0..559.2; glTF frame = (-x, y, -z) / 1000.
    const Aabb& b = scene_->bounds;
    ASSERT_FALSE(b.empty());
    expectVec3Near(b.min, {-0.556f, 0.0f, -0.5592f}, 1e-4f);
    expectVec3Near(b.max, {0.0f, 0.5488f, 0.0f}, 1e-4f);
}

TEST_F(CornellBox, MaterialsAndEmissiveStrength) {
    const auto& m = scene_->materials;
    expectVec3Near(glm::vec3(m[0].baseColorFactor), glm::vec3(0.73f), 1e-6f);
    expectVec3Near(glm::vec3(m[1].baseColorFactor), {0.65f, 0.05f, 0.05f}, 1e-6f);
    expectVec3Near(glm::vec3(m[2].baseColorFactor), {0.12f, 0.45f, 0.15f}, 1e-6f);
    for (const auto& mat : m) {
        EXPECT_EQ(mat.metallic, 0.0f);
        EXPECT_EQ(mat.roughness, 1.0f);
        EXPECT_EQ(mat.alphaMode, AlphaMode::Opaque);
    }
    expectVec3Near(m[0].emissive, glm::vec3(0.0f), 0.0f);
    // emissiveFactor (1, 12/17, 4/17) times KHR_materials_emissive_strength 17.
    expectVec3Near(m[3].emissive, {17.0f, 12.0f, 4.0f}, 1e-4f);
    EXPECT_EQ(meshNamed(*scene_, "light").primitives[0].material, 3u);
    EXPECT_EQ(meshNamed(*scene_, "left_wall_red").primitives[0].material, 1u);
    EXPECT_EQ(meshNamed(*scene_, "right_wall_green").primitives[0].material, 2u);
}

TEST_F(CornellBox, PublishedCamera) {
    const Camera& c = scene_->cameras[0];
    EXPECT_EQ(c.type, CameraType::Perspective);
    expectVec3Near(glm::vec3(c.world[3]), {-0.278f, 0.273f, 0.8f}, 1e-6f);  // (278, 273, -800) mm
    expectVec3Near(-glm::vec3(c.world[2]), {0.0f, 0.0f, -1.0f}, 1e-6f);     // looks into the box
    EXPECT_NEAR(c.yfov, 2.0 * std::atan(12.5 / 35.0), 1e-6);                // 35 mm lens, 25 mm film
    EXPECT_NEAR(c.yfov * 180.0 / M_PI, 39.3076, 1e-3);
    EXPECT_EQ(c.aspectRatio, 1.0f);
    EXPECT_EQ(scene_->nodes[c.node].camera, 0u);
}

TEST_F(CornellBox, PointLightUnderTheCeiling) {
    const Light& l = scene_->lights[0];
    EXPECT_EQ(l.type, LightType::Point);
    expectVec3Near(l.position, {-0.278f, 0.5388f, -0.2795f}, 1e-6f);
    expectVec3Near(l.color, {1.0f, 12.0f / 17.0f, 4.0f / 17.0f}, 1e-6f);
    EXPECT_NEAR(l.intensity, 17.0 * 0.130 * 0.105, 1e-5);  // on-axis intensity of the area light, L * A
    EXPECT_LT(l.position.y, scene_->bounds.max.y);
}

TEST_F(CornellBox, NormalsFaceIntoTheRoomAndOutOfTheBlocks) {
    const glm::vec3 roomCentre(-0.278f, 0.2744f, -0.2796f);
    for (const char* wall : {"floor", "ceiling", "back_wall", "left_wall_red", "right_wall_green"}) {
        const auto& p = meshNamed(*scene_, wall).primitives[0];
        for (size_t t = 0; t < p.indices.size(); t += 3) {
            const glm::vec3 a = p.positions[p.indices[t]], b = p.positions[p.indices[t + 1]],
                            c = p.positions[p.indices[t + 2]];
            const glm::vec3 n = p.normals[p.indices[t]];
            EXPECT_NEAR(glm::length(n), 1.0f, 1e-5f);
            EXPECT_GT(glm::dot(n, roomCentre - (a + b + c) / 3.0f), 0.0f) << wall;
            EXPECT_GT(glm::dot(glm::cross(b - a, c - a), n), 0.0f)
                << wall << ": winding must be CCW seen from the normal";
        }
    }
    expectVec3Near(meshNamed(*scene_, "floor").primitives[0].normals[0], {0, 1, 0}, 1e-6f);
    expectVec3Near(meshNamed(*scene_, "light").primitives[0].normals[0], {0, -1, 0}, 1e-6f);
    for (const char* block : {"short_block", "tall_block"}) {
        const auto& p = meshNamed(*scene_, block).primitives[0];
        glm::vec3 centre(0.0f);
        for (const auto& v : p.positions) centre += v;
        centre /= float(p.positions.size());
        for (size_t t = 0; t < p.indices.size(); t += 3) {
            const glm::vec3 faceCentre =
                (p.positions[p.indices[t]] + p.positions[p.indices[t + 1]] + p.positions[p.indices[t + 2]]) / 3.0f;
            EXPECT_GT(glm::dot(p.normals[p.indices[t]], faceCentre - centre), 0.0f) << block;
        }
    }
}

TEST_F(CornellBox, FileIsSmall) {
    EXPECT_LT(std::filesystem::file_size(sourceDir() / "scenes/cornell_box.gltf"), 100u * 1024u);
}

TEST(LoadFromMemory, SameSceneAndNamedErrors) {
    const auto bytes = test::readBytes(sourceDir() / "scenes/cornell_box.gltf");
    const Scene s = loadGltfFromMemory(bytes, "embedded:cornell_box.gltf");
    EXPECT_EQ(s.sourcePath, "embedded:cornell_box.gltf");
    EXPECT_EQ(s.meshes.size(), 8u);
    EXPECT_EQ(triangleCount(s), 32u);
    const auto glb = test::readBytes(sharedScene("Box/glTF-Binary/Box.glb"));
    EXPECT_EQ(triangleCount(loadGltfFromMemory(glb, "box.glb")), 12u);
    try {
        loadGltfFromMemory(std::span<const uint8_t>(glb.data(), glb.size() - 9), "embedded:box.glb");
        FAIL() << "expected LoadError";
    } catch (const LoadError& e) {
        EXPECT_EQ(std::string(e.what()).rfind("embedded:box.glb: truncated GLB", 0), 0u) << e.what();
    }
}

TEST(SharedAssets, BoxGlb) {
    const Scene s = loadGltf(sharedScene("Box/glTF-Binary/Box.glb"));
    EXPECT_EQ(s.meshes.size(), 1u);
    EXPECT_EQ(triangleCount(s), 12u);
    EXPECT_EQ(s.instances.size(), 1u);
    EXPECT_EQ(s.materials.size(), 1u);
    EXPECT_TRUE(s.cameras.empty());
    EXPECT_TRUE(s.warnings.empty());
    expectWellFormed(s);
    // A unit cube (the file rotates it from Z-up to Y-up).
    expectVec3Near(s.bounds.min, glm::vec3(-0.5f), 1e-5f);
    expectVec3Near(s.bounds.max, glm::vec3(0.5f), 1e-5f);
}

TEST(SharedAssets, BoxTexturedReferencesItsTexture) {
    const Scene s = loadGltf(sharedScene("BoxTextured/glTF-Binary/BoxTextured.glb"));
    EXPECT_EQ(triangleCount(s), 12u);
    ASSERT_EQ(s.materials.size(), 1u);
    ASSERT_TRUE(s.materials[0].baseColorTexture.has_value());
    const TextureRef& ref = *s.materials[0].baseColorTexture;
    ASSERT_LT(ref.texture, s.textures.size());
    EXPECT_EQ(ref.texCoord, 0u);
    const Texture& tex = s.textures[ref.texture];
    ASSERT_TRUE(tex.image.has_value());
    ASSERT_LT(*tex.image, s.images.size());
    const Image& img = s.images[*tex.image];
    EXPECT_EQ(img.mimeType, "image/png");
    ASSERT_GE(img.encoded.size(), 8u);  // kept encoded: the PNG signature, not pixels
    EXPECT_EQ(img.encoded[0], 0x89);
    EXPECT_EQ(img.encoded[1], 'P');
    EXPECT_TRUE(img.path.empty());
    for (const auto& p : s.meshes[0].primitives) EXPECT_EQ(p.uv0.size(), p.positions.size());
}

TEST(SharedAssets, MeshPrimitiveModesSkipsPointsAndLinesWithOneWarning) {
    const Scene s = loadGltf(sharedScene("MeshPrimitiveModes/glTF/MeshPrimitiveModes.gltf"));
    ASSERT_EQ(s.meshes.size(), 7u);  // indices stay stable: skipped primitives leave empty meshes
    for (size_t m = 0; m < 4; ++m) EXPECT_TRUE(s.meshes[m].primitives.empty()) << s.meshes[m].name;
    EXPECT_EQ(triangleCount(s.meshes[4]), 6u);  // TRIANGLES, 18 indices
    EXPECT_EQ(triangleCount(s.meshes[5]), 4u);  // TRIANGLE_STRIP, 6 indices
    EXPECT_EQ(triangleCount(s.meshes[6]), 6u);  // TRIANGLE_FAN, 8 indices
    EXPECT_EQ(s.instances.size(), 3u);
    ASSERT_EQ(s.warnings.size(), 1u);
    for (const char* mode : {"POINTS", "LINES", "LINE_LOOP", "LINE_STRIP"})
        EXPECT_NE(s.warnings[0].find(mode), std::string::npos) << s.warnings[0];
    expectWellFormed(s);
    // The file has no normals: flat normals come from the winding, which strips and fans must keep (+Z here).
    for (size_t m = 4; m < 7; ++m)
        for (const auto& n : s.meshes[m].primitives[0].normals) expectVec3Near(n, {0, 0, 1}, 1e-6f);
}

TEST(SharedAssets, DuckQuantized) {
    const Scene s = loadGltf(sharedScene("Duck/glTF-Quantized/Duck.gltf"));
    ASSERT_EQ(s.meshes.size(), 1u);
    EXPECT_EQ(triangleCount(s), 12636u / 3u);
    expectWellFormed(s);
    const Primitive& p = s.meshes[0].primitives[0];
    EXPECT_EQ(p.uv0.size(), p.positions.size());
    // Positions are unnormalized uint16; the node scale 0.000101006161 turns 16383 units into metres.
    EXPECT_NEAR(s.bounds.max.x - s.bounds.min.x, 16383.0 * 0.000101006161, 1e-3);
    // Normals are normalized int8: unit length up to quantization error.
    for (size_t i = 0; i < p.normals.size(); i += 97) EXPECT_NEAR(glm::length(p.normals[i]), 1.0f, 0.02f);
    // The UV dequantization lives in KHR_texture_transform on the base-colour texture.
    ASSERT_TRUE(s.materials[0].baseColorTexture.has_value());
    EXPECT_NEAR(s.materials[0].baseColorTexture->scale.x, 0.000233684244, 1e-9);
    EXPECT_NEAR(s.materials[0].baseColorTexture->offset.y, 0.019963026, 1e-9);
    ASSERT_EQ(s.images.size(), 1u);
    EXPECT_EQ(s.images[0].path.filename(), "DuckCM.png");  // external: recorded, not read
    EXPECT_TRUE(s.images[0].encoded.empty());
    // The camera hangs under a node scaled by 0.01: its placement keeps the position but drops the scale.
    ASSERT_EQ(s.cameras.size(), 1u);
    const Camera& c = s.cameras[0];
    expectVec3Near(glm::vec3(c.world[3]), {4.00113f, 4.63264f, -4.31078f}, 1e-4f);
    EXPECT_NEAR(glm::length(glm::vec3(c.world[2])), 1.0f, 1e-5f);
    const glm::vec3 toDuck = glm::normalize(s.bounds.centre() - glm::vec3(c.world[3]));
    EXPECT_GT(glm::dot(-glm::vec3(c.world[2]), toDuck), 0.95f);
}

TEST(SharedAssets, ManyAssetsLoadWellFormed) {
    for (const char* file : {"OrientationTest/glTF-Binary/OrientationTest.glb", "SimpleSkin/glTF/SimpleSkin.gltf",
                             "AnimatedMorphCube/glTF-Binary/AnimatedMorphCube.glb", "Fox/glTF-Binary/Fox.glb",
                             "SimpleInstancing/glTF-Binary/SimpleInstancing.glb",
                             "EmissiveStrengthTest/glTF-Binary/EmissiveStrengthTest.glb",
                             "AlphaBlendModeTest/glTF-Binary/AlphaBlendModeTest.glb"}) {
        if (!std::filesystem::exists(sharedScene(file))) continue;
        SCOPED_TRACE(file);
        const Scene s = loadGltf(sharedScene(file));
        EXPECT_FALSE(s.meshes.empty());
        EXPECT_FALSE(s.bounds.empty());
        expectWellFormed(s);
    }
}

TEST(SharedAssets, EmissiveStrengthTestMultipliesTheFactor) {
    const Scene s = loadGltf(sharedScene("EmissiveStrengthTest/glTF-Binary/EmissiveStrengthTest.glb"));
    float maxEmissive = 0.0f;
    for (const auto& m : s.materials) maxEmissive = std::max({maxEmissive, m.emissive.x, m.emissive.y, m.emissive.z});
    EXPECT_NEAR(maxEmissive, 0.9f * 16.0f, 1e-4f);  // factor 0.9 times emissiveStrength 16
}

}  // namespace
}  // namespace idk::scene
