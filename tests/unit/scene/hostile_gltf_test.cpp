// hostile_gltf_test.cpp: loadGltf() on damaged and malicious files (missing, truncated GLB, indices and byte
// ranges out of range, cycles, unsupported required extensions, random byte mutations): always a LoadError that
// names the file and the cause, never a crash. Also the accessor decoding paths (component types, sparse,
// non-indexed) on small hand-written files.
#include <cstring>
#include <random>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "scene/gltf_loader.hpp"
#include "test_files.hpp"
#include "test_gltf.hpp"

namespace idk::scene {
namespace {

using nlohmann::json;
using test::expectLoadError;
using test::GltfFile;
using test::TempDir;
using test::triangle;

TEST(HostileGltf, TheBaseTriangleLoads) {
    TempDir dir;
    const Scene s = loadGltf(triangle().write(dir));
    ASSERT_EQ(s.meshes.size(), 1u);
    ASSERT_EQ(s.meshes[0].primitives.size(), 1u);
    EXPECT_EQ(s.meshes[0].primitives[0].indices.size(), 3u);
    EXPECT_EQ(s.meshes[0].primitives[0].normals[0], glm::vec3(0, 0, 1));  // flat normal from the CCW winding
    EXPECT_EQ(s.instances.size(), 1u);
    EXPECT_EQ(s.bounds.max, glm::vec3(1, 1, 0));
}

TEST(HostileGltf, MissingFile) {
    TempDir dir;
    expectLoadError(dir / "does_not_exist.gltf", "file not found");
}

TEST(HostileGltf, EmptyFileAndInvalidJson) {
    TempDir dir;
    test::writeText(dir / "empty.gltf", "");
    expectLoadError(dir / "empty.gltf", "empty file");
    test::writeText(dir / "bad.gltf", "{ \"asset\": { \"version\": \"2.0\" }, \"nodes\": [ { oops");
    expectLoadError(dir / "bad.gltf", "parse error");
}

TEST(HostileGltf, DeeplyNestedJsonIsRejectedNotAStackOverflow) {
    const size_t depth = 200000;
    const std::string text = R"({"asset": {"version": "2.0"}, "extras": )" + std::string(depth, '[') +
                             std::string(depth, ']') + "}";
    const std::span<const uint8_t> bytes(reinterpret_cast<const uint8_t*>(text.data()), text.size());
    try {
        loadGltfFromMemory(bytes, "deep.gltf");
        FAIL() << "expected LoadError";
    } catch (const LoadError& e) {
        EXPECT_NE(std::string(e.what()).find("nested deeper than"), std::string::npos) << e.what();
    }
    // Brackets inside strings do not count.
    const std::string quoted = R"({"asset": {"version": "2.0", "generator": ")" + std::string(1000, '[') + R"("}})";
    EXPECT_NO_THROW(loadGltfFromMemory(
        std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(quoted.data()), quoted.size()), "quoted.gltf"));
}

TEST(HostileGltf, AccessorIndexOutOfRange) {
    TempDir dir;
    auto f = triangle();
    f.doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 7;
    expectLoadError(f.write(dir), "accessor 7 out of range");
}

TEST(HostileGltf, IndicesAccessorOutOfRange) {
    TempDir dir;
    auto f = triangle();
    f.doc["meshes"][0]["primitives"][0]["indices"] = 9;
    expectLoadError(f.write(dir), "parse error");  // tinygltf itself checks primitive.indices
}

TEST(HostileGltf, BufferViewPastTheEndOfItsBuffer) {
    TempDir dir;
    auto f = triangle();
    f.doc["bufferViews"][0]["byteLength"] = 1000;
    expectLoadError(f.write(dir), "extends past the end of buffer 0");
}

TEST(HostileGltf, BufferViewWithHugeOffsetDoesNotOverflow) {
    TempDir dir;
    auto f = triangle();
    f.doc["bufferViews"][0]["byteOffset"] = 18446744073709551000ull;
    expectLoadError(f.write(dir), "");
}

TEST(HostileGltf, AccessorPastTheEndOfItsBufferView) {
    TempDir dir;
    auto f = triangle();
    f.doc["accessors"][0]["count"] = 100;
    expectLoadError(f.write(dir), "extend past the end of bufferView 0");
    f = triangle();
    f.doc["accessors"][0]["byteOffset"] = 4611686018427387904ull;  // 2^62
    expectLoadError(f.write(dir), "extend past the end of bufferView 0");
}

TEST(HostileGltf, BufferViewIndexAndBufferIndexOutOfRange) {
    TempDir dir;
    auto f = triangle();
    f.doc["accessors"][0]["bufferView"] = 5;
    expectLoadError(f.write(dir), "bufferView 5 out of range");
    f = triangle();
    f.doc["bufferViews"][0]["buffer"] = 3;
    expectLoadError(f.write(dir), "buffer 3 out of range");
}

TEST(HostileGltf, StrideSmallerThanTheElement) {
    TempDir dir;
    auto f = triangle();
    f.doc["bufferViews"][0]["byteStride"] = 4;
    expectLoadError(f.write(dir), "smaller than the element size");
}

TEST(HostileGltf, VertexIndexOutOfRange) {
    TempDir dir;
    auto f = triangle();
    f.doc["accessors"][0]["count"] = 2;
    expectLoadError(f.write(dir), "index 2 out of range (2 vertices)");
}

TEST(HostileGltf, WrongAccessorTypeAndComponentType) {
    TempDir dir;
    auto f = triangle();
    f.doc["accessors"][0]["type"] = "VEC2";
    expectLoadError(f.write(dir), "type must have 3 components");
    f = triangle();
    f.doc["accessors"][1]["componentType"] = 5126;
    expectLoadError(f.write(dir), "not an unsigned integer type");
}

TEST(HostileGltf, UnsupportedRequiredExtensionIsNamed) {
    TempDir dir;
    auto f = triangle();
    f.doc["extensionsUsed"] = {"EXT_made_up"};
    f.doc["extensionsRequired"] = {"EXT_made_up"};
    expectLoadError(f.write(dir), "requires unsupported extension EXT_made_up");
}

TEST(HostileGltf, UsedButNotRequiredExtensionIsAWarning) {
    TempDir dir;
    auto f = triangle();
    f.doc["extensionsUsed"] = {"EXT_made_up"};
    const Scene s = loadGltf(f.write(dir));
    ASSERT_EQ(s.warnings.size(), 1u);
    EXPECT_NE(s.warnings[0].find("EXT_made_up"), std::string::npos);
}

TEST(HostileGltf, NodeHierarchyMustBeATree) {
    TempDir dir;
    auto f = triangle();
    f.doc["nodes"] = json::parse(R"([{"mesh": 0, "children": [1]}, {"children": [0]}])");
    expectLoadError(f.write(dir), "node");
    f = triangle();
    f.doc["nodes"] = json::parse(R"([{"mesh": 0, "children": [0]}])");
    expectLoadError(f.write(dir), "more than one parent");
    f = triangle();
    f.doc["nodes"] = json::parse(R"([{"mesh": 0, "children": [1, 1]}, {}])");
    expectLoadError(f.write(dir), "more than one parent");
    f = triangle();
    f.doc["nodes"] = json::parse(R"([{"mesh": 0, "children": [-1]}])");
    expectLoadError(f.write(dir), "child -1 out of range");
    f = triangle();
    f.doc["nodes"] = json::parse(R"([{"children": [1]}, {"children": [2]}, {"children": [1]}])");
    expectLoadError(f.write(dir), "more than one parent");
}

TEST(HostileGltf, OtherIndicesOutOfRange) {
    TempDir dir;
    auto f = triangle();
    f.doc["nodes"][0]["mesh"] = 4;
    expectLoadError(f.write(dir), "mesh 4 out of range");
    f = triangle();
    f.doc["meshes"][0]["primitives"][0]["material"] = 2;
    expectLoadError(f.write(dir), "material 2 out of range");
    f = triangle();
    f.doc["scene"] = 3;
    expectLoadError(f.write(dir), "");
    f = triangle();
    f.doc["scenes"][0]["nodes"] = {6};
    expectLoadError(f.write(dir), "");
    f = triangle();
    f.doc["materials"] = json::parse(R"([{"pbrMetallicRoughness": {"baseColorTexture": {"index": 3}}}])");
    expectLoadError(f.write(dir), "texture 3 out of range");
    f = triangle();
    f.doc["nodes"][0]["extensions"] = json::parse(R"({"KHR_lights_punctual": {"light": 2}})");
    expectLoadError(f.write(dir), "light index out of range");
}

TEST(HostileGltf, SparseAccessors) {
    TempDir dir;
    auto f = triangle();
    // Positions without a bufferView (all zeros) plus a sparse substitution of vertices 1 and 2.
    const size_t idx = f.append(std::vector<uint8_t>{1, 2, 0, 0});
    const size_t val = f.append(std::vector<float>{2, 0, 0, 0, 2, 0});
    f.doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", idx}, {"byteLength", 2}});
    f.doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", val}, {"byteLength", 24}});
    f.doc["accessors"][0].erase("bufferView");
    f.doc["accessors"][0]["sparse"] = json::parse(
        R"({"count": 2, "indices": {"bufferView": 2, "componentType": 5121}, "values": {"bufferView": 3}})");
    {
        const Scene s = loadGltf(f.write(dir));
        const auto& p = s.meshes[0].primitives[0].positions;
        ASSERT_EQ(p.size(), 3u);
        EXPECT_EQ(p[0], glm::vec3(0, 0, 0));
        EXPECT_EQ(p[1], glm::vec3(2, 0, 0));
        EXPECT_EQ(p[2], glm::vec3(0, 2, 0));
    }
    auto bad = f;
    bad.buffer[idx + 1] = 7;  // sparse index past the accessor's count
    expectLoadError(bad.write(dir), "sparse index 7 out of range");
    bad = f;
    bad.doc["accessors"][0]["sparse"]["count"] = 5;
    expectLoadError(bad.write(dir), "sparse count 5 exceeds");
    bad = f;
    bad.doc["accessors"][0]["sparse"]["values"]["byteOffset"] = 20;
    expectLoadError(bad.write(dir), "extend past the end of bufferView 3");
}

TEST(HostileGltf, HugeAccessorWithoutBufferViewIsRejected) {
    TempDir dir;
    auto f = triangle();
    f.doc["accessors"][0].erase("bufferView");
    f.doc["accessors"][0]["count"] = 4000000000ull;
    expectLoadError(f.write(dir), "too large");
}

TEST(HostileGltf, MissingExternalBuffer) {
    TempDir dir;
    auto f = triangle();
    f.doc["buffers"][0]["uri"] = "missing.bin";
    expectLoadError(f.write(dir), "parse error");
}

TEST(AccessorDecoding, NonIndexedPrimitiveAndComponentTypes) {
    TempDir dir;
    auto f = triangle();
    // Non-indexed: 3 vertices -> one triangle.
    f.doc["meshes"][0]["primitives"][0].erase("indices");
    // Normalized unsigned-byte UVs (KHR_mesh_quantization allows them; they are core glTF too).
    const size_t uv = f.append(std::vector<uint8_t>{0, 0, 0, 0, 255, 0, 0, 0, 0, 255, 0, 0});
    f.doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", uv}, {"byteLength", 12}, {"byteStride", 4}});
    f.doc["accessors"].push_back(
        {{"bufferView", 2}, {"componentType", 5121}, {"normalized", true}, {"count", 3}, {"type", "VEC2"}});
    f.doc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = 2;
    // Normalized signed-byte normals, padded to 4 bytes per element.
    const size_t nrm = f.append(std::vector<int8_t>{0, 0, 127, 0, 0, 0, -128, 0, 127, 0, 0, 0});
    f.doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", nrm}, {"byteLength", 12}, {"byteStride", 4}});
    f.doc["accessors"].push_back(
        {{"bufferView", 3}, {"componentType", 5120}, {"normalized", true}, {"count", 3}, {"type", "VEC3"}});
    f.doc["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = 3;
    const Scene s = loadGltf(f.write(dir));
    const Primitive& p = s.meshes[0].primitives[0];
    EXPECT_EQ(p.indices, (std::vector<uint32_t>{0, 1, 2}));
    ASSERT_EQ(p.uv0.size(), 3u);
    EXPECT_EQ(p.uv0[1], glm::vec2(1, 0));
    EXPECT_EQ(p.uv0[2], glm::vec2(0, 1));
    ASSERT_EQ(p.normals.size(), 3u);
    EXPECT_EQ(p.normals[0], glm::vec3(0, 0, 1));
    EXPECT_EQ(p.normals[1], glm::vec3(0, 0, -1));  // -128 clamps to -1
    EXPECT_EQ(p.normals[2], glm::vec3(1, 0, 0));
}

TEST(AccessorDecoding, IndexComponentTypesAndQuantizedPositions) {
    TempDir dir;
    for (const int componentType : {5121, 5123, 5125}) {
        auto f = triangle();
        f.doc["extensionsUsed"] = {"KHR_mesh_quantization"};
        f.doc["extensionsRequired"] = {"KHR_mesh_quantization"};
        // Positions as unnormalized int16 (KHR_mesh_quantization), stride 8.
        const size_t pos = f.append(std::vector<int16_t>{0, 0, 0, 0, 10, 0, 0, 0, 0, -10, 0, 0});
        f.doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", pos}, {"byteLength", 24}, {"byteStride", 8}});
        f.doc["accessors"][0] = {{"bufferView", 2}, {"componentType", 5122}, {"count", 3},
                                 {"type", "VEC3"},  {"min", {0, -10, 0}},    {"max", {10, 0, 0}}};
        size_t ib = 0;
        if (componentType == 5121) ib = f.append(std::vector<uint8_t>{0, 2, 1});
        if (componentType == 5123) ib = f.append(std::vector<uint16_t>{0, 2, 1});
        if (componentType == 5125) ib = f.append(std::vector<uint32_t>{0, 2, 1});
        const size_t size = componentType == 5121 ? 1 : componentType == 5123 ? 2 : 4;
        f.doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", ib}, {"byteLength", 3 * size}});
        f.doc["accessors"][1] = {{"bufferView", 3}, {"componentType", componentType}, {"count", 3}, {"type", "SCALAR"}};
        const Scene s = loadGltf(f.write(dir));
        SCOPED_TRACE(componentType);
        const Primitive& p = s.meshes[0].primitives[0];
        // No normals in the file: flat normals un-share the vertices in index order (0, 2, 1).
        EXPECT_EQ(p.positions[1], glm::vec3(0, -10, 0));
        EXPECT_EQ(p.positions[2], glm::vec3(10, 0, 0));
        EXPECT_EQ(p.normals[0], glm::vec3(0, 0, 1));  // (0, 2, 1) winds counter-clockwise seen from +Z
        EXPECT_EQ(s.bounds.min, glm::vec3(0, -10, 0));
    }
}

TEST(HostileGlb, TruncatedCopyOnDisk) {
    TempDir dir;
    const auto bytes = test::readBytes(test::sharedScene("Box/glTF-Binary/Box.glb"));
    test::writeBytes(dir / "truncated.glb", bytes.data(), bytes.size() / 2);
    expectLoadError(dir / "truncated.glb", "truncated GLB");
}

// Every prefix of a GLB (in memory: the same code path after the file read, without a disk write per case).
TEST(HostileGlb, EveryTruncationIsALoadError) {
    const auto bytes = test::readBytes(test::sharedScene("Box/glTF-Binary/Box.glb"));
    ASSERT_GT(bytes.size(), 100u);
    for (size_t n = 1; n < bytes.size(); ++n) {
        try {
            loadGltfFromMemory(std::span<const uint8_t>(bytes.data(), n), "truncated.glb");
            ADD_FAILURE() << "a GLB truncated to " << n << " bytes loaded";
        } catch (const LoadError& e) {
            EXPECT_EQ(std::string(e.what()).rfind("truncated.glb: ", 0), 0u);
        }
    }
}

TEST(HostileGlb, ChunkLengthPastTheEnd) {
    TempDir dir;
    auto bytes = test::readBytes(test::sharedScene("Box/glTF-Binary/Box.glb"));
    uint32_t jsonLength = 0;
    std::memcpy(&jsonLength, bytes.data() + 12, 4);
    const uint32_t huge = 0x7FFFFFF0u;
    std::memcpy(bytes.data() + 20 + jsonLength, &huge, 4);  // BIN chunk length
    test::writeBytes(dir / "chunk.glb", bytes.data(), bytes.size());
    expectLoadError(dir / "chunk.glb", "past the end of the file");
}

// Random byte mutations of a GLB and of a .gltf: every outcome must be a Scene or a LoadError.
TEST(HostileGlb, RandomMutationsNeverCrash) {
    const auto glb = test::readBytes(test::sharedScene("Box/glTF-Binary/Box.glb"));
    const auto gltf = test::readBytes(test::sourceDir() / "scenes/cornell_box.gltf");
    std::mt19937 rng(12345);
    int loaded = 0, rejected = 0;
    for (int iteration = 0; iteration < 600; ++iteration) {
        auto bytes = (iteration % 2 == 0) ? glb : gltf;
        const int edits = 1 + int(rng() % 4);
        for (int e = 0; e < edits; ++e) {
            const size_t at = rng() % bytes.size();
            if (iteration % 2 == 1 && rng() % 2 == 0) {
                bytes[at] = uint8_t('0' + rng() % 10);  // JSON: bend a number
            } else {
                bytes[at] = uint8_t(rng());
            }
        }
        try {
            loadGltfFromMemory(bytes, (iteration % 2 == 0) ? "mutated.glb" : "mutated.gltf");
            ++loaded;
        } catch (const LoadError&) {
            ++rejected;
        }
    }
    EXPECT_EQ(loaded + rejected, 600);
}

}  // namespace
}  // namespace idk::scene
