// memory_budget_test.cpp: LoadOptions::maxMemoryBytes (`--max-memory`). Each allocation the loader makes is
// charged before it happens: the file, external buffers, data URIs, accessor data (including accessors without a
// bufferView, which a few bytes of JSON can make 768 MiB large) and the decoded size PNG/JPEG headers declare.
// Going over is a LoadError naming the item, the numbers and the option; the same files load under a budget that
// fits, and without one. Peak RSS shows the refused accessor bomb was never allocated.
#include <sys/resource.h>

#include <gtest/gtest.h>

#include "scene/gltf_loader.hpp"
#include "test_files.hpp"
#include "test_gltf.hpp"

namespace idk::scene {
namespace {

using test::GltfFile;
using test::TempDir;

LoadOptions budget(uint64_t bytes) {
    LoadOptions o;
    o.maxMemoryBytes = bytes;
    return o;
}

void expectOverBudget(const std::filesystem::path& file, const LoadOptions& options, const std::string& item) {
    try {
        (void)loadGltf(file, options);
        ADD_FAILURE() << "loaded " << file << " under a budget of " << options.maxMemoryBytes << " bytes";
    } catch (const LoadError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find(file.string()), std::string::npos) << what;
        EXPECT_NE(what.find("memory budget exceeded: " + item), std::string::npos) << what;
        EXPECT_NE(what.find("--max-memory is"), std::string::npos) << what;
    }
}

TEST(MemoryBudget, TheTriangleFitsAGenerousBudgetAndNotATinyOne) {
    TempDir dir;
    const auto file = test::triangle().write(dir);
    EXPECT_EQ(loadGltf(file, budget(1 << 20)).meshes.size(), 1u);
    expectOverBudget(file, budget(64), "file test.gltf");  // the file itself is ~900 bytes
}

TEST(MemoryBudget, AnAccessorWithoutBufferViewIsRefusedBeforeAllocation) {
    TempDir dir;
    GltfFile f = test::triangle();
    // 2^26 VEC3 zeros: 768 MiB of floats from a few bytes of JSON.
    f.doc["accessors"][0] = {{"componentType", 5126}, {"count", 1 << 26}, {"type", "VEC3"},
                             {"min", {0, 0, 0}}, {"max", {0, 0, 0}}};
    f.doc["meshes"][0]["primitives"][0].erase("indices");
    const auto file = f.write(dir);
    rusage before{}, after{};
    getrusage(RUSAGE_SELF, &before);
    expectOverBudget(file, budget(size_t{64} << 20), "mesh 0 primitive 0 POSITION (accessor 0) needs 768.0 MiB");
    getrusage(RUSAGE_SELF, &after);
    EXPECT_LT(after.ru_maxrss - before.ru_maxrss, 64 * 1024) << "KiB of peak RSS growth";
}

TEST(MemoryBudget, ExternalBuffersAndDataUrisAreCharged) {
    TempDir dir;
    GltfFile f = test::triangle();
    std::vector<uint8_t> big(size_t{1} << 20, 0);
    test::writeBytes(dir / "big.bin", big.data(), big.size());
    f.doc["buffers"].push_back({{"uri", "big.bin"}, {"byteLength", big.size()}});
    const auto external = f.write(dir, "external.gltf");
    expectOverBudget(external, budget(512 << 10), "file big.bin");
    EXPECT_EQ(loadGltf(external, budget(4 << 20)).meshes.size(), 1u);

    GltfFile g = test::triangle();
    g.doc["buffers"].push_back({{"uri", "data:application/octet-stream;base64," + test::base64(big)},
                                {"byteLength", big.size()}});
    const auto embedded = g.write(dir, "embedded.gltf");
    expectOverBudget(embedded, budget(2 << 20), "buffer 1 data URI");  // the file (1.3 MiB) + 1 MiB decoded
    EXPECT_EQ(loadGltf(embedded, budget(4 << 20)).meshes.size(), 1u);
}

// An image is charged what it will decode to, from its header, when the scene is loaded.
TEST(MemoryBudget, ImagesAreChargedTheirDeclaredDecodedSize) {
    TempDir dir;
    // A PNG header declaring 8192 x 8192 (IHDR only: the loader reads nothing else; 341 MiB with mips).
    std::vector<uint8_t> png = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A, 0, 0, 0, 13, 'I', 'H', 'D', 'R',
                                0, 0, 0x20, 0, 0, 0, 0x20, 0, 8, 6, 0, 0, 0, 0, 0, 0, 0};
    test::writeBytes(dir / "huge.png", png.data(), png.size());
    GltfFile f = test::triangle();
    f.doc["images"] = {{{"uri", "huge.png"}}};
    const auto file = f.write(dir);
    expectOverBudget(file, budget(size_t{256} << 20), "image 0 (8192x8192 texels, decoded with mips) needs 341.3 MiB");
    EXPECT_EQ(loadGltf(file, budget(size_t{512} << 20)).images.size(), 1u);
    EXPECT_EQ(loadGltf(file).images.size(), 1u);  // no budget
}

}  // namespace
}  // namespace idk::scene
