// farm_job_test.cpp: the `idk farm` job state (app/farm_job.hpp) without a GPU or Slurm: chunk ranges tile the
// work exactly, the manifest round-trips, a malformed one is an error naming the file, task command lines, attempt
// counting and chunk states.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "app/farm_job.hpp"
#include "core/image_file.hpp"

namespace fs = std::filesystem;
using namespace idk::app;

namespace {

fs::path freshDir(const std::string& name) {
    const fs::path dir = fs::temp_directory_path() / ("idk_farm_test_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

FarmJob stillJob(const fs::path& dir) {
    FarmJob job;
    job.kind = "still";
    job.dir = dir;
    job.idk = "/usr/bin/idk";
    job.output = dir / "out.exr";
    job.size = "4x2";
    job.render = {"scene.glb", "--seed", "3"};
    job.total = 10;
    job.maxAttempts = 2;
    job.chunks = splitRanges(10, 3, "part", ".exr");
    return job;
}

}  // namespace

TEST(FarmJob, RangesTileTheWorkInNearEqualChunks) {
    for (uint64_t total : {1u, 7u, 30u, 300u, 1001u})
        for (uint64_t count = 1; count <= std::min<uint64_t>(total, 9); ++count) {
            const std::vector<FarmChunk> chunks = splitRanges(total, count, "chunk", ".mp4");
            ASSERT_EQ(chunks.size(), count);
            EXPECT_EQ(chunks.front().first, 0u);
            EXPECT_EQ(chunks.back().end, total);
            for (size_t i = 0; i < chunks.size(); ++i) {
                EXPECT_GE(chunks[i].end - chunks[i].first, total / count);
                EXPECT_LE(chunks[i].end - chunks[i].first, total / count + 1);
                if (i > 0) {
                    EXPECT_EQ(chunks[i].first, chunks[i - 1].end);
                }
            }
        }
    EXPECT_EQ(splitRanges(30, 3, "chunk", ".mp4")[2].file, "chunk_002.mp4");
}

TEST(FarmJob, ManifestRoundTripsAndBadOnesNameTheFile) {
    const fs::path dir = freshDir("manifest");
    const FarmJob job = stillJob(dir);
    saveJob(job);
    const FarmJob back = loadJob(dir);
    EXPECT_TRUE(sameWork(job, back));
    EXPECT_EQ(back.maxAttempts, 2u);
    FarmJob other = job;
    other.render.push_back("--max-depth");
    EXPECT_FALSE(sameWork(job, other));
    std::ofstream(manifestPath(dir)) << "{\"kind\": \"still\"";
    try {
        loadJob(dir);
        FAIL() << "a truncated manifest loaded";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("manifest.json"), std::string::npos) << e.what();
    }
    fs::remove_all(dir);
}

TEST(FarmJob, TaskCommandLinesAndStates) {
    const fs::path dir = freshDir("states");
    FarmJob job = stillJob(dir);
    const std::vector<std::string> cmd = chunkCommand(job, 1);
    const std::vector<std::string> expected = {"render", "scene.glb", "--seed", "3", "--size", "4x2", "--pathtrace",
                                               "--sample-range", "3:6", "--out", (dir / "part_001.exr").string()};
    EXPECT_EQ(cmd, expected);
    EXPECT_EQ(chunkState(job, 1), ChunkState::Pending);
    recordAttempt(job, 1);
    recordAttempt(job, 1);
    EXPECT_EQ(attempts(job, 1), 2u);
    EXPECT_EQ(chunkState(job, 1), ChunkState::Failed);  // maxAttempts 2, still no valid output
    // A valid part: the job's size, alpha = its 3 samples everywhere; a wrong count is invalid.
    idk::core::ImageRgba32f part{4, 2, std::vector<float>(4 * 2 * 4, 3.0f)};
    idk::core::writeImage(dir / "part_001.exr", part);
    EXPECT_EQ(chunkState(job, 1), ChunkState::Done);
    idk::core::writeImage(dir / "part_002.exr", part);  // chunk 2 has 4 samples (6:10)
    EXPECT_FALSE(chunkValid(job, 2));
    fs::remove_all(dir);
}
