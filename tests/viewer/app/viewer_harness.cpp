// viewer_harness.cpp: Xvfb start-up, child processes, image codes and the wall scene for the viewer tests.
#include "viewer/app/viewer_harness.hpp"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <stdexcept>

#include "core/image_file.hpp"

namespace idk::test {
namespace {

struct Xvfb {
    pid_t pid = -1;
    std::string display;
    ~Xvfb() {
        if (pid > 0) {
            kill(pid, SIGTERM);
            waitpid(pid, nullptr, 0);
        }
    }
};

std::string base64(const std::vector<uint8_t>& bytes) {
    static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t i = 0; i < bytes.size(); i += 3) {
        uint32_t v = uint32_t(bytes[i]) << 16;
        if (i + 1 < bytes.size()) v |= uint32_t(bytes[i + 1]) << 8;
        if (i + 2 < bytes.size()) v |= bytes[i + 2];
        out += table[(v >> 18) & 63];
        out += table[(v >> 12) & 63];
        out += i + 1 < bytes.size() ? table[(v >> 6) & 63] : '=';
        out += i + 2 < bytes.size() ? table[v & 63] : '=';
    }
    return out;
}

}  // namespace

std::string xvfbDisplay() {
    static Xvfb server;
    if (!server.display.empty()) return server.display;
    int fds[2];
    if (pipe(fds) != 0) throw std::runtime_error("pipe failed");
    pid_t pid = fork();
    if (pid == 0) {
        close(fds[0]);
        std::string fd = std::to_string(fds[1]);
        // -displayfd: Xvfb picks a free display and writes its number to the pipe once it accepts clients.
        execlp("Xvfb", "Xvfb", "-displayfd", fd.c_str(), "-screen", "0", "640x480x24", "-nolisten", "tcp",
               static_cast<char*>(nullptr));
        _exit(127);
    }
    close(fds[1]);
    std::string number;
    char c;
    while (read(fds[0], &c, 1) == 1 && c != '\n') number += c;
    close(fds[0]);
    if (pid < 0 || number.empty()) throw std::runtime_error("cannot start Xvfb (is the xvfb package installed?)");
    server.pid = pid;
    server.display = ":" + number;
    return server.display;
}

ProcessResult runCommand(const std::string& command, const std::string& environment) {
    std::string full = (environment.empty() ? "" : "env " + environment + " ") + command + " 2>&1";
    ProcessResult result;
    FILE* pipe = popen(full.c_str(), "r");
    if (!pipe) throw std::runtime_error("popen failed: " + full);
    std::array<char, 4096> buffer;
    size_t n;
    while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) result.output.append(buffer.data(), n);
    int status = pclose(pipe);
    result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
    return result;
}

std::filesystem::path testFolder(const std::string& name) {
    std::filesystem::path folder = std::filesystem::path(IDK_BINARY_DIR) / "viewer_tests" / name;
    std::filesystem::remove_all(folder);
    std::filesystem::create_directories(folder);
    return folder;
}

void writeText(const std::filesystem::path& path, const std::string& text) {
    std::ofstream file(path, std::ios::binary);
    file << text;
    if (!file) throw std::runtime_error(path.string() + ": cannot write");
}

Codes readCodes(const std::filesystem::path& png) {
    core::ImageRgba32f image = core::readImage(png);
    Codes codes{image.width, image.height, std::vector<uint8_t>(image.pixels.size())};
    for (size_t i = 0; i < image.pixels.size(); ++i) {
        float v = i % 4 == 3 ? image.pixels[i] : core::linearToSrgb(image.pixels[i]);
        codes.rgba[i] = uint8_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
    }
    return codes;
}

CodeDifference compareCodes(const Codes& a, const Codes& b, int threshold) {
    CodeDifference d;
    if (a.width != b.width || a.height != b.height) {
        ADD_FAILURE() << "image sizes differ: " << a.width << "x" << a.height << " vs " << b.width << "x" << b.height;
        d.meanRgb = d.maxRgb = 255;
        d.fractionOver = 1.0;
        return d;
    }
    const size_t pixels = size_t(a.width) * a.height;
    double sum = 0.0;
    size_t over = 0;
    for (size_t p = 0; p < pixels; ++p) {
        int largest = 0;
        for (int c = 0; c < 3; ++c) {
            int diff = std::abs(int(a.rgba[p * 4 + c]) - int(b.rgba[p * 4 + c]));
            sum += diff;
            largest = std::max(largest, diff);
        }
        d.maxRgb = std::max(d.maxRgb, largest);
        if (largest > threshold) ++over;
    }
    d.meanRgb = sum / double(pixels * 3);
    d.fractionOver = double(over) / double(pixels);
    return d;
}

std::filesystem::path writeWallScene(const std::filesystem::path& folder, float cameraZ) {
    // indices (6 x u16 = 12 bytes) then positions (4 x vec3 = 48 bytes) in one buffer.
    std::vector<uint8_t> bytes(60);
    const uint16_t indices[6] = {0, 1, 2, 0, 2, 3};
    const float positions[12] = {-20, -20, 0, 20, -20, 0, 20, 20, 0, -20, 20, 0};
    std::memcpy(bytes.data(), indices, sizeof(indices));
    std::memcpy(bytes.data() + 12, positions, sizeof(positions));
    std::string json = R"({
  "asset": {"version": "2.0"},
  "scene": 0,
  "scenes": [{"nodes": [0, 1]}],
  "nodes": [{"name": "wall", "mesh": 0}, {"name": "camera", "camera": 0, "translation": [0, 0, )" +
                       std::to_string(cameraZ) + R"(]}],
  "cameras": [{"type": "perspective", "perspective": {"yfov": 0.785398, "znear": 0.05}}],
  "materials": [{"name": "grey", "doubleSided": true,
                 "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.8, 0.8, 1], "metallicFactor": 0, "roughnessFactor": 1}}],
  "meshes": [{"name": "wall", "primitives": [{"attributes": {"POSITION": 1}, "indices": 0, "material": 0}]}],
  "buffers": [{"byteLength": 60, "uri": "data:application/octet-stream;base64,)" +
                       base64(bytes) + R"("}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 12, "target": 34963},
                  {"buffer": 0, "byteOffset": 12, "byteLength": 48, "target": 34962}],
  "accessors": [{"bufferView": 0, "componentType": 5123, "count": 6, "type": "SCALAR"},
                {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3",
                 "min": [-20, -20, 0], "max": [20, 20, 0]}]
}
)";
    std::filesystem::path path = folder / "wall.gltf";
    writeText(path, json);
    return path;
}

}  // namespace idk::test
