// farm_job.hpp: the state of one `idk farm` job, kept in its state folder so that a rerun resumes it: the manifest
// (manifest.json: what is rendered, the chunks' half-open ranges and their files), per-chunk attempt logs
// (attempts/NNN, one line per start, appended by the task) and the checks that decide whether a chunk's output is
// valid (a video chunk: ffprobe counts exactly its frames; a still part: an EXR of the job's size whose alpha is
// the part's sample count at every pixel). Used by cmd_farm.cpp.
#pragma once
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace idk::app {

struct FarmChunk {
    uint64_t first = 0, end = 0;  // frames (video) or sample indices (still) first .. end-1
    std::string file;             // relative to the state folder
};

struct FarmJob {
    std::string kind;                 // "video" (a replay) or "still" (a path-traced image)
    std::filesystem::path dir;        // the state folder (absolute)
    std::filesystem::path idk;        // the idk binary the tasks run (absolute)
    std::filesystem::path output;     // the final video or image (absolute)
    std::filesystem::path replay;     // video: the capture
    std::string size = "256x256";     // --size of every task
    std::vector<std::string> render;  // the other `idk render` arguments, passed to every task
    uint64_t total = 0;               // frames or samples
    uint32_t maxAttempts = 3;
    std::vector<FarmChunk> chunks;
};

std::filesystem::path manifestPath(const std::filesystem::path& dir);
void saveJob(const FarmJob& job);                             // manifest.json via a temporary file + rename
FarmJob loadJob(const std::filesystem::path& dir);            // throws naming manifest.json and the cause
bool sameWork(const FarmJob& a, const FarmJob& b);            // same kind, inputs, options and chunk ranges

// `count` near-equal half-open ranges covering 0..total.
std::vector<FarmChunk> splitRanges(uint64_t total, uint64_t count, const std::string& prefix, const std::string& ext);

// The `idk render` command line (argv without the program) that produces chunk `index`.
std::vector<std::string> chunkCommand(const FarmJob& job, size_t index);

uint32_t attempts(const FarmJob& job, size_t index);
void recordAttempt(const FarmJob& job, size_t index);  // appends one line to attempts/NNN

// Frames ffprobe decodes from a video (-count_frames), or -1 when it cannot read the file.
int64_t countVideoFrames(const std::filesystem::path& file);
bool chunkValid(const FarmJob& job, size_t index);
bool outputValid(const FarmJob& job);

enum class ChunkState { Done, Pending, Failed };  // Failed: invalid after maxAttempts attempts
ChunkState chunkState(const FarmJob& job, size_t index);
const char* chunkStateName(ChunkState state);

// Runs argv[0] (looked up in PATH) with the rest as arguments; returns its exit status (-1 when it cannot start
// or was killed) and, when `out` is given, its stdout.
int runProgram(const std::vector<std::string>& argv, std::string* out = nullptr);

}  // namespace idk::app
