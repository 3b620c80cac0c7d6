// fuzz_replay_test.cpp: every committed seed (tests/fuzz/seeds/NAME/) and every crash input kept after its fix
// (tests/fuzz/regressions/NAME/) through the harness NAME, built without libFuzzer. A harness throws
// ContractViolation when the code under test breaks its contract (an undocumented exception, a broken invariant,
// a capture that does not round-trip); ASan/UBSan report memory errors in the sanitizer pass.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "fuzz_target.hpp"

namespace {

namespace fs = std::filesystem;
const fs::path kFuzzDir = fs::path(IDK_SOURCE_DIR) / "tests" / "fuzz";

// The harness a corpus folder belongs to: glb corpora run the glTF harness (build-fuzz builds it as fuzz_glb).
idk::fuzz::Entry harnessFor(const std::string& folder) {
    const std::string name = folder == "glb" ? "gltf" : folder;
    for (const auto& h : idk::fuzz::harnesses())
        if (h.name == name) return h.entry;
    return nullptr;
}

std::vector<fs::path> inputs(const fs::path& folder) {
    std::vector<fs::path> files;
    if (fs::is_directory(folder))
        for (const auto& entry : fs::directory_iterator(folder))
            if (entry.is_regular_file()) files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    return files;
}

void replay(idk::fuzz::Entry entry, const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    ASSERT_TRUE(in) << file;
    const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    try {
        entry(bytes.data(), bytes.size());
    } catch (const idk::fuzz::ContractViolation& e) {
        ADD_FAILURE() << file << ": " << e.what();
    }
}

class FuzzReplay : public ::testing::TestWithParam<std::string> {};

TEST_P(FuzzReplay, SeedsAndKeptCrashInputsKeepTheContract) {
    const std::string folder = GetParam();
    const idk::fuzz::Entry entry = harnessFor(folder);
    if (!entry) GTEST_SKIP() << "harness " << folder << " is not built here (the viewer needs GLFW)";
    const auto seeds = inputs(kFuzzDir / "seeds" / folder);
    const auto crashes = inputs(kFuzzDir / "regressions" / folder);
    for (const auto& file : seeds) replay(entry, file);
    for (const auto& file : crashes) replay(entry, file);
    RecordProperty("inputs", int(seeds.size() + crashes.size()));
}

INSTANTIATE_TEST_SUITE_P(Harnesses, FuzzReplay, ::testing::Values("gltf", "glb", "image", "capture", "script"),
                         [](const auto& info) { return info.param; });

// Every kept input sits in a folder named after a harness that exists (a typo would silently replay nothing).
TEST(FuzzReplay, RegressionFoldersNameHarnesses) {
    for (const char* kind : {"seeds", "regressions"})
        for (const auto& entry : fs::directory_iterator(kFuzzDir / kind))
            if (entry.is_directory()) {
                const std::string name = entry.path().filename().string();
                EXPECT_TRUE(name == "script" || harnessFor(name)) << kind << "/" << name;
            }
}

}  // namespace
