// uri_confinement_test.cpp: external buffer and image URIs stay inside the asset's folder (asset_uri.hpp).
// resolveAssetUri() on its own (traversal, percent-encoding, absolute paths, NUL, symlinks, sibling-prefix
// folders), then loadGltf() on hostile .gltf and .glb files: each is a LoadError naming the file and the URI, and
// an inotify watch on the folder holding the target proves the file was never opened; allowExternalUris loads
// the same files (and reads the target).
#include <sys/inotify.h>
#include <unistd.h>

#include <cerrno>
#include <climits>

#include <gtest/gtest.h>

#include "scene/asset_uri.hpp"
#include "scene/gltf_loader.hpp"
#include "test_files.hpp"
#include "test_gltf.hpp"

namespace idk::scene {
namespace {

namespace fs = std::filesystem;
using test::GltfFile;
using test::TempDir;

// Counts open/read events on every file in a folder (inotify: the kernel reports them, no hook in the loader).
class OpenWatch {
public:
    explicit OpenWatch(const fs::path& folder) {
        fd_ = inotify_init1(IN_NONBLOCK | IN_CLOEXEC);
        EXPECT_GE(fd_, 0) << "inotify_init1: errno " << errno;
        EXPECT_GE(inotify_add_watch(fd_, folder.c_str(), IN_OPEN | IN_ACCESS), 0) << "inotify_add_watch " << folder;
    }
    ~OpenWatch() { ::close(fd_); }
    OpenWatch(const OpenWatch&) = delete;
    OpenWatch& operator=(const OpenWatch&) = delete;
    // Events since the last call.
    int events() {
        alignas(inotify_event) char buffer[16 * (sizeof(inotify_event) + NAME_MAX + 1)];
        int count = 0;
        for (ssize_t n; (n = ::read(fd_, buffer, sizeof(buffer))) > 0;)
            for (char* p = buffer; p < buffer + n; p += sizeof(inotify_event) + reinterpret_cast<inotify_event*>(p)->len)
                ++count;
        return count;
    }

private:
    int fd_ = -1;
};

// <tmp>/asset/ holds the scene; <tmp>/outside/secret.bin is the triangle's buffer and secret.png a PNG header.
struct Layout {
    TempDir dir;
    GltfFile file = test::triangle();
    fs::path asset = dir / "asset";
    fs::path outside = dir / "outside";
    Layout() {
        fs::create_directories(asset);
        fs::create_directories(outside);
        test::writeBytes(outside / "secret.bin", file.buffer.data(), file.buffer.size());
        const std::vector<uint8_t> png = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A, 0, 0, 0, 13, 'I', 'H', 'D', 'R'};
        test::writeBytes(outside / "secret.png", png.data(), png.size());
    }
    fs::path withBufferUri(const std::string& uri) {
        GltfFile f = file;
        f.doc["buffers"][0]["uri"] = uri;
        f.doc["buffers"][0]["byteLength"] = file.buffer.size();
        return f.write(dir, "asset/scene.gltf");
    }
    fs::path glbWithBufferUri(const std::string& uri) {  // buffer 0: the BIN chunk; the geometry in buffer 1
        GltfFile f = file;
        f.doc["buffers"].push_back({{"uri", uri}, {"byteLength", file.buffer.size()}});
        for (auto& view : f.doc["bufferViews"]) view["buffer"] = 1;
        return f.writeGlb(dir, "asset/scene.glb");
    }
    fs::path withImageUri(const std::string& uri) {
        GltfFile f = file;
        f.doc["images"] = {{{"uri", uri}}};
        return f.write(dir, "asset/scene.gltf");
    }
};

void expectRefused(const fs::path& file, const std::string& uri, const std::string& cause, OpenWatch& watch) {
    try {
        (void)loadGltf(file);
        ADD_FAILURE() << "loaded " << file << " with uri " << uri;
    } catch (const LoadError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find(file.string()), std::string::npos) << what;
        EXPECT_NE(what.find("uri '" + uri + "'"), std::string::npos) << what;
        EXPECT_NE(what.find(cause), std::string::npos) << what;
    }
    EXPECT_EQ(watch.events(), 0) << "a file outside the asset's folder was opened for " << uri;
}

