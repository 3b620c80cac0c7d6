// bvh_bench_scenes.hpp: what bench/bvh_bench.cpp shares with the other BVH benchmark files (bvh_wide_bench.cpp):
// its scenes with their primary and diffuse rays, the split-0.3 BLAS they are traced against with its CPU hits
// (the reference of every GPU row), and its row labels (the BVH table of scripts/bench_report.py).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "bench_support.hpp"
#include "bvh/blas.hpp"
#include "bvh/traverse.hpp"
#include "render/bvh_gpu.hpp"

namespace idk::bench {

struct BvhBenchScene {
    const render::TriangleMesh* mesh;
    const bvh::Blas* blas;  // the traversal benchmarks' BLAS
    const std::vector<bvh::Ray>* primary;
    const std::vector<bvh::Ray>* diffuse;
    const std::vector<bvh::Hit>* primaryHits;  // bvh::closestHit on `blas`
    const std::vector<bvh::Hit>* diffuseHits;
    std::string input;      // the row's input text
    std::string blasText;   // "BLAS split 0.3"
    bool big;               // ~1M triangles: fewer repetitions
};

// Built on first use and kept for the run. Throws std::invalid_argument for an unknown name.
BvhBenchScene bvhBenchScene(const std::string& name);

// Uploads the scene's primary or diffuse rays, runs `trace` (which records one traversal of `n` rays from `rays` into
// `hits`) once to warm up (pipeline creation) and then per iteration timed by timestamp queries; sets the counters
// every GPU traversal row has (mismatches against the CPU traversal's hits: same triangle and t; rays; submit wall).
void runGpuTrace(benchmark::State& state, const BvhBenchScene& s, bool diffuse,
                 const std::function<void(VkCommandBuffer, VkDeviceAddress rays, VkDeviceAddress hits, uint32_t n)>& trace);

// The BVH table's row label: kind = build | cpu | gpu, rays = primary | diffuse.
void setBvhBenchRow(benchmark::State& state, const RowInfo& row, const std::string& kind, const std::string& rays);

}  // namespace idk::bench
