// raw_mesh.cpp: bounds-checked parsing of the raw triangle format (byte order fixed to little endian).
#include "bvh/raw_mesh.hpp"

#include <bit>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <stdexcept>

namespace idk::bvh {
namespace {

uint32_t readU32(const std::byte* p) {
    return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}

}  // namespace

std::vector<Triangle> parseRawTriangles(std::span<const std::byte> bytes, const std::string& name) {
    constexpr size_t kVertexBytes = 16;
    constexpr size_t kTriangleBytes = 3 * kVertexBytes;
    if (bytes.size() < 4) {
        throw std::runtime_error(name + ": raw triangle file too short (" + std::to_string(bytes.size()) +
                                 " bytes, the triangle count alone needs 4)");
    }
    const int32_t count = std::bit_cast<int32_t>(readU32(bytes.data()));
    if (count < 0) throw std::runtime_error(name + ": negative triangle count " + std::to_string(count));
    const size_t expected = 4 + size_t(count) * kTriangleBytes;
    if (bytes.size() != expected) {
        throw std::runtime_error(name + ": " + std::to_string(count) + " triangles need " + std::to_string(expected) +
                                 " bytes, the file has " + std::to_string(bytes.size()));
    }
    std::vector<Triangle> triangles(static_cast<size_t>(count));
    const std::byte* p = bytes.data() + 4;
    for (Triangle& tri : triangles) {
        for (glm::vec3* v : {&tri.v0, &tri.v1, &tri.v2}) {
            for (int c = 0; c < 3; ++c) (*v)[c] = std::bit_cast<float>(readU32(p + 4 * c));
            p += kVertexBytes;
        }
    }
    return triangles;
}

std::vector<Triangle> loadRawTriangles(const std::string& path) {
    std::ifstream file(path, std::ios::binary);
    if (!file) throw std::runtime_error(path + ": cannot open raw triangle file");
    std::vector<char> data((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
    if (file.bad()) throw std::runtime_error(path + ": read error");
    return parseRawTriangles(std::as_bytes(std::span<const char>(data)), path);
}

}  // namespace idk::bvh
