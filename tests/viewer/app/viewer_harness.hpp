// viewer_harness.hpp: runs idk-viewer (and idk render) as child processes for the viewer tests: a private Xvfb
// display per test process (Xvfb -displayfd picks a free display number, so parallel tests never collide),
// captured output and exit code, 8-bit image comparison, and a generated glTF wall scene.
#pragma once
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace idk::test {

// Starts Xvfb once per process (stopped at exit); returns ":N". Fails the test (GTEST_SKIP is not used: the
// viewer label requires Xvfb) when Xvfb cannot start.
std::string xvfbDisplay();

struct ProcessResult {
    int exitCode = -1;
    std::string output;  // stdout and stderr together
};
// Runs `command` (a shell command line) with `environment` prepended (e.g. "DISPLAY=:5").
ProcessResult runCommand(const std::string& command, const std::string& environment = "");

// A fresh empty folder under the build tree for one test.
std::filesystem::path testFolder(const std::string& name);
void writeText(const std::filesystem::path& path, const std::string& text);

// 8-bit sRGB codes of a PNG (RGBA, top row first).
struct Codes {
    uint32_t width = 0, height = 0;
    std::vector<uint8_t> rgba;
};
Codes readCodes(const std::filesystem::path& png);

struct CodeDifference {
    double meanRgb = 0.0;      // mean |a - b| over RGB of all pixels, in codes
    int maxRgb = 0;            // largest |a - b|
    double fractionOver = 0.0; // pixels whose largest RGB difference exceeds `threshold`
};
CodeDifference compareCodes(const Codes& a, const Codes& b, int threshold);

// A glTF file: one 40 x 40 square wall in the plane z = 0 (facing +z, double-sided) and a perspective camera
// at (0, 0, cameraZ) looking down -z (yfov 45 degrees).
std::filesystem::path writeWallScene(const std::filesystem::path& folder, float cameraZ);

}  // namespace idk::test
