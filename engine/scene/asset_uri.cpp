// asset_uri.cpp: confinement of glTF external URIs to the asset's folder (see asset_uri.hpp).
#include "scene/asset_uri.hpp"

#include <algorithm>

#include "scene/gltf_loader.hpp"

namespace idk::scene {

std::string percentDecode(std::string_view uri) {
    auto hex = [](char c) -> int {
        if (c >= '0' && c <= '9') return c - '0';
        if (c >= 'a' && c <= 'f') return c - 'a' + 10;
        if (c >= 'A' && c <= 'F') return c - 'A' + 10;
        return -1;
    };
    std::string out;
    for (size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] == '%' && i + 2 < uri.size() && hex(uri[i + 1]) >= 0 && hex(uri[i + 2]) >= 0) {
            out += char(hex(uri[i + 1]) * 16 + hex(uri[i + 2]));
            i += 2;
        } else {
            out += uri[i];
        }
    }
    return out;
}

bool isDataUri(std::string_view uri) {
    return uri.substr(0, 5) == "data:";
}

std::filesystem::path assetFolder(const std::filesystem::path& assetFile) {
    std::error_code ec;
    const std::filesystem::path parent = assetFile.parent_path();
    std::filesystem::path folder = std::filesystem::absolute(parent.empty() ? "." : parent, ec);
    if (ec) folder = parent;
    std::filesystem::path canonical = std::filesystem::weakly_canonical(folder, ec);
    return ec ? folder.lexically_normal() : canonical;
}

bool insideFolder(const std::filesystem::path& folder, const std::filesystem::path& path) {
    std::error_code ec;
    std::filesystem::path resolved = std::filesystem::weakly_canonical(std::filesystem::absolute(path, ec), ec);
    if (ec) return false;
    // Component-wise prefix test: "/a/bc" is not inside "/a/b". A trailing empty component ("/a/b/") is ignored.
    auto f = folder.begin(), fEnd = folder.end();
    if (f != fEnd && std::prev(fEnd)->empty()) --fEnd;
    for (auto p = resolved.begin(); f != fEnd; ++f, ++p)
        if (p == resolved.end() || *p != *f) return false;
    return true;
}

std::filesystem::path resolveAssetUri(const std::filesystem::path& assetFile, const std::string& uri,
                                      bool allowExternal, const std::string& what) {
    const std::string decoded = percentDecode(uri);
    const std::string named = what + " uri '" + uri + "'";
    const std::string hint = " (pass --allow-external-uris to read files outside the asset's folder)";
    if (decoded.find('\0') != std::string::npos) throw LoadError(assetFile, named + " contains a NUL byte");
    const std::filesystem::path relative(decoded);
    if (relative.has_root_path() && !allowExternal)
        throw LoadError(assetFile, named + " is an absolute path, not relative to the asset" + hint);
    const std::filesystem::path folder = assetFolder(assetFile);
    std::error_code ec;
    std::filesystem::path resolved = std::filesystem::weakly_canonical(folder / relative, ec);
    if (ec) resolved = (folder / relative).lexically_normal();
    if (!allowExternal && !insideFolder(folder, resolved))
        throw LoadError(assetFile, named + " resolves to " + resolved.string() + ", outside the asset's folder " +
                                       folder.string() + hint);
    return resolved;
}

}  // namespace idk::scene
