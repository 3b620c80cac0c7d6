// fuzz_gltf.cpp: libFuzzer harness for the glTF loader (scene::loadGltfFromMemory), .gltf and .glb alike (the
// loader tells them apart by the GLB magic; build-fuzz/ builds it twice, as fuzz_gltf and fuzz_glb, each with its
// own seed corpus). Contract (gltf_loader.hpp): bad input throws scene::LoadError naming the file, nothing else;
// an accepted scene keeps scene.hpp's promises (scene_invariants.hpp) and can be posed by evaluateAnimations().
//
// The harness must read nothing but its input: the file is named inside an empty temporary folder that is also the
// working folder (tinygltf searches both), and inputs whose buffer or image URIs could leave that folder (absolute
// paths, "..", separators, percent escapes, schemes other than data:) are skipped before the loader sees them.
#include <cstring>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "fuzz_support.hpp"
#include "scene/animation.hpp"
#include "scene/gltf_loader.hpp"
#include "scene_invariants.hpp"

namespace {

bool uriStaysInFolder(const std::string& uri) {
    if (uri.rfind("data:", 0) == 0) return true;
    if (uri.empty() || uri.find_first_not_of('.') == std::string::npos) return false;  // "", ".", "..", "..."
    for (const char c : uri) {
        const bool plain = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' ||
                           c == '_' || c == '-';
        if (!plain) return false;
    }
    return true;
}

// False when the JSON parses and names a URI that could resolve outside the empty folder. JSON the loader's parser
// (nlohmann, which tinygltf uses too) cannot read never gets as far as resolving a URI, so it is loaded.
bool onlyLocalUris(const uint8_t* data, size_t size) {
    std::string_view text(reinterpret_cast<const char*>(data), size);
    if (size >= 20 && std::memcmp(data, "glTF", 4) == 0) {
        uint32_t jsonLength = 0;
        std::memcpy(&jsonLength, data + 12, 4);
        if (jsonLength > size - 20) return true;  // the loader's GLB checks reject it first
        text = text.substr(20, jsonLength);
    }
    const auto json = nlohmann::json::parse(text.begin(), text.end(), nullptr, /*allow_exceptions=*/false);
    if (json.is_discarded() || !json.is_object()) return true;
    for (const char* list : {"buffers", "images"}) {
        const auto it = json.find(list);
        if (it == json.end() || !it->is_array()) continue;
        for (const auto& item : *it) {
            if (!item.is_object()) continue;
            const auto uri = item.find("uri");
            if (uri != item.end() && uri->is_string() && !uriStaysInFolder(uri->get<std::string>())) return false;
        }
    }
    return true;
}

}  // namespace

IDK_FUZZ_TARGET(gltf) {
    const std::filesystem::path name = idk::fuzz::emptyWorkingFolder() / "input.gltf";
    if (!onlyLocalUris(data, size)) return -1;  // not added to the corpus
    try {
        idk::scene::Scene scene = idk::scene::loadGltfFromMemory({data, size}, name);
        if (std::string broken = idk::fuzz::firstBrokenInvariant(scene); !broken.empty())
            idk::fuzz::violation("gltf", "loaded scene breaks an invariant: " + broken);
        // What `idk render --time T` does next with an accepted file: pose it (all animations) and summarise it.
        idk::scene::evaluateAnimations(scene, 0.75);
        (void)scene.features();
        if (std::string broken = idk::fuzz::firstBrokenInvariant(scene); !broken.empty())
            idk::fuzz::violation("gltf", "posed scene breaks an invariant: " + broken);
    } catch (const idk::fuzz::ContractViolation&) {
        throw;
    } catch (const idk::scene::LoadError& e) {
        if (e.file() != name) idk::fuzz::violation("gltf", std::string("LoadError names another file: ") + e.what());
    } catch (const std::exception& e) {
        idk::fuzz::violation("gltf", std::string("undocumented exception: ") + e.what());
    }
    return 0;
}
