// atomic_file.hpp: user-requested outputs (images, capture files, graph dumps) appear whole or not at all. The
// bytes go to a fresh temporary file next to the target, which is flushed to disk and renamed over the target
// (rename is atomic within a file system): a crash or an error mid-write never leaves a truncated file under the
// requested name, and an older file there survives a failed write.
#pragma once
#include <filesystem>
#include <functional>
#include <string_view>

namespace idk::core {

// The temporary's name: "<folder>/.<stem>.partial-XXXXXX<extension>" (the extension is kept so writers that pick
// the format from the name still do). Calls write(temporary), then fsyncs and renames it onto `path` (whose folder
// must exist). If write throws, or anything after it fails, the temporary is removed and the exception
// propagates (std::runtime_error naming `path` for the file system's own failures); `path` is untouched.
void writeAtomically(const std::filesystem::path& path,
                     const std::function<void(const std::filesystem::path& temporary)>& write);

// writeAtomically for bytes already in memory.
void writeFileAtomically(const std::filesystem::path& path, std::string_view bytes);

}  // namespace idk::core
