// camera_capture.hpp: camera and time recordings for deterministic replay (Ctrl+R / Ctrl+Space in the viewer,
// `idk render --replay`). Ports IDKEngine's StateRecorder/FrameState (internals 2.18) with its weakness fixed: the
// original dumps raw 512-byte structs with no header or version; this is a versioned little-endian file:
//
//   header (32 bytes)  offset 0  char[8] magic "IDKCAPT\0"
//                             8  u32     version (kCaptureVersion)
//                            12  u32     record size in bytes (44 for version 1)
//                            16  f32     rate in Hz (records are 1/rate seconds apart)
//                            20  u32     reserved, 0
//                            24  u64     frame count
//   record i (44 bytes) at 32 + 44 i:
//                             0  f64     time since the recording started (s)
//                             8  f32x3   camera position
//                            20  f32     yaw (radians, FlyCameraState convention)
//                            24  f32     pitch (radians)
//                            28  f32     vertical field of view (radians)
//                            32  f64     scene (animation) time (s)
//                            40  u32     flags: bit 0 = time paused
//
// readCapture rejects anything else with a CaptureError that names the file and the byte offset.
#pragma once

#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scene/camera.hpp"

namespace idk::tools {

inline constexpr char kCaptureMagic[8] = {'I', 'D', 'K', 'C', 'A', 'P', 'T', '\0'};
inline constexpr uint32_t kCaptureVersion = 1;
inline constexpr uint32_t kCaptureHeaderBytes = 32;
inline constexpr uint32_t kCaptureRecordBytes = 44;
inline constexpr uint64_t kCaptureMaxFrames = 100'000'000;  // ~38 days at 30 Hz; more is a corrupt count
inline constexpr float kCaptureDefaultRate = 30.0f;          // the original's FPSGoal
inline constexpr float kCaptureMaxRate = 1000.0f;            // readers reject a rate outside (0, 1000] Hz

struct CaptureFrame {
    double time = 0.0;  // seconds since the recording started
    glm::vec3 position{0.0f};
    float yaw = 0.0f, pitch = 0.0f;
    float yfov = scene::kDefaultYfov;
    double sceneTime = 0.0;
    bool paused = false;
};

struct Capture {
    float rateHz = kCaptureDefaultRate;
    std::vector<CaptureFrame> frames;
};

class CaptureError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// Throws CaptureError "<path>: byte offset N: <cause>" (cannot open, wrong magic, version 0 or newer than this
// build, wrong record size, bad rate, absurd frame count, truncated header or record, trailing bytes, non-finite
// values).
Capture readCapture(const std::filesystem::path& path);
// Parses bytes already in memory; `name` is used in the messages in place of a path.
Capture parseCapture(const std::vector<uint8_t>& bytes, const std::string& name);
std::vector<uint8_t> serializeCapture(const Capture& capture);
// Writes through a temporary file renamed into place: a failure leaves no partial file. Throws CaptureError.
void writeCapture(const std::filesystem::path& path, const Capture& capture);

// Duration covered by the records: (count - 1) / rate, 0 for fewer than two.
double captureDuration(const Capture& capture);
// The state at time t (clamped to the recording): linear between the two records around t (paused from the earlier
// one). Deterministic: depends only on the capture and t. The capture must not be empty.
CaptureFrame sampleCapture(const Capture& capture, double t);

// Records at a fixed rate while the viewer calls update() once per displayed frame with the wall time that passed
// and the state now. Record k is the state at k / rate, interpolated between the two updates around it, so a
// 30 Hz recording made at 144 fps or at 20 fps samples the same path.
class CaptureRecorder {
public:
    explicit CaptureRecorder(float rateHz = kCaptureDefaultRate);  // clamped to (0, kCaptureMaxRate]
    void start(const CaptureFrame& now);  // clears, records frame 0 = now (its time set to 0)
    void update(double wallDt, const CaptureFrame& now);
    bool recording() const { return recording_; }
    void stop() { recording_ = false; }
    const Capture& capture() const { return capture_; }

private:
    Capture capture_;
    bool recording_ = false;
    double elapsed_ = 0.0;   // wall time since start
    CaptureFrame previous_;  // the state at the last update (time = elapsed_ then)
};

// The camera of a record: placement from position/yaw/pitch, yfov from the record, the rest from `lens`.
scene::CameraView captureCameraView(const CaptureFrame& frame, const scene::CameraView& lens);

}  // namespace idk::tools
