// gltf_load_bench.cpp: loadGltf (engine/scene/gltf_loader.hpp) of two Khronos sample assets from
// ../shared/scenes (DamagedHelmet: one textured mesh; BrainStem: many skinned primitives), wall time including
// file I/O; images stay encoded. The peer is reading the same file's bytes into memory (the I/O floor), so the
// ratio is what parsing and conversion cost on top of it.
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "bench_support.hpp"
#include "scene/gltf_loader.hpp"

namespace idk::bench {
namespace {

std::string sceneInput(const std::string& name) {
    std::error_code ec;
    auto bytes = std::filesystem::file_size(sharedScene(name), ec);
    char mib[32];
    std::snprintf(mib, sizeof mib, "%.1f", ec ? 0.0 : double(bytes) / (1 << 20));
    return name + ".glb (" + mib + " MiB)";
}

bool requireScene(benchmark::State& state, const std::string& name) {
    if (std::filesystem::exists(sharedScene(name))) return true;
    state.SkipWithError(("missing " + sharedScene(name).string()).c_str());
    for (auto _ : state) {
    }
    return false;
}

void BM_GltfLoad(benchmark::State& state, const std::string& name) {
    if (!requireScene(state, name)) return;
    std::filesystem::path path = sharedScene(name);
    size_t triangles = 0, vertices = 0;
    for (auto _ : state) {
        scene::Scene scene = scene::loadGltf(path);
        triangles = vertices = 0;
        for (const scene::Mesh& mesh : scene.meshes) {
            for (const scene::Primitive& p : mesh.primitives) {
                triangles += p.indices.size() / 3;
                vertices += p.positions.size();
            }
        }
        benchmark::DoNotOptimize(scene.meshes.data());
    }
    state.counters["triangles"] = double(triangles);
    state.counters["vertices"] = double(vertices);
    state.SetBytesProcessed(state.iterations() * int64_t(std::filesystem::file_size(path)));
    setRow(state, {"scene loading", sceneInput(name), "loadGltf: parse, validate, flatten; images kept encoded",
                   "-", "BM_FileRead/" + name, "ours", "real"});
}
BENCHMARK_CAPTURE(BM_GltfLoad, DamagedHelmet, std::string("DamagedHelmet"))
    ->UseRealTime()->MinTime(0.3)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_GltfLoad, BrainStem, std::string("BrainStem"))
    ->UseRealTime()->MinTime(0.3)->Unit(benchmark::kMillisecond);

void BM_FileRead(benchmark::State& state, const std::string& name) {
    if (!requireScene(state, name)) return;
    std::filesystem::path path = sharedScene(name);
    for (auto _ : state) {
        std::ifstream in(path, std::ios::binary);
        std::vector<char> bytes(std::filesystem::file_size(path));
        in.read(bytes.data(), std::streamsize(bytes.size()));
        benchmark::DoNotOptimize(bytes.data());
    }
    state.SetBytesProcessed(state.iterations() * int64_t(std::filesystem::file_size(path)));
    setRow(state, {"scene loading", sceneInput(name), "std::ifstream::read of the whole file (page cache warm)", "-", "",
                   "peer", "real"});
}
BENCHMARK_CAPTURE(BM_FileRead, DamagedHelmet, std::string("DamagedHelmet"))
    ->UseRealTime()->MinTime(0.2)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_FileRead, BrainStem, std::string("BrainStem"))
    ->UseRealTime()->MinTime(0.2)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace idk::bench
