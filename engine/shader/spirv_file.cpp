// spirv_file.cpp: reads a .spv file into words with explicit, path-naming errors for each way it can be wrong.
#include "shader/spirv_file.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <string>

namespace idk::shader {

std::vector<uint32_t> readSpirvFile(const std::filesystem::path& path) {
    auto fail = [&](const std::string& cause) -> std::runtime_error {
        return std::runtime_error("cannot load SPIR-V " + path.string() + ": " + cause);
    };
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) {
        throw fail("no such file");
    }
    if (!std::filesystem::is_regular_file(path, ec)) {
        throw fail("not a regular file");
    }
    const uintmax_t bytes = std::filesystem::file_size(path, ec);
    if (ec) {
        throw fail(ec.message());
    }
    if (bytes == 0) {
        throw fail("file is empty");
    }
    if (bytes % 4 != 0) {
        throw fail("size " + std::to_string(bytes) + " bytes is not a multiple of 4");
    }
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        throw fail(std::strerror(errno));
    }
    std::vector<uint32_t> words(bytes / 4);
    in.read(reinterpret_cast<char*>(words.data()), static_cast<std::streamsize>(bytes));
    if (in.gcount() != static_cast<std::streamsize>(bytes)) {
        throw fail("short read");
    }
    if (words[0] != 0x07230203u) {
        throw fail("not a SPIR-V module (bad magic number)");
    }
    return words;
}

}  // namespace idk::shader
