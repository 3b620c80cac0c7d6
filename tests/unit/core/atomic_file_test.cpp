// atomic_file_test.cpp: outputs appear whole or not at all (core/atomic_file.hpp). A writer that throws midway, a
// process killed midway, and a real OpenImageIO PNG/EXR write that fails (the file-size limit RLIMIT_FSIZE cuts it
// off: EFBIG with SIGXFSZ ignored, or the process killed by SIGXFSZ) leave no file under the requested name, an
// older file there untouched, and (except after a kill) no temporary either.
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fstream>
#include <random>
#include <set>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "core/atomic_file.hpp"
#include "core/image_file.hpp"

namespace idk::core {
namespace {

namespace fs = std::filesystem;

class AtomicFile : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir = fs::temp_directory_path() / ("idk_atomic_" + std::to_string(::getpid()) + "_" + info->name());
        fs::remove_all(dir);
        fs::create_directories(dir);
    }
    void TearDown() override { fs::remove_all(dir); }

    std::set<std::string> files() const {
        std::set<std::string> names;
        for (const auto& e : fs::directory_iterator(dir)) names.insert(e.path().filename().string());
        return names;
    }
    static std::string read(const fs::path& path) {
        std::ifstream in(path, std::ios::binary);
        return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    }
    // Runs `body` in a child process; returns its wait status.
    template <class F>
    static int inChild(F body) {
        const pid_t pid = ::fork();
        if (pid == 0) {
            body();
            ::_exit(0);
        }
        int status = 0;
        ::waitpid(pid, &status, 0);
        return status;
    }

    fs::path dir;
};

ImageRgba32f noise(uint32_t size) {  // incompressible, so the encoded file is large
    ImageRgba32f img{size, size, std::vector<float>(size_t(size) * size * 4)};
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (float& v : img.pixels) v = u(rng);
    return img;
}

TEST_F(AtomicFile, WritesAndReplacesWithNothingLeftOver) {
    writeFileAtomically(dir / "a.txt", "first");
    EXPECT_EQ(read(dir / "a.txt"), "first");
    writeFileAtomically(dir / "a.txt", "second, longer");
    EXPECT_EQ(read(dir / "a.txt"), "second, longer");
    EXPECT_EQ(files(), std::set<std::string>{"a.txt"});
    EXPECT_THROW(writeFileAtomically(dir / "no/such/b.dot", "digraph {}"), std::runtime_error);
    writeImage(dir / "sub/c.png", noise(2));  // writeImage creates the folder, as it always did
    EXPECT_TRUE(fs::is_regular_file(dir / "sub/c.png"));
}

TEST_F(AtomicFile, TheTemporaryKeepsTheExtensionAndLivesNextToTheTarget) {
    fs::path seen;
    writeAtomically(dir / "frame.png", [&](const fs::path& temporary) {
        seen = temporary;
        std::ofstream(temporary) << "x";
    });
    EXPECT_EQ(seen.parent_path(), dir);
    EXPECT_EQ(seen.extension(), ".png");
    EXPECT_EQ(seen.filename().string().rfind(".frame.partial-", 0), 0u) << seen;
    EXPECT_FALSE(fs::exists(seen));
}

TEST_F(AtomicFile, AWriterThatThrowsMidwayLeavesNothing) {
    auto failing = [](const fs::path& temporary) {
        std::ofstream(temporary) << "half of the da";
        throw std::runtime_error("injected failure");
    };
    EXPECT_THROW(writeAtomically(dir / "new.exr", failing), std::runtime_error);
    EXPECT_TRUE(files().empty()) << "left: " << *files().begin();

    writeFileAtomically(dir / "old.exr", "the older, complete file");
    EXPECT_THROW(writeAtomically(dir / "old.exr", failing), std::runtime_error);
    EXPECT_EQ(read(dir / "old.exr"), "the older, complete file");
    EXPECT_EQ(files(), std::set<std::string>{"old.exr"});
}

TEST_F(AtomicFile, AProcessKilledMidWriteLeavesNoTruncatedFile) {
    writeFileAtomically(dir / "old.idkcap", "older capture");
    const int status = inChild([&] {
        writeAtomically(dir / "old.idkcap", [](const fs::path& temporary) {
            std::ofstream(temporary) << "half a capt" << std::flush;
            ::raise(SIGKILL);
        });
        writeAtomically(dir / "new.idkcap", [](const fs::path&) { ::raise(SIGKILL); });
    });
    ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL) << status;
    EXPECT_EQ(read(dir / "old.idkcap"), "older capture");
    EXPECT_FALSE(fs::exists(dir / "new.idkcap"));
    // A killed process cannot clean up: its temporary stays, under a name that is not the output's.
    for (const std::string& name : files()) {
        if (name == "old.idkcap") continue;
        EXPECT_EQ(name.rfind(".old.partial-", 0), 0u) << name;
    }
}

// A real PNG/EXR write cut off by the file-size limit: with SIGXFSZ ignored the write fails with EFBIG and
// writeImage throws; without, the process dies mid-write. Both leave the older file (or nothing) in place.
TEST_F(AtomicFile, AFailedImageWriteLeavesNoFile) {
    const ImageRgba32f image = noise(128);  // PNG ~ 190 KiB, EXR ~ 250 KiB; the limit is 16 KiB
    writeImage(dir / "old.png", noise(4));
    const std::string older = read(dir / "old.png");
    for (const char* name : {"old.png", "new.exr", "new.png"}) {
        const int status = inChild([&] {
            ::signal(SIGXFSZ, SIG_IGN);
            const rlimit limit{16384, 16384};
            ::setrlimit(RLIMIT_FSIZE, &limit);
            try {
                writeImage(dir / name, image);
            } catch (const std::runtime_error& e) {
                ::_exit(std::string(e.what()).find(name) != std::string::npos ? 3 : 4);
            }
        });
        ASSERT_TRUE(WIFEXITED(status)) << name << " " << status;
        EXPECT_EQ(WEXITSTATUS(status), 3) << name << ": writeImage did not throw an error naming the file";
        EXPECT_EQ(files(), std::set<std::string>{"old.png"}) << name;
        EXPECT_EQ(read(dir / "old.png"), older);
    }
    const int killed = inChild([&] {
        const rlimit limit{16384, 16384};
        ::setrlimit(RLIMIT_FSIZE, &limit);
        writeImage(dir / "old.png", image);
    });
    ASSERT_TRUE(WIFSIGNALED(killed) && WTERMSIG(killed) == SIGXFSZ) << killed;
    EXPECT_EQ(read(dir / "old.png"), older);
}

}  // namespace
}  // namespace idk::core
