// camera_capture_test.cpp: the capture file (tools/camera_capture.hpp): exact round trip, the byte layout the
// header comment documents, an error naming the file and the right byte offset for every truncated prefix, wrong
// magic, version 0 / newer versions, bad record size, rate and counts, trailing bytes, non-finite records; the
// fixed-rate recorder at different display rates; deterministic sampling.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <unistd.h>

#include "tools/camera_capture.hpp"

namespace idk::tools {
namespace {

Capture sampleRecording(size_t frames) {
    Capture c;
    c.rateHz = 30.0f;
    for (size_t i = 0; i < frames; ++i) {
        CaptureFrame f;
        f.time = double(i) / 30.0;
        f.position = {0.5f * float(i), -1.25f, 3.0f + 0.1f * float(i)};
        f.yaw = 0.01f * float(i);
        f.pitch = -0.2f;
        f.yfov = 0.8f;
        f.sceneTime = 10.0 + f.time;
        f.paused = i % 3 == 1;
        c.frames.push_back(f);
    }
    return c;
}

std::string errorOf(const std::vector<uint8_t>& bytes) {
    try {
        parseCapture(bytes, "rec.idkcap");
    } catch (const CaptureError& e) {
        return e.what();
    }
    return "";
}

bool sameFrame(const CaptureFrame& a, const CaptureFrame& b) {
    return a.time == b.time && a.position == b.position && a.yaw == b.yaw && a.pitch == b.pitch && a.yfov == b.yfov &&
           a.sceneTime == b.sceneTime && a.paused == b.paused;
}

TEST(CaptureFile, RoundTripAndLayout) {
    const Capture c = sampleRecording(5);
    const std::vector<uint8_t> bytes = serializeCapture(c);
    ASSERT_EQ(bytes.size(), 32u + 5u * 44u);
    EXPECT_EQ(std::memcmp(bytes.data(), "IDKCAPT\0", 8), 0);
    EXPECT_EQ(bytes[8], 1u);    // version, little endian
    EXPECT_EQ(bytes[12], 44u);  // record size
    float rate;
    std::memcpy(&rate, &bytes[16], 4);
    EXPECT_EQ(rate, 30.0f);
    EXPECT_EQ(bytes[24], 5u);  // frame count
    float x1;
    std::memcpy(&x1, &bytes[32 + 44 + 8], 4);  // record 1, position.x
    EXPECT_EQ(x1, 0.5f);
    EXPECT_EQ(bytes[32 + 44 + 40], 1u);  // record 1 is paused

    const Capture back = parseCapture(bytes, "x");
    EXPECT_EQ(back.rateHz, 30.0f);
    ASSERT_EQ(back.frames.size(), 5u);
    for (size_t i = 0; i < 5; ++i) EXPECT_TRUE(sameFrame(back.frames[i], c.frames[i])) << i;
    EXPECT_TRUE(parseCapture(serializeCapture(Capture{}), "x").frames.empty());
}

TEST(CaptureFile, EveryTruncatedPrefixNamesTheFileAndOffset) {
    const std::vector<uint8_t> bytes = serializeCapture(sampleRecording(3));
    for (size_t length = 0; length < bytes.size(); ++length) {
        const std::string error = errorOf(std::vector<uint8_t>(bytes.begin(), bytes.begin() + length));
        ASSERT_NE(error, "") << "prefix of " << length << " bytes was accepted";
        const size_t offset = length < 32 ? length : 32 + (length - 32) / 44 * 44;
        EXPECT_NE(error.find("rec.idkcap: byte offset " + std::to_string(offset) + ":"), std::string::npos)
            << length << ": " << error;
        EXPECT_NE(error.find("truncated"), std::string::npos) << error;
    }
}

TEST(CaptureFile, RejectsCorruptHeadersAndRecords) {
    const std::vector<uint8_t> good = serializeCapture(sampleRecording(2));
    auto with = [&](size_t at, std::vector<uint8_t> patch) {
        std::vector<uint8_t> b = good;
        std::copy(patch.begin(), patch.end(), b.begin() + long(at));
        return errorOf(b);
    };
    std::string e = with(0, {'P', 'N', 'G'});
    EXPECT_NE(e.find("byte offset 0: wrong magic"), std::string::npos) << e;
    e = errorOf({'h', 'i'});
    EXPECT_NE(e.find("byte offset 0: wrong magic"), std::string::npos) << e;
    e = with(8, {2, 0, 0, 0});
    EXPECT_NE(e.find("byte offset 8: format version 2 is newer"), std::string::npos) << e;
    e = with(8, {0, 0, 0, 0});
    EXPECT_NE(e.find("byte offset 8: format version 0 is invalid"), std::string::npos) << e;
    e = with(12, {40, 0, 0, 0});
    EXPECT_NE(e.find("byte offset 12: record size 40"), std::string::npos) << e;
    e = with(16, {0, 0, 0, 0});  // rate 0
    EXPECT_NE(e.find("byte offset 16: rate"), std::string::npos) << e;
    e = with(24, {0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0x7F});
    EXPECT_NE(e.find("byte offset 24: absurd frame count"), std::string::npos) << e;
    e = with(24, {3, 0, 0, 0, 0, 0, 0, 0});  // promises 3, holds 2
    EXPECT_NE(e.find("byte offset 120: truncated record 2 of 3"), std::string::npos) << e;
    e = with(24, {1, 0, 0, 0, 0, 0, 0, 0});  // promises 1, holds 2
    EXPECT_NE(e.find("byte offset 76: 44 unexpected byte(s)"), std::string::npos) << e;
    e = with(32 + 44 + 8, {0, 0, 0xC0, 0x7F});  // NaN position.x in record 1
    EXPECT_NE(e.find("byte offset 76: record 1 has a non-finite"), std::string::npos) << e;
    e = with(32 + 28, {0, 0, 0, 0});  // yfov 0 in record 0
    EXPECT_NE(e.find("byte offset 60: record 0: vertical field of view"), std::string::npos) << e;
}

TEST(CaptureFile, FilesOnDisk) {
    const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("idk_capture_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const Capture c = sampleRecording(4);
    writeCapture(dir / "a.idkcap", c);
    const Capture back = readCapture(dir / "a.idkcap");
    ASSERT_EQ(back.frames.size(), 4u);
    EXPECT_TRUE(sameFrame(back.frames[3], c.frames[3]));
    // Only the file itself: no temporary left next to it.
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), std::filesystem::directory_iterator()), 1);
    try {
        readCapture(dir / "missing.idkcap");
        ADD_FAILURE() << "missing file accepted";
    } catch (const CaptureError& e) {
        EXPECT_NE(std::string(e.what()).find("missing.idkcap"), std::string::npos);
    }
    EXPECT_THROW(writeCapture(dir / "no/such/dir/x.idkcap", c), CaptureError);
    std::filesystem::remove_all(dir);
}

