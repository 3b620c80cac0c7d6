// log.cpp: the default stderr sink and the global level filter.
#include "core/log.hpp"

#include <cstdio>
#include <mutex>

namespace idk::core {
namespace {
std::mutex gLogMutex;
LogSink gSink;
LogLevel gMinimum = LogLevel::Info;

const char* levelName(LogLevel level) {
    switch (level) {
        case LogLevel::Debug: return "debug";
        case LogLevel::Info: return "info";
        case LogLevel::Warning: return "warning";
        case LogLevel::Error: return "error";
    }
    return "?";
}
}  // namespace

void setLogSink(LogSink sink) {
    std::lock_guard lock(gLogMutex);
    gSink = std::move(sink);
}

void setLogLevel(LogLevel minimum) {
    std::lock_guard lock(gLogMutex);
    gMinimum = minimum;
}

void logMessage(LogLevel level, std::string_view message) {
    std::lock_guard lock(gLogMutex);
    if (level < gMinimum) return;
    if (gSink) {
        gSink(level, message);
        return;
    }
    std::fprintf(stderr, "idk %s: %.*s\n", levelName(level), static_cast<int>(message.size()), message.data());
}

}  // namespace idk::core
