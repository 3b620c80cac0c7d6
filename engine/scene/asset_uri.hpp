// asset_uri.hpp: where a glTF file's external URIs (buffers, images) may point. One rule for every path that
// turns a URI into a file read (tinygltf's buffer reads, the image records the texture decoder opens later):
// the percent-decoded URI must be relative and, after `..` and symlinks are resolved, lie inside the asset's
// folder. A scene from an untrusted source can then read nothing but its own folder. `allowExternal`
// (`--allow-external-uris`) lifts the rule for trusted content.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

namespace idk::scene {

// %XX escapes decoded (RFC 3986); a '%' not followed by two hex digits stays as is. '+' is not a space in a
// URI path.
std::string percentDecode(std::string_view uri);

bool isDataUri(std::string_view uri);

// The folder external URIs of `assetFile` resolve against, made absolute with symlinks resolved.
std::filesystem::path assetFolder(const std::filesystem::path& assetFile);

// Whether `path` (made absolute, `..` and symlinks resolved) lies inside `folder` (already canonical).
bool insideFolder(const std::filesystem::path& folder, const std::filesystem::path& path);

// The file an external (non-data) URI names: percent-decoded, resolved against the asset's folder, made
// canonical. Throws LoadError naming `assetFile`, `what` (e.g. "buffer 1") and the URI when the URI holds a NUL
// byte, or (unless allowExternal) is an absolute path or resolves outside the folder. Only the file system's
// metadata (symlink targets) is read, never a file's content.
std::filesystem::path resolveAssetUri(const std::filesystem::path& assetFile, const std::string& uri,
                                      bool allowExternal, const std::string& what);

}  // namespace idk::scene
