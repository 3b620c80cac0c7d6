// video_writer_test.cpp: the ffmpeg pipe (tools/video_writer.hpp), checked with ffprobe (both from the Debian
// ffmpeg package): frame count, size, codec and pixel format of small videos; odd sizes padded to even; every
// error names the output and leaves nothing in the output directory.
#include <gtest/gtest.h>

#include <cstdio>
#include <unistd.h>

#include "tools/video_writer.hpp"

namespace idk::tools {
namespace {

class VideoWriterTest : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = std::filesystem::temp_directory_path() /
               ("idk_video_" + std::to_string(::getpid()) + "_" +
                ::testing::UnitTest::GetInstance()->current_test_info()->name());
        std::filesystem::remove_all(dir_);
        std::filesystem::create_directories(dir_);
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }

    size_t filesInDir() const {
        return size_t(std::distance(std::filesystem::directory_iterator(dir_), std::filesystem::directory_iterator()));
    }
    // "codec,width,height,pix_fmt,frames" of the first video stream.
    static std::string probe(const std::filesystem::path& file) {
        const std::string cmd = "ffprobe -v error -select_streams v:0 -count_frames -show_entries "
                                "stream=codec_name,width,height,pix_fmt,nb_read_frames -of csv=p=0 '" +
                                file.string() + "'";
        FILE* pipe = ::popen(cmd.c_str(), "r");
        if (pipe == nullptr) return "";
        std::string out;
        char buf[256];
        while (std::fgets(buf, sizeof buf, pipe) != nullptr) out += buf;
        ::pclose(pipe);
        while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
        return out;
    }
    static std::vector<uint8_t> frame(uint32_t w, uint32_t h, int index) {
        std::vector<uint8_t> px(size_t(w) * h * 4);
        for (uint32_t y = 0; y < h; ++y)
            for (uint32_t x = 0; x < w; ++x) {
                uint8_t* p = &px[(size_t(y) * w + x) * 4];
                p[0] = uint8_t(x * 4 + index * 10);
                p[1] = uint8_t(y * 4);
                p[2] = uint8_t(index * 25);
                p[3] = 255;
            }
        return px;
    }

    std::filesystem::path dir_;
};

TEST_F(VideoWriterTest, EncodesEveryFrameAtTheGivenSize) {
    const std::filesystem::path out = dir_ / "clip.mp4";
    VideoWriter video(out, 64, 48, VideoOptions{.fps = 30.0});
    for (int i = 0; i < 10; ++i) video.addFrame(frame(64, 48, i));
    video.finish();
    EXPECT_EQ(video.framesWritten(), 10u);
    EXPECT_EQ(probe(out), "h264,64,48,yuv420p,10");
    EXPECT_EQ(filesInDir(), 1u);  // the video only: no temporary or log left
}

TEST_F(VideoWriterTest, OddSizesArePaddedToEven) {
    EXPECT_EQ(evenVideoSize(63), 64u);
    EXPECT_EQ(evenVideoSize(64), 64u);
    const std::filesystem::path out = dir_ / "odd.mp4";
    VideoWriter video(out, 33, 17);
    for (int i = 0; i < 3; ++i) video.addFrame(frame(33, 17, i));
    video.finish();
    EXPECT_EQ(probe(out), "h264,34,18,yuv420p,3");
}

TEST_F(VideoWriterTest, ErrorsNameTheOutputAndLeaveNothing) {
    const std::filesystem::path out = dir_ / "bad.mp4";
    {
        VideoWriter video(out, 16, 16);
        video.addFrame(frame(16, 16, 0));
        try {
            video.addFrame(frame(8, 8, 1));
            ADD_FAILURE() << "a wrong-sized frame was accepted";
        } catch (const VideoError& e) {
            EXPECT_NE(std::string(e.what()).find(out.string()), std::string::npos) << e.what();
        }
    }
    EXPECT_EQ(filesInDir(), 0u);
    {
        VideoWriter video(out, 16, 16);
        video.addFrame(frame(16, 16, 0));
    }  // destroyed without finish(): aborted
    EXPECT_EQ(filesInDir(), 0u);
    {
        VideoWriter video(out, 16, 16);
        EXPECT_THROW(video.finish(), VideoError);  // no frames
    }
    EXPECT_EQ(filesInDir(), 0u);
    try {
        VideoWriter video(out, 16, 16, VideoOptions{.ffmpeg = "/no/such/ffmpeg"});
        ADD_FAILURE() << "a missing ffmpeg was accepted";
    } catch (const VideoError& e) {
        EXPECT_NE(std::string(e.what()).find("bad.mp4"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("ffmpeg"), std::string::npos) << e.what();
    }
    EXPECT_THROW(VideoWriter(dir_ / "no/such/dir/x.mp4", 16, 16), VideoError);
    EXPECT_THROW(VideoWriter(dir_ / "zero.mp4", 0, 16), VideoError);
    // ffmpeg itself fails (an unknown preset): the message carries ffmpeg's words, nothing is left.
    try {
        VideoWriter video(out, 16, 16, VideoOptions{.preset = "no-such-preset"});
        for (int i = 0; i < 3; ++i) video.addFrame(frame(16, 16, i));
        video.finish();
        ADD_FAILURE() << "an ffmpeg failure was not reported";
    } catch (const VideoError& e) {
        EXPECT_NE(std::string(e.what()).find("bad.mp4"), std::string::npos) << e.what();
    }
    EXPECT_EQ(filesInDir(), 0u);
    EXPECT_FALSE(std::filesystem::exists(out));
}

}  // namespace
}  // namespace idk::tools
