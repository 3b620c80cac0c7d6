// camera_capture.cpp: the capture file format, its reader with offset-naming errors, sampling and the
// fixed-rate recorder (see camera_capture.hpp; ports IDKEngine StateRecorder/FrameState).
#include "tools/camera_capture.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <system_error>
#include <unistd.h>

#include "core/atomic_file.hpp"
#include "core/log.hpp"
#include "tools/camera_controller.hpp"

namespace idk::tools {

namespace {

// Little-endian field access, independent of the host's byte order and struct layout.
class Writer {
public:
    explicit Writer(std::vector<uint8_t>& out) : out_(out) {}
    void u32(uint32_t v) { bytes(v, 4); }
    void u64(uint64_t v) { bytes(v, 8); }
    void f32(float v) {
        uint32_t bits;
        std::memcpy(&bits, &v, 4);
        u32(bits);
    }
    void f64(double v) {
        uint64_t bits;
        std::memcpy(&bits, &v, 8);
        u64(bits);
    }

private:
    void bytes(uint64_t v, int count) {
        for (int i = 0; i < count; ++i) out_.push_back(uint8_t(v >> (8 * i)));
    }
    std::vector<uint8_t>& out_;
};

class Reader {
public:
    explicit Reader(const uint8_t* data) : data_(data) {}
    uint32_t u32() { return uint32_t(bytes(4)); }
    uint64_t u64() { return bytes(8); }
    float f32() {
        const uint32_t bits = u32();
        float v;
        std::memcpy(&v, &bits, 4);
        return v;
    }
    double f64() {
        const uint64_t bits = u64();
        double v;
        std::memcpy(&v, &bits, 8);
        return v;
    }

private:
    uint64_t bytes(int count) {
        uint64_t v = 0;
        for (int i = 0; i < count; ++i) v |= uint64_t(data_[i]) << (8 * i);
        data_ += count;
        return v;
    }
    const uint8_t* data_;
};

[[noreturn]] void fail(const std::string& name, uint64_t offset, const std::string& cause) {
    throw CaptureError(core::concat(name, ": byte offset ", offset, ": ", cause));
}

}  // namespace

std::vector<uint8_t> serializeCapture(const Capture& capture) {
    std::vector<uint8_t> out;
    out.reserve(kCaptureHeaderBytes + capture.frames.size() * kCaptureRecordBytes);
    out.insert(out.end(), kCaptureMagic, kCaptureMagic + 8);
    Writer w(out);
    w.u32(kCaptureVersion);
    w.u32(kCaptureRecordBytes);
    w.f32(capture.rateHz);
    w.u32(0);
    w.u64(capture.frames.size());
    for (const CaptureFrame& f : capture.frames) {
        w.f64(f.time);
        w.f32(f.position.x);
        w.f32(f.position.y);
        w.f32(f.position.z);
        w.f32(f.yaw);
        w.f32(f.pitch);
        w.f32(f.yfov);
        w.f64(f.sceneTime);
        w.u32(f.paused ? 1u : 0u);
    }
    return out;
}

Capture parseCapture(const std::vector<uint8_t>& bytes, const std::string& name) {
    const uint64_t size = bytes.size();
    const bool magicPrefix = std::equal(bytes.begin(), bytes.begin() + long(std::min<uint64_t>(size, 8)), kCaptureMagic);
    if (!magicPrefix) fail(name, 0, "wrong magic: not an idk camera capture (expected \"IDKCAPT\\0\")");
    if (size < kCaptureHeaderBytes)
        fail(name, size, core::concat("truncated header: a capture header has ", kCaptureHeaderBytes,
                                      " bytes, the file ends after ", size));
    Reader r(bytes.data() + 8);
    const uint32_t version = r.u32();
    const uint32_t recordBytes = r.u32();
    const float rate = r.f32();
    r.u32();  // reserved
    const uint64_t count = r.u64();
    if (version == 0 || version > kCaptureVersion)
        fail(name, 8, core::concat("format version ", version, version == 0 ? " is invalid" : " is newer than this build",
                                   " (it reads version ", kCaptureVersion, ")"));
    if (recordBytes != kCaptureRecordBytes)
        fail(name, 12, core::concat("record size ", recordBytes, " bytes, version ", version, " records have ",
                                    kCaptureRecordBytes));
    if (!std::isfinite(rate) || rate <= 0.0f || rate > kCaptureMaxRate)
        fail(name, 16, core::concat("rate ", rate, " Hz is not in (0, ", kCaptureMaxRate, "]"));
    if (count > kCaptureMaxFrames) fail(name, 24, core::concat("absurd frame count ", count));
    const uint64_t available = (size - kCaptureHeaderBytes) / kCaptureRecordBytes;
    if (available < count) {
        const uint64_t offset = kCaptureHeaderBytes + available * kCaptureRecordBytes;
        fail(name, offset, core::concat("truncated record ", available, " of ", count, ": the file ends after ", size,
                                        " bytes, ", kCaptureHeaderBytes + count * kCaptureRecordBytes, " expected"));
    }
    const uint64_t end = kCaptureHeaderBytes + count * kCaptureRecordBytes;
    if (size > end) fail(name, end, core::concat(size - end, " unexpected byte(s) after the last of ", count, " records"));

    Capture capture;
    capture.rateHz = rate;
    capture.frames.resize(count);
    for (uint64_t i = 0; i < count; ++i) {
        const uint64_t offset = kCaptureHeaderBytes + i * kCaptureRecordBytes;
        Reader rec(bytes.data() + offset);
        CaptureFrame& f = capture.frames[i];
        f.time = rec.f64();
        f.position.x = rec.f32();
        f.position.y = rec.f32();
        f.position.z = rec.f32();
        f.yaw = rec.f32();
        f.pitch = rec.f32();
        f.yfov = rec.f32();
        f.sceneTime = rec.f64();
        const uint32_t flags = rec.u32();
        const bool finite = std::isfinite(f.time) && std::isfinite(f.sceneTime) && std::isfinite(f.yaw) &&
                            std::isfinite(f.pitch) && std::isfinite(f.position.x) && std::isfinite(f.position.y) &&
                            std::isfinite(f.position.z);
        if (!finite) fail(name, offset, core::concat("record ", i, " has a non-finite time, position or angle"));
        if (!(f.yfov > 0.0f && f.yfov < 3.14159265f))
            fail(name, offset + 28, core::concat("record ", i, ": vertical field of view ", f.yfov, " is not in (0, pi)"));
        if (flags > 1u) fail(name, offset + 40, core::concat("record ", i, ": unknown flags ", flags));
        f.paused = (flags & 1u) != 0;
    }
    return capture;
}

Capture readCapture(const std::filesystem::path& path) {
    std::ifstream file(path, std::ios::binary);
    if (!file) throw CaptureError(path.string() + ": cannot open the capture file");
    std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
    if (file.bad()) throw CaptureError(path.string() + ": read error");
    return parseCapture(bytes, path.string());
}

void writeCapture(const std::filesystem::path& path, const Capture& capture) {
    const std::vector<uint8_t> bytes = serializeCapture(capture);
    try {
        core::writeFileAtomically(path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
    } catch (const std::runtime_error& e) {
        throw CaptureError(std::string(e.what()) + " (cannot write the capture file)");
    }
}

double captureDuration(const Capture& capture) {
    return capture.frames.size() < 2 ? 0.0 : double(capture.frames.size() - 1) / double(capture.rateHz);
}

namespace {

// a + (b - a) * s for s in [0, 1], finite for any finite a and b: the difference of two values near the largest
// double overflows (found by tests/fuzz/fuzz_capture.cpp), so it is taken in long double (wider exponent on x86-64)
// and the result is kept between a and b; where long double is no wider, an overflow gives the nearer end.
double lerpFinite(double a, double b, double s) {
    const long double r = static_cast<long double>(a) + (static_cast<long double>(b) - a) * s;
    if (!std::isfinite(r)) return s < 0.5 ? a : b;
    return std::clamp(static_cast<double>(r), std::min(a, b), std::max(a, b));
}

float lerpFinite(float a, float b, double s) {
    return static_cast<float>(lerpFinite(static_cast<double>(a), static_cast<double>(b), s));
}

CaptureFrame lerpFrames(const CaptureFrame& a, const CaptureFrame& b, double s, double time) {
    CaptureFrame out = a;
    out.time = time;
    for (int axis = 0; axis < 3; ++axis) out.position[axis] = lerpFinite(a.position[axis], b.position[axis], s);
    out.yaw = lerpFinite(a.yaw, b.yaw, s);
    out.pitch = lerpFinite(a.pitch, b.pitch, s);
    out.yfov = lerpFinite(a.yfov, b.yfov, s);
    // A paused span keeps the scene time of its start; otherwise the scene time runs with the interpolation.
    out.sceneTime = a.paused ? a.sceneTime : lerpFinite(a.sceneTime, b.sceneTime, s);
    return out;
}

}  // namespace

CaptureFrame sampleCapture(const Capture& capture, double t) {
    if (capture.frames.empty()) throw CaptureError("sampleCapture: the capture has no frames");
    const double position = std::clamp(std::isfinite(t) ? t : 0.0, 0.0, captureDuration(capture)) * capture.rateHz;
    const size_t i = std::min(size_t(position), capture.frames.size() - 1);
    if (i + 1 >= capture.frames.size()) return capture.frames.back();
    return lerpFrames(capture.frames[i], capture.frames[i + 1], position - double(i), position / capture.rateHz);
}

CaptureRecorder::CaptureRecorder(float rateHz) {
    capture_.rateHz = std::isfinite(rateHz) && rateHz > 0.0f ? std::min(rateHz, kCaptureMaxRate) : kCaptureDefaultRate;
}

void CaptureRecorder::start(const CaptureFrame& now) {
    capture_.frames.clear();
    elapsed_ = 0.0;
    previous_ = now;
    previous_.time = 0.0;
    capture_.frames.push_back(previous_);
    recording_ = true;
}

void CaptureRecorder::update(double wallDt, const CaptureFrame& now) {
    if (!recording_ || !std::isfinite(wallDt) || wallDt <= 0.0) return;
    const double start = elapsed_;
    elapsed_ += wallDt;
    CaptureFrame current = now;
    current.time = elapsed_;
    // Every record time k / rate in (start, elapsed_]: between the previous and the current state.
    for (;;) {
        const double t = double(capture_.frames.size()) / capture_.rateHz;
        if (t > elapsed_ + 1e-9 || capture_.frames.size() >= kCaptureMaxFrames) break;
        const double s = std::clamp((t - start) / wallDt, 0.0, 1.0);
        CaptureFrame frame = lerpFrames(previous_, current, s, t);
        frame.paused = s < 1.0 ? previous_.paused : current.paused;
        capture_.frames.push_back(frame);
    }
    previous_ = current;
}

scene::CameraView captureCameraView(const CaptureFrame& frame, const scene::CameraView& lens) {
    FlyCameraState state;
    state.position = frame.position;
    state.yaw = frame.yaw;
    state.pitch = frame.pitch;
    scene::CameraView view = toCameraView(state, lens);
    view.yfov = frame.yfov;
    return view;
}

}  // namespace idk::tools
