// cmd_bvh.cpp: `idk bvh SCENE [--split-factor X] [--spatial-splits [--split-budget X]] [--json]`: builds the BLAS of
// a scene (every instanced triangle of a glTF file in world space, or a bunny.bin-style raw triangle file) with the
// SweepSAH builder and pre-splitting, or the spatial-split builder (engine/bvh) and prints its statistics: triangles, fragments, references, nodes, leaves, SAH, EPO, depth, the
// traversal stack it needs and the build time. The counterpart of IDKEngine's BVH debug UI (BLAS.cs statistics).
#include <nlohmann/json.hpp>

#include <unistd.h>

#include <cctype>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>

#include "app/commands.hpp"
#include "app/scene_options.hpp"
#include "bvh/blas.hpp"
#include "bvh/metrics.hpp"
#include "bvh/raw_mesh.hpp"
#include "core/cli.hpp"
#include "render/bvh_gpu.hpp"
#include "scene/gltf_loader.hpp"

namespace idk::app {

const char* const kBvhHelp =
    "usage: idk bvh SCENE [--split-factor X] [--spatial-splits [--split-budget X]] [--json] [--no-epo]\n"
    "  SCENE            .gltf/.glb (all instanced triangles in world space) or a raw triangle file (.bin:\n"
    "                   int32 count, then 3 vertices of 4 float32 per triangle, like ../shared/scenes/bunny/bunny.bin)\n"
    "  --split-factor X pre-splitting: up to X times more fragments for large triangles (default 0 = off;\n"
    "                   IDKEngine uses 0.3)\n"
    "  --spatial-splits the spatial-split builder (SBVH) instead of SweepSAH alone: triangles straddling a node are\n"
    "                   chopped where that lowers the SAH\n"
    "  --split-budget X with --spatial-splits: at most X references per triangle (fragment) in all (default 2,\n"
    "                   in [1, 16]; 1 = no spatial split)\n"
    "  --json           machine-readable output\n"
    "  --no-epo         skip the end-point overlap metric (exact, and slow on millions of triangles)\n"
    "Prints triangles, fragments after pre-splitting, triangle references in the leaves, nodes, leaves, SAH (traversal\n"
    "cost 1, triangle cost 1.1), EPO, maximum depth, the traversal stack the GPU needs, and the build time.\n";

namespace {

// A one-line progress indication on stderr while a long step runs, only when stderr is a terminal; it appears after
// half a second so quick runs print nothing, and is erased when the step ends.
class Progress {
public:
    Progress() : enabled_(isatty(STDERR_FILENO) != 0) {
        if (enabled_) thread_ = std::thread([this] { run(); });
    }
    ~Progress() {
        if (!enabled_) return;
        {
            std::lock_guard<std::mutex> lock(mutex_);
            done_ = true;
        }
        wake_.notify_all();
        thread_.join();
    }
    Progress(const Progress&) = delete;
    Progress& operator=(const Progress&) = delete;

    void step(const std::string& what) {
        if (!enabled_) return;
        std::lock_guard<std::mutex> lock(mutex_);
        step_ = what;
        start_ = std::chrono::steady_clock::now();
    }

private:
    void run() {
        static const char kSpinner[] = "|/-\\";
        std::unique_lock<std::mutex> lock(mutex_);
        bool shown = false;
        for (uint32_t tick = 0; !done_; ++tick) {
            wake_.wait_for(lock, std::chrono::milliseconds(100));
            if (done_) break;
            const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
            if (step_.empty() || seconds < 0.5) continue;
            std::fprintf(stderr, "\r\033[K%c %s %.1f s", kSpinner[tick % 4], step_.c_str(), seconds);
            std::fflush(stderr);
            shown = true;
        }
        if (shown) std::fprintf(stderr, "\r\033[K");
    }

