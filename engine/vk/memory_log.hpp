// memory_log.hpp: a periodic memory dump for soak runs (`idk-viewer --memory-log F`, `IDK_MEMORY_LOG=F idk render
// --replay ...`; scripts/soak.sh): every `every` frames one JSON line with the frame number, the process's resident
// host memory (VmRSS from /proc/self/status) and the device memory the engine's allocator holds, by category.
#pragma once
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <optional>

#include "vk/memory.hpp"

namespace idk::vk {

class MemoryLog {
public:
    // Throws std::runtime_error naming the file when it cannot be created.
    MemoryLog(const std::filesystem::path& file, uint64_t every);
    // IDK_MEMORY_LOG=FILE[:EVERY] (default every 100 frames); empty when unset.
    static std::optional<MemoryLog> fromEnvironment();
    // Writes a line when frame % every == 0 (and always for frame 0).
    void sample(uint64_t frame, const MemoryAllocator& allocator);

private:
    std::ofstream out_;
    uint64_t every_;
};

// VmRSS of this process in KiB (0 where /proc is not available).
uint64_t residentKiB();

}  // namespace idk::vk
