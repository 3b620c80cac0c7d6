// log.hpp: leveled logging to stderr with a replaceable sink (tests capture messages through it).
// g++ 12 has no <format>, so messages are built by streaming the arguments: logInfo("loaded ", n, " meshes").
#pragma once
#include <functional>
#include <sstream>
#include <string>
#include <string_view>

namespace idk::core {

enum class LogLevel { Debug, Info, Warning, Error };

using LogSink = std::function<void(LogLevel, std::string_view)>;

void setLogSink(LogSink sink);       // an empty sink restores the stderr sink
void setLogLevel(LogLevel minimum);  // messages below are dropped
void logMessage(LogLevel level, std::string_view message);

// Concatenates any streamable values into one string.
template <class... Args>
std::string concat(const Args&... args) {
    std::ostringstream out;
    (out << ... << args);
    return out.str();
}

template <class... Args> void logDebug(const Args&... args) { logMessage(LogLevel::Debug, concat(args...)); }
template <class... Args> void logInfo(const Args&... args) { logMessage(LogLevel::Info, concat(args...)); }
template <class... Args> void logWarning(const Args&... args) { logMessage(LogLevel::Warning, concat(args...)); }
template <class... Args> void logError(const Args&... args) { logMessage(LogLevel::Error, concat(args...)); }

}  // namespace idk::core