    bool enabled_;
    std::thread thread_;
    std::mutex mutex_;
    std::condition_variable wake_;
    bool done_ = false;
    std::string step_;
    std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

std::vector<bvh::Triangle> loadTriangles(const std::filesystem::path& path, const scene::LoadOptions& options,
                                         std::string& kind) {
    std::string ext = path.extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    if (ext == ".bin") {
        kind = "raw triangles";
        return bvh::loadRawTriangles(path.string());
    }
    if (ext != ".gltf" && ext != ".glb") {
        throw std::runtime_error(path.string() + ": unsupported scene file (expected .gltf, .glb or a raw .bin)");
    }
    kind = "glTF, instanced triangles in world space";
    const scene::Scene scene = scene::loadGltf(path, options);  // logs its own warnings
    const render::TriangleMesh mesh = render::worldTriangles(scene);
    std::vector<bvh::Triangle> tris(mesh.indices.size());
    for (size_t t = 0; t < tris.size(); ++t) {
        const glm::uvec3 i = mesh.indices[t];
        tris[t] = {mesh.positions[i.x], mesh.positions[i.y], mesh.positions[i.z]};
    }
    return tris;
}

}  // namespace

int runBvh(const std::vector<std::string>& argv) {
    const core::CliArgs args = core::parseCli(
        argv, withSceneOptions({{"--json", "--no-epo", "--help", "--spatial-splits"}, {"--split-factor", "--split-budget"}}));
    if (args.has("--help")) {
        std::fputs(kBvhHelp, stdout);
        std::fputs(kSceneOptionsHelp, stdout);
        return 0;
    }
    if (args.positional.empty()) throw core::CliError("SCENE is required");
    if (args.positional.size() > 1) throw core::CliError("more than one scene given");
    bvh::BuildOptions options;
    const double split = core::parseNumber("--split-factor", args.get("--split-factor", "0"));
    if (!(split >= 0.0 && split <= 64.0)) throw core::CliError("--split-factor must be in [0, 64]");
    options.splitFactor = float(split);
    options.spatialSplits = args.has("--spatial-splits");
    if (args.get("--split-budget") && !options.spatialSplits) throw core::CliError("--split-budget needs --spatial-splits");
    const double budget = core::parseNumber("--split-budget", args.get("--split-budget", "2"));
    if (!(budget >= 1.0 && budget <= 16.0)) throw core::CliError("--split-budget must be in [1, 16]");
    options.splitBudget = float(budget);
    const std::filesystem::path path = args.positional[0];

    Progress progress;
    progress.step("loading " + path.filename().string());
    std::string kind;
    const std::vector<bvh::Triangle> triangles = loadTriangles(path, loadOptionsFromCli(args), kind);
    progress.step("building the BVH over " + std::to_string(triangles.size()) + " triangles");
    const bvh::Blas blas = bvh::buildBlas(triangles, options);
    double epo = 0.0, epoMs = 0.0;
    const bool withEpo = !args.has("--no-epo");
    if (withEpo) {
        progress.step("computing EPO");
        const auto start = std::chrono::steady_clock::now();
        epo = bvh::computeEpo(blas, triangles);
        epoMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    }
    progress.step("");
    const bvh::BuildStats& s = blas.stats;
    const uint32_t threads = std::max(1u, std::thread::hardware_concurrency());

    if (args.has("--json")) {
        nlohmann::json j;
        j["scene"] = path.string();
        j["kind"] = kind;
        j["splitFactor"] = options.splitFactor;
        j["spatialSplits"] = options.spatialSplits;
        j["splitBudget"] = options.spatialSplits ? nlohmann::json(options.splitBudget) : nlohmann::json(nullptr);
        j["spatialSplitNodes"] = s.spatialSplits;
        j["maxLeafSize"] = options.maxLeafSize;
        j["triangles"] = s.triangleCount;
        j["skippedTriangles"] = s.skippedTriangles;
        j["fragments"] = s.fragmentCount;
        j["references"] = s.referenceCount;
        j["nodes"] = s.nodeCount;
        j["leaves"] = s.leafCount;
        j["sah"] = s.sah;
        j["epo"] = withEpo ? nlohmann::json(epo) : nlohmann::json(nullptr);
        j["maxDepth"] = s.maxDepth;
        j["requiredStackSize"] = s.requiredStackSize;
        j["buildMs"] = s.buildMs;
        j["presplitMs"] = s.presplitMs;
        j["epoMs"] = withEpo ? nlohmann::json(epoMs) : nlohmann::json(nullptr);
        j["threads"] = threads;
        std::cout << j.dump(2) << "\n";
        return 0;
    }
    std::printf("scene:          %s (%s)\n", path.string().c_str(), kind.c_str());
    std::printf("triangles:      %u", s.triangleCount);
    if (s.skippedTriangles) std::printf(" (%u with non-finite vertices skipped)", s.skippedTriangles);
    std::printf("\nsplit factor:   %g\n", double(options.splitFactor));
    if (options.spatialSplits) {
        std::printf("spatial splits: %u nodes (reference budget %gx)\n", s.spatialSplits, double(options.splitBudget));
    }
    std::printf("fragments:      %u (after pre-splitting)\n", s.fragmentCount);
    std::printf("references:     %u (triangle references in the leaves, de-duplicated)\n", s.referenceCount);
    std::printf("nodes:          %u\n", s.nodeCount);
    std::printf("leaves:         %u (at most %u triangles each)\n", s.leafCount, options.maxLeafSize);
    std::printf("SAH:            %.3f (traversal cost 1, triangle cost %.1f)\n", double(s.sah), double(options.triangleCost));
    if (withEpo) {
        std::printf("EPO:            %.3f (%.0f ms)\n", epo, epoMs);
    } else {
        std::printf("EPO:            - (--no-epo)\n");
    }
    std::printf("max depth:      %u\n", s.maxDepth);
    std::printf("stack:          %u entries (GPU traversal)\n", s.requiredStackSize);
    std::printf("build:          %.2f ms (pre-splitting %.2f ms), %u threads\n", s.buildMs, s.presplitMs, threads);
    return 0;
}

}  // namespace idk::app