TEST(AssetUri, PercentDecoding) {
    EXPECT_EQ(percentDecode("a%20b%2e%2E%2fc"), "a b../c");
    EXPECT_EQ(percentDecode("100%"), "100%");
    EXPECT_EQ(percentDecode("%zz%4"), "%zz%4");
    EXPECT_EQ(percentDecode("a+b"), "a+b");
}

TEST(AssetUri, ResolvesInsideAndRefusesEverythingElse) {
    Layout l;
    const fs::path scene = l.asset / "scene.gltf";
    const fs::path folder = fs::canonical(l.asset);
    EXPECT_EQ(resolveAssetUri(scene, "tex/a.png", false, "image 0"), folder / "tex/a.png");
    EXPECT_EQ(resolveAssetUri(scene, "tex/../a%20b.png", false, "image 0"), folder / "a b.png");
    auto refused = [&](const std::string& uri, const std::string& cause) {
        try {
            (void)resolveAssetUri(scene, uri, false, "buffer 3");
            ADD_FAILURE() << "accepted " << uri;
        } catch (const LoadError& e) {
            EXPECT_EQ(e.file(), scene);
            EXPECT_NE(e.cause().find("buffer 3 uri '" + uri + "'"), std::string::npos) << e.what();
            EXPECT_NE(e.cause().find(cause), std::string::npos) << e.what();
        }
    };
    refused("../outside/secret.bin", "outside the asset's folder");
    refused("tex/../../outside/secret.bin", "outside the asset's folder");
    refused("%2e%2e/outside/secret.bin", "outside the asset's folder");
    refused("..%2F..%2F..%2Fetc%2Fpasswd", "outside the asset's folder");
    refused("/etc/passwd", "absolute path");
    refused("%2Fetc%2Fpasswd", "absolute path");
    refused("a.bin%00../../x", "NUL byte");
    // A sibling folder whose name starts with the asset folder's name is not inside it.
    fs::create_directories(l.dir / "asset2");
    refused("../asset2/x.bin", "outside the asset's folder");
    // Allowed: the canonical target.
    EXPECT_EQ(resolveAssetUri(scene, "../outside/secret.bin", true, "buffer 0"),
              fs::canonical(l.outside / "secret.bin"));
    EXPECT_EQ(resolveAssetUri(scene, "/etc/passwd", true, "buffer 0"), fs::path("/etc/passwd"));
}

TEST(AssetUri, SymlinksAreResolvedBeforeTheCheck) {
    Layout l;
    const fs::path scene = l.asset / "scene.gltf";
    fs::create_symlink(l.outside / "secret.bin", l.asset / "link.bin");   // a file link leading out
    fs::create_directory_symlink(l.outside, l.asset / "linkdir");         // a folder link leading out
    fs::create_directories(l.asset / "real");
    fs::create_directory_symlink(l.asset / "real", l.asset / "inner");   // a link that stays inside
    EXPECT_THROW((void)resolveAssetUri(scene, "link.bin", false, "buffer 0"), LoadError);
    EXPECT_THROW((void)resolveAssetUri(scene, "linkdir/secret.bin", false, "buffer 0"), LoadError);
    EXPECT_EQ(resolveAssetUri(scene, "inner/x.png", false, "image 0"), fs::canonical(l.asset / "real") / "x.png");
    // The asset itself reached through a symlinked folder: its URIs resolve against the real folder.
    fs::create_directory_symlink(l.asset, l.dir / "alias");
    EXPECT_EQ(resolveAssetUri(l.dir / "alias/scene.gltf", "inner/x.png", false, "image 0"),
              fs::canonical(l.asset / "real") / "x.png");
}

