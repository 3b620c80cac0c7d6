// fuzz_capture.cpp: libFuzzer harness for the camera capture reader (tools::parseCapture, what readCapture and
// `idk render --replay` run on a file). Contract (camera_capture.hpp): bad input throws CaptureError naming the file
// and a byte offset; an accepted capture has finite values, a rate in (0, kCaptureMaxRate], serializes back to the
// same bytes (the reserved header word aside, which the reader ignores and the writer zeroes) and can be sampled.
#include <algorithm>
#include <cmath>
#include <string>

#include "fuzz_support.hpp"
#include "tools/camera_capture.hpp"

namespace {

constexpr const char* kName = "fuzz.idkcap";

void checkCapture(const std::vector<uint8_t>& bytes, const idk::tools::Capture& c) {
    using idk::fuzz::violation;
    if (!(c.rateHz > 0.0f && c.rateHz <= idk::tools::kCaptureMaxRate)) violation("capture", "rate out of range");
    std::vector<uint8_t> again = idk::tools::serializeCapture(c);
    std::vector<uint8_t> expected = bytes;
    if (expected.size() < idk::tools::kCaptureHeaderBytes) violation("capture", "accepted a truncated header");
    std::fill_n(expected.begin() + 20, 4, uint8_t(0));  // the reserved word
    if (again != expected) violation("capture", "serializeCapture(parseCapture(x)) != x");
    if (c.frames.empty()) return;
    const double duration = idk::tools::captureDuration(c);
    for (const double t : {-1.0, 0.0, 0.37 * duration, duration, duration + 1.0, double(NAN)}) {
        const idk::tools::CaptureFrame f = idk::tools::sampleCapture(c, t);
        if (!std::isfinite(f.time) || !std::isfinite(f.sceneTime) || !std::isfinite(f.position.x) ||
            !std::isfinite(f.position.y) || !std::isfinite(f.position.z) || !std::isfinite(f.yaw) ||
            !std::isfinite(f.pitch) || !(f.yfov > 0.0f))
            violation("capture", "sampleCapture gave a non-finite value at t = " + std::to_string(t));
    }
}

}  // namespace

IDK_FUZZ_TARGET(capture) {
    const std::vector<uint8_t> bytes(data, data + size);
    try {
        checkCapture(bytes, idk::tools::parseCapture(bytes, kName));
    } catch (const idk::fuzz::ContractViolation&) {
        throw;
    } catch (const idk::tools::CaptureError& e) {
        if (std::string(e.what()).rfind(std::string(kName) + ": byte offset ", 0) != 0)
            idk::fuzz::violation("capture", std::string("CaptureError without file and offset: ") + e.what());
    } catch (const std::exception& e) {
        idk::fuzz::violation("capture", std::string("undocumented exception: ") + e.what());
    }
    return 0;
}
