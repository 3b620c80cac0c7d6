// farm_job.cpp: the `idk farm` job state (app/farm_job.hpp): manifest JSON, chunk ranges and task command lines,
// attempt logs, and the validity checks of chunk outputs (ffprobe for videos, the EXR's size and counts for stills).
#include "app/farm_job.hpp"

#include <nlohmann/json.hpp>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "core/image_file.hpp"

namespace idk::app {

namespace fs = std::filesystem;

fs::path manifestPath(const fs::path& dir) { return dir / "manifest.json"; }

void saveJob(const FarmJob& job) {
    nlohmann::json j;
    j["kind"] = job.kind;
    j["idk"] = job.idk.string();
    j["output"] = job.output.string();
    j["replay"] = job.replay.string();
    j["size"] = job.size;
    j["render"] = job.render;
    j["total"] = job.total;
    j["maxAttempts"] = job.maxAttempts;
    nlohmann::json chunks = nlohmann::json::array();
    for (const FarmChunk& c : job.chunks) chunks.push_back({{"first", c.first}, {"end", c.end}, {"file", c.file}});
    j["chunks"] = chunks;
    const fs::path tmp = manifestPath(job.dir).string() + ".tmp";
    {
        std::ofstream f(tmp);
        f << j.dump(2) << "\n";
        if (!f) throw std::runtime_error(tmp.string() + ": cannot write the farm manifest");
    }
    fs::rename(tmp, manifestPath(job.dir));  // readers never see a half-written manifest
}

FarmJob loadJob(const fs::path& dir) {
    const fs::path path = manifestPath(dir);
    std::ifstream f(path);
    if (!f) throw std::runtime_error(path.string() + ": no farm job here (cannot open the manifest)");
    try {
        const nlohmann::json j = nlohmann::json::parse(f);
        FarmJob job;
        job.dir = fs::absolute(dir);
        job.kind = j.at("kind").get<std::string>();
        job.idk = j.at("idk").get<std::string>();
        job.output = j.at("output").get<std::string>();
        job.replay = j.at("replay").get<std::string>();
        job.size = j.at("size").get<std::string>();
        job.render = j.at("render").get<std::vector<std::string>>();
        job.total = j.at("total").get<uint64_t>();
        job.maxAttempts = j.at("maxAttempts").get<uint32_t>();
        for (const nlohmann::json& c : j.at("chunks"))
            job.chunks.push_back({c.at("first").get<uint64_t>(), c.at("end").get<uint64_t>(), c.at("file").get<std::string>()});
        if ((job.kind != "video" && job.kind != "still") || job.chunks.empty())
            throw std::runtime_error("kind must be video or still, with at least one chunk");
        for (const FarmChunk& c : job.chunks)
            if (c.end <= c.first || c.file.find('/') != std::string::npos)
                throw std::runtime_error("chunk " + c.file + " has an empty range or a path outside the folder");
        return job;
    } catch (const std::exception& e) {
        throw std::runtime_error(path.string() + ": malformed farm manifest: " + e.what());
    }
}

bool sameWork(const FarmJob& a, const FarmJob& b) {
    if (a.kind != b.kind || a.output != b.output || a.replay != b.replay || a.size != b.size || a.render != b.render ||
        a.total != b.total || a.chunks.size() != b.chunks.size())
        return false;
    for (size_t i = 0; i < a.chunks.size(); ++i)
        if (a.chunks[i].first != b.chunks[i].first || a.chunks[i].end != b.chunks[i].end) return false;
    return true;
}

std::vector<FarmChunk> splitRanges(uint64_t total, uint64_t count, const std::string& prefix, const std::string& ext) {
    std::vector<FarmChunk> chunks;
    for (uint64_t i = 0; i < count; ++i) {
        char name[64];
        std::snprintf(name, sizeof(name), "%s_%03llu%s", prefix.c_str(), static_cast<unsigned long long>(i), ext.c_str());
        chunks.push_back({i * total / count, (i + 1) * total / count, name});
    }
    return chunks;
}

std::vector<std::string> chunkCommand(const FarmJob& job, size_t index) {
    const FarmChunk& c = job.chunks.at(index);
    std::vector<std::string> argv = {"render"};
    argv.insert(argv.end(), job.render.begin(), job.render.end());
    argv.insert(argv.end(), {"--size", job.size});
    const std::string range = std::to_string(c.first) + ":" + std::to_string(c.end);
    const std::string file = (job.dir / c.file).string();
    if (job.kind == "video") argv.insert(argv.end(), {"--replay", job.replay.string(), "--frames", range, "--video", file});
    else argv.insert(argv.end(), {"--pathtrace", "--sample-range", range, "--out", file});
    return argv;
}

static fs::path attemptLog(const FarmJob& job, size_t index) {
    char name[32];
    std::snprintf(name, sizeof(name), "%03zu", index);
    return job.dir / "attempts" / name;
}

uint32_t attempts(const FarmJob& job, size_t index) {
    std::ifstream f(attemptLog(job, index));
    uint32_t n = 0;
    for (std::string line; std::getline(f, line);) ++n;
    return n;
}

void recordAttempt(const FarmJob& job, size_t index) {
    fs::create_directories(job.dir / "attempts");
    std::ofstream f(attemptLog(job, index), std::ios::app);  // one short line: O_APPEND keeps concurrent lines whole
    const char* task = std::getenv("SLURM_JOB_ID");
    f << "start pid " << getpid() << (task ? std::string(" slurm job ") + task : std::string(" local")) << "\n";
    if (!f) throw std::runtime_error(attemptLog(job, index).string() + ": cannot record the attempt");
}

int runProgram(const std::vector<std::string>& argv, std::string* out) {
    int fds[2] = {-1, -1};
    if (out && pipe(fds) != 0) return -1;
    const pid_t pid = fork();
    if (pid < 0) return -1;
    if (pid == 0) {
        if (out) {
            dup2(fds[1], STDOUT_FILENO);
            close(fds[0]);
            close(fds[1]);
        }
        std::vector<char*> args;
        for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
        args.push_back(nullptr);
        execvp(args[0], args.data());
        _exit(127);
    }
    if (out) {
        close(fds[1]);
        char buffer[4096];
        for (ssize_t n; (n = read(fds[0], buffer, sizeof(buffer))) > 0;) out->append(buffer, size_t(n));
        close(fds[0]);
    }
    int status = 0;
    if (waitpid(pid, &status, 0) != pid) return -1;
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

int64_t countVideoFrames(const fs::path& file) {
    if (!fs::is_regular_file(file)) return -1;
    std::string out;
    if (runProgram({"ffprobe", "-v", "error", "-select_streams", "v:0", "-count_frames", "-show_entries",
                    "stream=nb_read_frames", "-of", "csv=p=0", file.string()},
                   &out) != 0)
        return -1;
    try {
        return std::stoll(out);
    } catch (const std::exception&) {
        return -1;
    }
}

// A still part: readable, the job's size, alpha = its sample count everywhere (a mean image has alpha 1).
static bool stillValid(const FarmJob& job, const fs::path& file, float count) {
    if (!fs::is_regular_file(file)) return false;
    try {
        const core::ImageRgba32f image = core::readImage(file);
        if (job.size != std::to_string(image.width) + "x" + std::to_string(image.height)) return false;
        for (size_t i = 0; i < image.pixels.size(); ++i)
            if (!std::isfinite(image.pixels[i]) || (i % 4 == 3 && image.pixels[i] != count)) return false;
        return true;
    } catch (const std::exception&) {
        return false;
    }
}

bool chunkValid(const FarmJob& job, size_t index) {
    const FarmChunk& c = job.chunks.at(index);
    if (job.kind == "video") return countVideoFrames(job.dir / c.file) == int64_t(c.end - c.first);
    return stillValid(job, job.dir / c.file, float(c.end - c.first));
}

bool outputValid(const FarmJob& job) {
    if (job.kind == "video") return countVideoFrames(job.output) == int64_t(job.total);
    return stillValid(job, job.output, 1.0f);
}

ChunkState chunkState(const FarmJob& job, size_t index) {
    if (chunkValid(job, index)) return ChunkState::Done;
    return attempts(job, index) >= job.maxAttempts ? ChunkState::Failed : ChunkState::Pending;
}

const char* chunkStateName(ChunkState state) {
    return state == ChunkState::Done ? "done" : state == ChunkState::Pending ? "pending" : "failed";
}

}  // namespace idk::app