TEST(UriConfinement, HostileBufferUrisAreRefusedBeforeAnyRead) {
    Layout l;
    fs::create_symlink(l.outside / "secret.bin", l.asset / "link.bin");
    OpenWatch watch(l.outside);
    const std::string absolute = (l.outside / "secret.bin").string();
    expectRefused(l.withBufferUri("../outside/secret.bin"), "../outside/secret.bin", "outside", watch);
    expectRefused(l.withBufferUri("%2e%2e/outside/secret.bin"), "%2e%2e/outside/secret.bin", "outside", watch);
    expectRefused(l.withBufferUri(absolute), absolute, "absolute path", watch);
    expectRefused(l.withBufferUri("link.bin"), "link.bin", "outside", watch);
    expectRefused(l.glbWithBufferUri("../outside/secret.bin"), "../outside/secret.bin", "outside", watch);
    expectRefused(l.glbWithBufferUri("link.bin"), "link.bin", "outside", watch);

    // --allow-external-uris: the same files load, and the geometry comes from the file outside.
    LoadOptions allow;
    allow.allowExternalUris = true;
    for (const std::string uri : {"../outside/secret.bin", "%2e%2e/outside/secret.bin", absolute.c_str(), "link.bin"}) {
        for (const fs::path& file : {l.withBufferUri(uri), l.glbWithBufferUri(uri)}) {
            const Scene s = loadGltf(file, allow);
            ASSERT_EQ(s.meshes.size(), 1u) << file << " " << uri;
            EXPECT_EQ(s.meshes[0].primitives[0].positions[1], glm::vec3(1, 0, 0)) << file;
        }
    }
    EXPECT_GT(watch.events(), 0) << "the allowed loads did read the file outside";
}

TEST(UriConfinement, HostileImageUrisAreRefusedBeforeAnyRead) {
    Layout l;
    fs::create_directory_symlink(l.outside, l.asset / "linkdir");
    OpenWatch watch(l.outside);
    expectRefused(l.withImageUri("../outside/secret.png"), "../outside/secret.png", "outside", watch);
    expectRefused(l.withImageUri("..%2foutside%2fsecret.png"), "..%2foutside%2fsecret.png", "outside", watch);
    expectRefused(l.withImageUri("linkdir/secret.png"), "linkdir/secret.png", "outside", watch);
    const std::string absolute = (l.outside / "secret.png").string();
    expectRefused(l.withImageUri(absolute), absolute, "absolute path", watch);

    LoadOptions allow;
    allow.allowExternalUris = true;
    const Scene s = loadGltf(l.withImageUri("../outside/secret.png"), allow);
    ASSERT_EQ(s.images.size(), 1u);
    EXPECT_EQ(s.images[0].path, fs::canonical(l.outside / "secret.png"));
    EXPECT_EQ(s.images[0].status, ImageStatus::Ok);
}

// tinygltf looks for a buffer in the asset's folder and then in the working directory ("./uri"); the file
// system callbacks confine that second look too.
TEST(UriConfinement, TheWorkingDirectoryIsNotSearched) {
    Layout l;
    const fs::path previous = fs::current_path();
    fs::current_path(l.outside);
    const fs::path scene = l.withBufferUri("secret.bin");  // absent from asset/, present in the working directory
    OpenWatch watch(l.outside);
    try {
        (void)loadGltf(scene);
        ADD_FAILURE() << "loaded secret.bin from the working directory";
    } catch (const LoadError& e) {
        EXPECT_NE(std::string(e.what()).find("secret.bin"), std::string::npos) << e.what();
    }
    EXPECT_EQ(watch.events(), 0);
    fs::current_path(previous);
}

TEST(UriConfinement, FilesInsideTheFolderStillLoad) {
    Layout l;
    fs::create_directories(l.asset / "data");
    test::writeBytes(l.asset / "data/tri angle.bin", l.file.buffer.data(), l.file.buffer.size());
    const Scene s = loadGltf(l.withBufferUri("data/../data/tri%20angle.bin"));
    ASSERT_EQ(s.meshes.size(), 1u);
    EXPECT_EQ(s.meshes[0].primitives[0].positions[2], glm::vec3(0, 1, 0));
}

}  // namespace
}  // namespace idk::scene
