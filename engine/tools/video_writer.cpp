// video_writer.cpp: frames -> ffmpeg through a pipe (see video_writer.hpp).
#include "tools/video_writer.hpp"

#include <atomic>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

#include "core/log.hpp"

extern char** environ;

namespace idk::tools {

namespace {

std::atomic<uint32_t> writerCounter{0};

// write() that turns a closed pipe into EPIPE instead of killing the process with SIGPIPE: the signal is blocked
// for this thread while writing and a SIGPIPE it raised is consumed before the mask is restored (the rest of the
// program, e.g. the viewer, keeps its own SIGPIPE disposition).
bool writeAll(int fd, const uint8_t* data, size_t size) {
    sigset_t pipeSet, previous, pending;
    sigemptyset(&pipeSet);
    sigaddset(&pipeSet, SIGPIPE);
    pthread_sigmask(SIG_BLOCK, &pipeSet, &previous);
    sigpending(&pending);
    const bool alreadyPending = sigismember(&pending, SIGPIPE) == 1;
    bool ok = true;
    while (size > 0) {
        const ssize_t n = ::write(fd, data, size);
        if (n < 0) {
            if (errno == EINTR) continue;
            ok = false;
            break;
        }
        data += n;
        size -= size_t(n);
    }
    if (!ok && errno == EPIPE && !alreadyPending) {
        const timespec zero{0, 0};
        sigtimedwait(&pipeSet, nullptr, &zero);
    }
    pthread_sigmask(SIG_SETMASK, &previous, nullptr);
    return ok;
}

// The last non-empty lines of ffmpeg's log, for the error message.
std::string logTail(const std::filesystem::path& log) {
    std::ifstream file(log);
    std::string line, tail;
    while (std::getline(file, line)) {
        if (!line.empty()) tail = tail.empty() ? line : tail + " / " + line;
        if (tail.size() > 400) tail = tail.substr(tail.size() - 400);
    }
    return tail;
}

}  // namespace

uint32_t evenVideoSize(uint32_t size) { return size + (size & 1u); }

VideoWriter::VideoWriter(std::filesystem::path output, uint32_t width, uint32_t height, const VideoOptions& options)
    : output_(std::move(output)), width_(width), height_(height) {
    const std::string out = output_.string();
    if (width == 0 || height == 0 || width > 16384 || height > 16384)
        throw VideoError(core::concat(out, ": video size ", width, "x", height, " is not in 1x1..16384x16384"));
    if (!std::isfinite(options.fps) || options.fps <= 0.0 || options.fps > 1000.0)
        throw VideoError(core::concat(out, ": frame rate ", options.fps, " is not in (0, 1000]"));
    std::filesystem::path directory = output_.parent_path();
    if (directory.empty()) directory = ".";
    if (!std::filesystem::is_directory(directory))
        throw VideoError(out + ": the directory " + directory.string() + " does not exist");
    if (std::filesystem::is_directory(output_)) throw VideoError(out + ": is a directory");

    const std::string tag = core::concat(::getpid(), "-", writerCounter++);
    temporary_ = directory / ("." + output_.filename().string() + ".partial-" + tag + ".mp4");
    log_ = std::filesystem::temp_directory_path() / ("idk-ffmpeg-" + tag + ".log");

    std::vector<std::string> args = {options.ffmpeg, "-hide_banner", "-loglevel", "error", "-y",
                                     "-f", "rawvideo", "-pix_fmt", "rgba",
                                     "-video_size", core::concat(width, "x", height),
                                     "-framerate", core::concat(options.fps), "-i", "pipe:0", "-an"};
    if (evenVideoSize(width) != width || evenVideoSize(height) != height) {
        // yuv420p subsamples chroma 2x2: pad odd sizes with a black column/row at the right/bottom.
        args.insert(args.end(), {"-vf", core::concat("pad=", evenVideoSize(width), ":", evenVideoSize(height), ":0:0:black")});
    }
    args.insert(args.end(), {"-c:v", "libx264", "-preset", options.preset, "-crf", core::concat(options.crf),
                             "-pix_fmt", "yuv420p", "-movflags", "+faststart", "-f", "mp4", temporary_.string()});
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);

    int fds[2];
    if (::pipe2(fds, O_CLOEXEC) != 0) throw VideoError(out + ": cannot create a pipe to ffmpeg: " + std::strerror(errno));
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, fds[0], STDIN_FILENO);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, log_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    const int spawned = posix_spawnp(&pid_, options.ffmpeg.c_str(), &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    ::close(fds[0]);
    if (spawned != 0) {
        ::close(fds[1]);
        pid_ = -1;
        std::error_code ignored;
        std::filesystem::remove(log_, ignored);
        throw VideoError(out + ": cannot run '" + options.ffmpeg + "' (" + std::strerror(spawned) +
                         "); install the Debian package ffmpeg");
    }
    pipe_ = fds[1];
}

VideoWriter::~VideoWriter() {
    if (!finished_) abort();
}

void VideoWriter::addFrame(std::span<const uint8_t> rgba) {
    if (finished_ || pid_ < 0) throw VideoError(output_.string() + ": the video writer is closed");
    const size_t expected = size_t(width_) * height_ * 4;
    if (rgba.size() != expected)
        fail(core::concat("frame ", frames_, " has ", rgba.size(), " bytes, a ", width_, "x", height_,
                          " RGBA8 frame has ", expected));
    if (!writeAll(pipe_, rgba.data(), rgba.size())) fail(core::concat("ffmpeg stopped reading at frame ", frames_));
    ++frames_;
}

void VideoWriter::finish() {
    if (finished_) return;
    if (pid_ < 0) throw VideoError(output_.string() + ": the video writer is closed");
    if (frames_ == 0) fail("no frames were given");
    ::close(pipe_);
    pipe_ = -1;
    int status = 0;
    while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
    }
    pid_ = -1;
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) fail("ffmpeg failed");
    std::error_code error;
    std::filesystem::rename(temporary_, output_, error);
    if (error) fail("cannot move the encoded video into place: " + error.message());
    std::filesystem::remove(log_, error);
    finished_ = true;
}

void VideoWriter::abort() noexcept {
    if (pipe_ >= 0) {
        ::close(pipe_);
        pipe_ = -1;
    }
    if (pid_ > 0) {
        ::kill(pid_, SIGKILL);
        int status = 0;
        while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
        }
        pid_ = -1;
    }
    std::error_code ignored;
    std::filesystem::remove(temporary_, ignored);
    std::filesystem::remove(log_, ignored);
    finished_ = true;
}

void VideoWriter::fail(const std::string& cause) {
    std::string message = output_.string() + ": " + cause;
    const std::string tail = logTail(log_);
    if (!tail.empty()) message += " (ffmpeg: " + tail + ")";
    abort();
    throw VideoError(message);
}

}  // namespace idk::tools
