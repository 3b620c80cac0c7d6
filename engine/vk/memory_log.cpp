// memory_log.cpp: see memory_log.hpp.
#include "vk/memory_log.hpp"

#include <cstdlib>
#include <stdexcept>
#include <string>

namespace idk::vk {

uint64_t residentKiB() {
    std::ifstream status("/proc/self/status");
    std::string line;
    while (std::getline(status, line))
        if (line.rfind("VmRSS:", 0) == 0) return std::strtoull(line.c_str() + 6, nullptr, 10);
    return 0;
}

MemoryLog::MemoryLog(const std::filesystem::path& file, uint64_t every)
    : out_(file, std::ios::trunc), every_(every == 0 ? 1 : every) {
    if (!out_) throw std::runtime_error(file.string() + ": cannot write the memory log");
}

std::optional<MemoryLog> MemoryLog::fromEnvironment() {
    const char* env = std::getenv("IDK_MEMORY_LOG");
    if (!env || !*env) return std::nullopt;
    std::string text = env;
    uint64_t every = 100;
    if (const size_t colon = text.rfind(':'); colon != std::string::npos) {
        every = std::strtoull(text.c_str() + colon + 1, nullptr, 10);
        text.resize(colon);
    }
    return std::optional<MemoryLog>(std::in_place, text, every);
}

void MemoryLog::sample(uint64_t frame, const MemoryAllocator& allocator) {
    if (frame % every_ != 0) return;
    const MemoryStats stats = allocator.stats();
    out_ << "{\"frame\":" << frame << ",\"rssKiB\":" << residentKiB() << ",\"deviceBlockBytes\":" << stats.blockBytes
         << ",\"deviceDedicatedBytes\":" << stats.dedicatedBytes
         << ",\"deviceMemoryObjects\":" << stats.deviceMemoryCount << ",\"deviceBytes\":{";
    bool first = true;
    for (const auto& [category, bytes] : stats.bytesByCategory) {
        out_ << (first ? "" : ",") << "\"" << category << "\":" << bytes;  // categories are engine-chosen names
        first = false;
    }
    out_ << "}}\n";
    out_.flush();
}

}  // namespace idk::vk
