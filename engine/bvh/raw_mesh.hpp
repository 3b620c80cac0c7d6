// raw_mesh.hpp: loader of the raw triangle files used for BVH tests and benchmarks (../shared/scenes/bunny/
// bunny.bin): int32 triangle count, then count * 3 vertices of 4 little-endian float32 (x, y, z, unused).
#pragma once

#include "bvh/geometry.hpp"

#include <cstddef>
#include <span>
#include <string>
#include <vector>

namespace idk::bvh {

// Throws std::runtime_error naming `path` when the file cannot be read, the count is negative, or the size is not
// exactly 4 + count * 48 bytes.
std::vector<Triangle> loadRawTriangles(const std::string& path);

// The same checks on bytes already in memory; `name` is used in error messages.
std::vector<Triangle> parseRawTriangles(std::span<const std::byte> bytes, const std::string& name);

}  // namespace idk::bvh
