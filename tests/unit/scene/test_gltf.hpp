// test_gltf.hpp: hand-written glTF files for the scene tests: a JSON document plus one binary buffer embedded as
// a base64 data URI (GltfFile), the one-triangle base file the hostile tests mutate, and expectLoadError().
#pragma once

#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "scene/gltf_loader.hpp"
#include "test_files.hpp"

namespace idk::scene::test {

using nlohmann::json;

// A one-triangle glTF: buffer = 3 float positions (36 bytes) + 3 uint16 indices (6 bytes) + 2 padding bytes.
struct GltfFile {
    json doc;
    std::vector<uint8_t> buffer;

    template <class T>
    size_t append(const std::vector<T>& values) {  // 4-byte aligned, returns the offset
        while (buffer.size() % 4) buffer.push_back(0);
        const size_t offset = buffer.size();
        buffer.resize(offset + values.size() * sizeof(T));
        std::memcpy(buffer.data() + offset, values.data(), values.size() * sizeof(T));
        return offset;
    }

    std::filesystem::path write(const TempDir& dir, const std::string& name = "test.gltf") {
        json out = doc;
        if (!out["buffers"].empty() && !out["buffers"][0].contains("uri"))
            out["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64(buffer);
        if (!out["buffers"].empty() && !out["buffers"][0].contains("byteLength"))
            out["buffers"][0]["byteLength"] = buffer.size();
        const auto path = dir / name;
        writeText(path, out.dump());
        return path;
    }

    // The same as a GLB: buffer 0 (which must have no uri) becomes the BIN chunk.
    std::filesystem::path writeGlb(const TempDir& dir, const std::string& name = "test.glb") {
        json out = doc;
        out["buffers"][0]["byteLength"] = buffer.size();
        std::string text = out.dump();
        while (text.size() % 4) text += ' ';
        std::vector<uint8_t> bin = buffer;
        while (bin.size() % 4) bin.push_back(0);
        std::vector<uint8_t> glb;
        auto u32 = [&](uint32_t v) {
            for (int i = 0; i < 4; ++i) glb.push_back(uint8_t(v >> (8 * i)));
        };
        u32(0x46546C67);
        u32(2);
        u32(uint32_t(12 + 8 + text.size() + 8 + bin.size()));
        u32(uint32_t(text.size()));
        u32(0x4E4F534A);
        glb.insert(glb.end(), text.begin(), text.end());
        u32(uint32_t(bin.size()));
        u32(0x004E4942);
        glb.insert(glb.end(), bin.begin(), bin.end());
        const auto path = dir / name;
        writeBytes(path, glb.data(), glb.size());
        return path;
    }
};

inline GltfFile triangle() {
    GltfFile f;
    f.append(std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0});
    f.append(std::vector<uint16_t>{0, 1, 2});
    f.doc = json::parse(R"({
      "asset": {"version": "2.0"},
      "scene": 0,
      "scenes": [{"nodes": [0]}],
      "nodes": [{"mesh": 0}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
      "accessors": [
        {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0,0,0], "max": [1,1,0]},
        {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}],
      "bufferViews": [
        {"buffer": 0, "byteOffset": 0, "byteLength": 36},
        {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
      "buffers": [{}]
    })");
    return f;
}

// Loads and expects a LoadError whose message names the file and contains `cause`.
inline void expectLoadError(const std::filesystem::path& path, const std::string& cause) {
    try {
        const Scene s = loadGltf(path);
        ADD_FAILURE() << "expected LoadError containing '" << cause << "', loaded " << s.meshes.size() << " meshes";
    } catch (const LoadError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find(path.string()), std::string::npos) << what;
        EXPECT_NE(what.find(cause), std::string::npos) << "message: " << what << "\nexpected: " << cause;
        EXPECT_EQ(e.file(), path);
    } catch (const std::exception& e) {
        ADD_FAILURE() << "expected LoadError, got another exception: " << e.what();
    }
}

}  // namespace idk::scene::test
