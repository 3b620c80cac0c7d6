// spirv_file.hpp: loads a compiled SPIR-V module (.spv) from disk as 32-bit words, checking that the file exists,
// that its size is a whole number of words and that it starts with the SPIR-V magic number.
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

namespace idk::shader {

// Throws std::runtime_error naming the path and the cause (missing, unreadable, empty, size not a multiple of 4,
// wrong magic number).
std::vector<uint32_t> readSpirvFile(const std::filesystem::path& path);

}  // namespace idk::shader
