// cmd_farm.cpp: `idk farm submit|status|task|finish`: renders a replay video or a path-traced still in chunks
// (app/farm_job.hpp) as a Slurm job array (`sbatch --array`, one `idk farm task` per chunk, then a job with
// --dependency=afterok that runs `idk farm finish`), or as local processes (--local -j N) with the same task
// command lines. finish concatenates video chunks without re-encoding (ffmpeg concat demuxer, -c copy) and checks
// the frame count, or merges still parts in sample order (`idk merge`). A rerun resumes: only chunks whose output
// is missing or invalid run again; each chunk runs at most --max-attempts times in all (a task retries in place).
// No IDKEngine counterpart.
#include <nlohmann/json.hpp>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <algorithm>
#include <map>

#include "app/commands.hpp"
#include "app/farm_job.hpp"
#include "core/cli.hpp"
#include "tools/camera_capture.hpp"

namespace idk::app {

namespace fs = std::filesystem;

const char* const kFarmHelp =
    "usage: idk farm submit DIR (--replay F.idkcap --video OUT.mp4 | --still --spp N --out OUT.exr)\n"
    "                  [--chunks K] [--local [-j N]] [--max-attempts M] [--sbatch-arg X ...] [-- RENDER OPTIONS]\n"
    "       idk farm submit DIR [--local [-j N]] [--max-attempts M]     resume the job in DIR\n"
    "       idk farm status DIR      chunks done/pending/failed, attempts, the output, and squeue's view\n"
    "       idk farm task DIR [I]    run chunk I (default $SLURM_ARRAY_TASK_ID), retrying up to --max-attempts\n"
    "       idk farm finish DIR      concatenate (video) or merge (still) the chunks into the output and check it\n"
    "  DIR            state folder: manifest.json, the chunks, attempts/, logs/ (created when missing)\n"
    "  --replay F     video: render the capture's frames in K ranges (`idk render --replay F --frames a:b`)\n"
    "  --still        still: path-trace one image in K sample ranges (`idk render --pathtrace --sample-range a:b`)\n"
    "  --chunks K     number of chunks (default 4, at most the frame or sample count)\n"
    "  --local        run the tasks here as child processes instead of submitting to Slurm; -j N at once (default 1)\n"
    "  --max-attempts M  runs of one chunk before it counts as failed (default 3)\n"
    "  --sbatch-arg X extra sbatch argument for every job (repeatable, e.g. --sbatch-arg=--partition=gpu)\n"
    "  -- ...         the rest goes to every `idk render` (scene, --size, --seed, --pathtrace options, --crf, ...);\n"
    "                 use --crf 0 for videos whose decoded frames equal one machine's render (lossless chunks)\n"
    "A rerun submits only the chunks whose outputs are missing or invalid (ffprobe frame count; EXR size and counts).\n"
    "Exit codes: 0 = done (status: the job is complete), 1 = an error or a failed chunk (named), 2 = a usage error,\n"
    "3 = status of a job that is not complete yet.\n";

namespace {

FarmJob newJob(const core::CliArgs& args, const std::vector<std::string>& render, const fs::path& dir) {
    FarmJob job;
    job.dir = fs::absolute(dir);
    job.idk = fs::read_symlink("/proc/self/exe");
    job.render = render;
    for (const std::string& r : render)
        if (r == "--size" || r.rfind("--size=", 0) == 0) {
            throw core::CliError("give --size before `--` (farm option), not to idk render");
        } else if (r == "--out" || r == "--video" || r == "--replay" || r == "--frames" || r == "--sample-range" ||
                   r == "--spp" || r == "--pathtrace") {
            throw core::CliError("'" + r + "' after `--`: idk farm sets it for every task");
        }
    job.size = args.get("--size", "256x256");
    const uint64_t chunks = uint64_t(core::parseNumber("--chunks", args.get("--chunks", "4")));
    if (chunks < 1 || chunks > 10000) throw core::CliError("--chunks: give 1..10000");
    if (args.has("--still")) {
        if (args.get("--replay")) throw core::CliError("--still and --replay: give one");
        job.kind = "still";
        const double spp = core::parseNumber("--spp", args.get("--spp", "16"));
        if (!(spp >= 1 && spp <= 1e7 && spp == std::floor(spp))) throw core::CliError("--spp: give a whole count >= 1");
        job.total = uint64_t(spp);
        const std::optional<std::string> out = args.get("--out");
        if (!out || fs::path(*out).extension() != ".exr") throw core::CliError("--still needs --out FILE.exr");
        job.output = fs::absolute(*out);
        job.chunks = splitRanges(job.total, std::min(chunks, job.total), "part", ".exr");
    } else {
        const std::optional<std::string> replay = args.get("--replay"), video = args.get("--video");
        if (!replay || !video) throw core::CliError("give --replay F --video OUT.mp4, or --still");
        if (fs::path(*video).extension() != ".mp4") throw core::CliError("--video '" + *video + "': must end in .mp4");
        job.kind = "video";
        job.replay = fs::absolute(*replay);
        job.total = tools::readCapture(job.replay).frames.size();  // a bad capture fails here, naming the file
        if (job.total == 0) throw std::runtime_error(replay->c_str() + std::string(": the capture has no frames"));
        job.output = fs::absolute(*video);
        job.chunks = splitRanges(job.total, std::min(chunks, job.total), "chunk", ".mp4");
    }
    return job;
}

// Runs `idk farm task DIR I` for each index, at most `parallel` at once; returns how many failed.
int runLocal(const FarmJob& job, const std::vector<size_t>& indices, int parallel) {
    std::map<pid_t, size_t> running;
    int failed = 0;
    size_t next = 0;
    while (next < indices.size() || !running.empty()) {
        while (next < indices.size() && int(running.size()) < parallel) {
            const pid_t pid = fork();
            if (pid < 0) throw std::runtime_error("cannot start a local task (fork failed)");
            if (pid == 0) {
                const std::string dir = job.dir.string(), index = std::to_string(indices[next]), exe = job.idk.string();
                execl(exe.c_str(), exe.c_str(), "farm", "task", dir.c_str(), index.c_str(), static_cast<char*>(nullptr));
                _exit(127);
            }
            running[pid] = indices[next++];
        }
        int status = 0;
        const pid_t done = wait(&status);
        if (done < 0) break;
        if (!(WIFEXITED(status) && WEXITSTATUS(status) == 0)) ++failed;
        running.erase(done);
    }
    return failed;
}

std::string quote(const std::string& s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

// sbatch --parsable ...; returns the job id.
std::string sbatch(const FarmJob& job, const std::vector<std::string>& options, const std::string& command) {
    std::vector<std::string> argv = {"sbatch", "--parsable"};
    argv.insert(argv.end(), options.begin(), options.end());
    argv.insert(argv.end(), {"--wrap", command});
    std::string out;
    const int rc = runProgram(argv, &out);
    const std::string id = out.substr(0, out.find_first_of(";\n"));
    if (rc != 0 || id.empty() || id.find_first_not_of("0123456789") != std::string::npos)
        throw std::runtime_error("sbatch failed (exit " + std::to_string(rc) + ") submitting " + job.dir.string() +
                                 (rc == -1 || rc == 127 ? ": is Slurm installed (sbatch in PATH)? --local runs without it" : ""));
    std::ofstream(job.dir / "jobs.txt", std::ios::app) << id << "\n";
    return id;
}

int submit(const core::CliArgs& args, const std::vector<std::string>& render) {
    const fs::path dir = args.positional.at(1);
    const bool describes = args.get("--replay") || args.has("--still");
    FarmJob job;
    if (fs::exists(manifestPath(dir))) {
        job = loadJob(dir);
        if (describes && !sameWork(job, newJob(args, render, dir)))
            throw std::runtime_error(manifestPath(dir).string() + " describes another job: rerun with the same options, "
                                     "or without any to resume it, or use another folder");
    } else {
        if (!describes) throw core::CliError("no job in " + dir.string() + " yet: give --replay/--video or --still");
        fs::create_directories(dir);
        job = newJob(args, render, dir);
    }
    if (std::optional<std::string> m = args.get("--max-attempts")) {
        const double v = core::parseNumber("--max-attempts", *m);
        if (!(v >= 1 && v <= 100 && v == std::floor(v))) throw core::CliError("--max-attempts: give 1..100");
        job.maxAttempts = uint32_t(v);
    }
    saveJob(job);
    fs::create_directories(job.dir / "logs");

    std::vector<size_t> pending, failed;
    for (size_t i = 0; i < job.chunks.size(); ++i) {
        const ChunkState s = chunkState(job, i);
        if (s == ChunkState::Pending) pending.push_back(i);
        if (s == ChunkState::Failed) failed.push_back(i);
    }
    std::string list;
    for (size_t i : pending) list += (list.empty() ? "" : ",") + std::to_string(i);
    std::printf("chunks to run: %s\n", list.empty() ? "none" : list.c_str());
    if (!failed.empty()) {
        std::string f;
        for (size_t i : failed) f += (f.empty() ? "" : ",") + std::to_string(i);
        throw std::runtime_error("chunk(s) " + f + " of " + dir.string() + " failed " + std::to_string(job.maxAttempts) +
                                 " times (logs/, attempts/): raise --max-attempts to try again");
    }
    if (pending.empty() && outputValid(job)) {
        std::printf("%s is complete: %s\n", dir.string().c_str(), job.output.string().c_str());
        return 0;
    }
    const std::string self = quote(job.idk.string()) + " farm ";
    if (args.has("--local")) {
        const int parallel = int(core::parseNumber("-j", args.get("--jobs", "1")));
        if (parallel < 1 || parallel > 256) throw core::CliError("-j: give 1..256");
        if (runLocal(job, pending, parallel) != 0) {
            std::fprintf(stderr, "idk farm: some chunks failed; `idk farm status %s` lists them\n", dir.c_str());
            return 1;
        }
        std::vector<std::string> finishArgs = {"finish", dir.string()};
        return runFarm(finishArgs);
    }
    std::vector<std::string> common = {"--job-name=idk-farm"};
    for (const std::string& a : args.getAll("--sbatch-arg")) common.push_back(a);
    std::vector<std::string> finishOptions = common;
    finishOptions.push_back("--output=" + (job.dir / "logs" / "finish.log").string());
    if (!pending.empty()) {
        std::vector<std::string> options = common;
        options.push_back("--array=" + list);
        options.push_back("--requeue");  // Slurm's own requeue after a node failure; attempts/ still bounds the runs
        options.push_back("--output=" + (job.dir / "logs" / "task_%a.log").string());
        const std::string array = sbatch(job, options, "exec " + self + "task " + quote(job.dir.string()));
        std::printf("submitted job array %s (%zu task(s))\n", array.c_str(), pending.size());
        finishOptions.push_back("--dependency=afterok:" + array);
        finishOptions.push_back("--kill-on-invalid-dep=yes");
    }
    const std::string finish = sbatch(job, finishOptions, "exec " + self + "finish " + quote(job.dir.string()));
    std::printf("submitted finish job %s\n", finish.c_str());
    return 0;
}

int task(const core::CliArgs& args) {
    const FarmJob job = loadJob(args.positional.at(1));
    const char* slurmIndex = std::getenv("SLURM_ARRAY_TASK_ID");
    const std::string text = args.positional.size() > 2 ? args.positional[2] : slurmIndex ? slurmIndex : "";
    if (text.empty()) throw core::CliError("give the chunk index (or run inside a Slurm array task)");
    const double v = core::parseNumber("chunk index", text);
    if (!(v >= 0 && v < double(job.chunks.size()) && v == std::floor(v)))
        throw core::CliError("chunk " + text + ": the job has chunks 0.." + std::to_string(job.chunks.size() - 1));
    const size_t index = size_t(v);
    std::vector<std::string> argv = chunkCommand(job, index);
    argv.insert(argv.begin(), job.idk.string());
    while (!chunkValid(job, index)) {
        if (attempts(job, index) >= job.maxAttempts) {
            std::fprintf(stderr, "idk farm: chunk %zu failed %u time(s)\n", index, job.maxAttempts);
            return 1;
        }
        recordAttempt(job, index);
        std::string line;
        for (const std::string& a : argv) line += " " + a;
        std::fprintf(stderr, "idk farm: chunk %zu attempt %u:%s\n", index, attempts(job, index), line.c_str());
        const int rc = runProgram(argv);
        if (rc != 0) std::fprintf(stderr, "idk farm: chunk %zu: idk render exited %d\n", index, rc);
    }
    return 0;
}

int finish(const core::CliArgs& args) {
    const FarmJob job = loadJob(args.positional.at(1));
    for (size_t i = 0; i < job.chunks.size(); ++i)
        if (!chunkValid(job, i))
            throw std::runtime_error((job.dir / job.chunks[i].file).string() + ": chunk missing or invalid; rerun submit");
    if (job.kind == "still") {
        std::vector<std::string> merge;
        for (const FarmChunk& c : job.chunks) merge.push_back((job.dir / c.file).string());
        merge.insert(merge.end(), {"--out", job.output.string()});
        if (runMerge(merge) != 0 || !outputValid(job)) throw std::runtime_error(job.output.string() + ": merge failed");
    } else {
        const fs::path list = job.dir / "concat.txt", partial = job.output.string() + ".partial";
        {
            std::ofstream f(list);
            for (const FarmChunk& c : job.chunks) f << "file " << quote((job.dir / c.file).string()) << "\n";
        }
        // -c copy: the chunks' H.264 streams are joined as they are (each starts with an IDR frame).
        const int rc = runProgram({"ffmpeg", "-v", "error", "-nostdin", "-y", "-f", "concat", "-safe", "0", "-i",
                                   list.string(), "-c", "copy", "-f", "mp4", partial.string()});
        const int64_t frames = rc == 0 ? countVideoFrames(partial) : -1;
        if (frames != int64_t(job.total)) {
            fs::remove(partial);
            throw std::runtime_error(job.output.string() + ": concatenation failed (ffmpeg exit " + std::to_string(rc) +
                                     ", " + std::to_string(frames) + " frames, expected " + std::to_string(job.total) + ")");
        }
        fs::rename(partial, job.output);
    }
    std::printf("wrote %s (%s, %llu %s, %zu chunks)\n", job.output.c_str(), job.kind.c_str(),
                static_cast<unsigned long long>(job.total), job.kind == "video" ? "frames" : "samples", job.chunks.size());
    return 0;
}

int status(const core::CliArgs& args) {
    const FarmJob job = loadJob(args.positional.at(1));
    int counts[3] = {0, 0, 0};
    for (size_t i = 0; i < job.chunks.size(); ++i) {
        const ChunkState s = chunkState(job, i);
        ++counts[int(s)];
        std::printf("chunk %3zu  %llu:%llu  %-7s attempts %u/%u  %s\n", i,
                    static_cast<unsigned long long>(job.chunks[i].first), static_cast<unsigned long long>(job.chunks[i].end),
                    chunkStateName(s), attempts(job, i), job.maxAttempts, job.chunks[i].file.c_str());
    }
    std::printf("%s: %zu chunks: %d done, %d pending, %d failed; output %s %s\n", job.kind.c_str(), job.chunks.size(),
                counts[0], counts[1], counts[2], job.output.c_str(), outputValid(job) ? "valid" : "not written yet");
    std::ifstream ids(job.dir / "jobs.txt");
    std::string joined;
    for (std::string id; std::getline(ids, id);) joined += (joined.empty() ? "" : ",") + id;
    if (!joined.empty()) {
        std::string out;
        if (runProgram({"squeue", "-h", "-j", joined, "-o", "%i %T %R"}, &out) == 0)
            std::printf("slurm (squeue):\n%s", out.empty() ? "  no queued or running jobs\n" : out.c_str());
    }
    return counts[1] == 0 && counts[2] == 0 && outputValid(job) ? 0 : 3;
}

}  // namespace

int runFarm(const std::vector<std::string>& argv) {
    std::vector<std::string> own = argv, render;
    if (auto dash = std::find(own.begin(), own.end(), "--"); dash != own.end()) {
        render.assign(dash + 1, own.end());
        own.erase(dash, own.end());
    }
    for (std::string& a : own)  // -j N / -jN as make spells it
        if (a == "-j") a = "--jobs";
        else if (a.rfind("-j", 0) == 0 && a.size() > 2 && a[2] != '-') a = "--jobs=" + a.substr(2);
    core::CliArgs args = core::parseCli(own, {{"--help", "--still", "--local"},
                                              {"--replay", "--video", "--out", "--spp", "--chunks", "--jobs", "--max-attempts",
                                               "--sbatch-arg", "--size"}});
    if (args.has("--help") || args.positional.empty()) {
        std::fputs(kFarmHelp, stdout);
        return args.has("--help") ? 0 : 2;
    }
    const std::string& sub = args.positional[0];
    if (args.positional.size() < 2) throw core::CliError(sub + ": give the state folder DIR");
    if (sub == "submit") return submit(args, render);
    if (!render.empty()) throw core::CliError("`--` options belong to `idk farm submit`");
    if (sub == "task") return task(args);
    if (sub == "finish") return finish(args);
    if (sub == "status") return status(args);
    throw core::CliError("unknown farm command '" + sub + "' (submit, status, task, finish)");
}

}  // namespace idk::app
