// video_writer.hpp: encodes RGBA8 frames to an H.264 MP4 by piping them to the `ffmpeg` program (Debian package
// ffmpeg): rawvideo rgba on its stdin -> libx264, yuv420p, CRF 22 (the original's command, internals 2.18). yuv420p
// needs even sizes: an odd width or height is padded with one black column/row, so the video is the next even size.
// ffmpeg writes a temporary file next to the output that finish() renames into place; on any error (ffmpeg missing,
// it exits early, a frame of the wrong size, the writer destroyed without finish()) the process is stopped and the
// temporary file removed, so nothing is left at the output path. Errors are VideoError naming the output file.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <stdexcept>
#include <string>
#include <sys/types.h>

namespace idk::tools {

class VideoError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

struct VideoOptions {
    double fps = 30.0;
    int crf = 22;                     // libx264 constant rate factor (lower: better)
    std::string preset = "medium";    // libx264 preset
    std::string ffmpeg = "ffmpeg";    // program to run (looked up in PATH)
};

// Width and height the video gets for a frame size (each rounded up to even).
uint32_t evenVideoSize(uint32_t size);

class VideoWriter {
public:
    // Starts ffmpeg. Throws VideoError (ffmpeg not found, bad size or fps, output directory missing).
    VideoWriter(std::filesystem::path output, uint32_t width, uint32_t height, const VideoOptions& options = {});
    ~VideoWriter();  // without finish(): aborts (stops ffmpeg, removes the temporary file)
    VideoWriter(const VideoWriter&) = delete;
    VideoWriter& operator=(const VideoWriter&) = delete;

    // One frame: width * height * 4 bytes, RGBA8, top row first. Throws VideoError.
    void addFrame(std::span<const uint8_t> rgba);
    // Closes the pipe, waits for ffmpeg and moves the file into place. Throws VideoError (with ffmpeg's message).
    void finish();
    void abort() noexcept;

    uint64_t framesWritten() const { return frames_; }

private:
    void fail(const std::string& cause);  // aborts, then throws VideoError naming the output

    std::filesystem::path output_, temporary_, log_;
    uint32_t width_ = 0, height_ = 0;
    pid_t pid_ = -1;
    int pipe_ = -1;
    uint64_t frames_ = 0;
    bool finished_ = false;
};

}  // namespace idk::tools
