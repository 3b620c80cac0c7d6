// gltf_files.cpp: every file the glTF loader reads, and what it may cost: the asset file itself, the URI check
// (asset_uri.hpp) run over the JSON before tinygltf reads anything, tinygltf's file-system callbacks (confined
// again, nothing expanded or written) and the LoadOptions::maxMemoryBytes budget they all charge.
#include <cstdio>
#include <fstream>

#include "scene/asset_uri.hpp"
#include "scene/gltf_internal.hpp"

namespace idk::scene::gltf {

namespace {
std::string sizeText(uint64_t bytes) {
    if (bytes < (1u << 20)) return std::to_string(bytes) + " bytes";
    char text[32];
    std::snprintf(text, sizeof(text), "%.1f MiB", double(bytes) / double(1u << 20));
    return text;
}
}  // namespace

void MemoryBudget::charge(uint64_t bytes, const std::string& what) {
    if (limit_ != 0 && (bytes > limit_ || used_ > limit_ - bytes))
        throw LoadError(file_, "memory budget exceeded: " + what + " needs " + sizeText(bytes) + " with " +
                                   sizeText(used_) + " already committed; --max-memory is " + sizeText(limit_));
    used_ += bytes;
}

std::vector<uint8_t> readWholeFile(const std::filesystem::path& path, MemoryBudget* budget) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) throw LoadError(path, "file not found");
    if (!std::filesystem::is_regular_file(path, ec)) throw LoadError(path, "not a regular file");
    const auto size = std::filesystem::file_size(path, ec);
    if (ec) throw LoadError(path, "cannot read file size: " + ec.message());
    if (size > kMaxFileBytes) throw LoadError(path, "file larger than 4 GiB");
    if (budget) budget->charge(size, "file " + path.filename().string());
    std::ifstream in(path, std::ios::binary);
    if (!in) throw LoadError(path, "cannot open file");
    std::vector<uint8_t> bytes(static_cast<size_t>(size));
    if (size > 0 && !in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(size)))
        throw LoadError(path, "cannot read file");
    return bytes;
}

void checkUris(const std::filesystem::path& path, const nlohmann::json& json, const LoadOptions& options,
               MemoryBudget& budget) {
    for (const std::string kind : {"buffer", "image"}) {
        const auto list = json.find(kind + "s");
        if (list == json.end() || !list->is_array()) continue;
        for (size_t i = 0; i < list->size(); ++i) {
            const auto& item = (*list)[i];
            const auto uri = item.is_object() ? item.find("uri") : item.end();
            if (uri == item.end() || !uri->is_string()) continue;
            if (isDataUri(uri->get<std::string>())) {
                budget.charge(uri->get<std::string>().size() / 4 * 3, kind + " " + str(i) + " data URI");
                continue;
            }
            resolveAssetUri(path, uri->get<std::string>(), options.allowExternalUris, kind + " " + str(i));
        }
    }
}

namespace {

bool fileAllowed(const std::string& file, void* user) {
    const auto& access = *static_cast<const FileAccess*>(user);
    std::error_code ec;
    return std::filesystem::is_regular_file(file, ec) && (access.allowExternal || insideFolder(access.folder, file));
}

// No `~` or `$VAR` expansion. tinygltf joins even an absolute URI onto the base folder ("base//abs"): an
// allowed absolute URI is taken as written (a refused one never gets here, see checkUris).
std::string expandFile(const std::string& file, void* user) {
    const auto& access = *static_cast<const FileAccess*>(user);
    const std::string prefix = access.baseDir + "/";
    if (access.allowExternal && !access.baseDir.empty() && file.size() > prefix.size() &&
        file.compare(0, prefix.size(), prefix) == 0 && file[prefix.size()] == '/')
        return file.substr(prefix.size());
    return file;
}

bool readAllowedFile(std::vector<unsigned char>* out, std::string* err, const std::string& file, void* user) {
    if (!fileAllowed(file, user)) {
        if (err) *err = "not a regular file inside the asset's folder";
        return false;
    }
    // Over the budget: the LoadError passes through tinygltf to loadGltfFromMemory unchanged.
    *out = readWholeFile(file, static_cast<const FileAccess*>(user)->budget);
    return true;
}

bool writeNothing(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
    if (err) *err = "the loader never writes files";
    return false;
}

}  // namespace

tinygltf::FsCallbacks fileCallbacks(FileAccess& access) {
    return {&fileAllowed, &expandFile, &readAllowedFile, &writeNothing, &access};
}

}  // namespace idk::scene::gltf