TEST(CaptureRecorder, FixedRateWhateverTheDisplayRate) {
    // A camera moving at 1 m/s along x, the scene clock running: recorded at 144 fps and at an irregular ~20 fps,
    // both give the 30 Hz samples x = k / 30 (linear motion: interpolation is exact up to rounding).
    for (const std::vector<double>& dts : {std::vector<double>(144, 1.0 / 144.0),
                                           std::vector<double>{0.05, 0.07, 0.03, 0.1, 0.05, 0.2, 0.15, 0.1, 0.25}}) {
        CaptureRecorder rec(30.0f);
        CaptureFrame now;
        now.sceneTime = 5.0;
        rec.start(now);
        double t = 0.0;
        for (double dt : dts) {
            t += dt;
            now.position.x = float(t);
            now.sceneTime = 5.0 + t;
            rec.update(dt, now);
        }
        const Capture& c = rec.capture();
        ASSERT_EQ(c.frames.size(), size_t(std::floor(t * 30.0 + 1e-6)) + 1);
        for (size_t k = 0; k < c.frames.size(); ++k) {
            EXPECT_NEAR(c.frames[k].time, double(k) / 30.0, 1e-12);
            EXPECT_NEAR(c.frames[k].position.x, float(k) / 30.0f, 1e-5f) << k;
            EXPECT_NEAR(c.frames[k].sceneTime, 5.0 + double(k) / 30.0, 1e-6) << k;
        }
    }
}

TEST(CaptureReplay, SamplingIsDeterministicAndHitsTheRecords) {
    const Capture c = sampleRecording(10);
    EXPECT_DOUBLE_EQ(captureDuration(c), 9.0 / 30.0);
    for (size_t i = 0; i < c.frames.size(); ++i) {
        const CaptureFrame f = sampleCapture(c, double(i) / 30.0);
        EXPECT_NEAR(f.position.x, c.frames[i].position.x, 1e-5f);
        EXPECT_NEAR(f.sceneTime, c.frames[i].sceneTime, 1e-9);
    }
    const CaptureFrame mid = sampleCapture(c, 0.5 / 30.0);
    EXPECT_NEAR(mid.position.x, 0.25f, 1e-6f);
    const CaptureFrame again = sampleCapture(c, 0.5 / 30.0);
    EXPECT_EQ(std::memcmp(&mid.position, &again.position, sizeof mid.position), 0);
    EXPECT_TRUE(sameFrame(sampleCapture(c, 100.0), c.frames.back()));
    EXPECT_TRUE(sameFrame(sampleCapture(c, -1.0), c.frames.front()));
    const scene::CameraView view = captureCameraView(c.frames[2], scene::CameraView{});
    EXPECT_EQ(view.position, c.frames[2].position);
    EXPECT_EQ(view.yfov, 0.8f);
    EXPECT_THROW(sampleCapture(Capture{}, 0.0), CaptureError);
}

}  // namespace
}  // namespace idk::tools
