// bvh_gpu_test_util.hpp: what the asset-based GPU BVH tests add to the shared traversal support
// (engine/conformance/bvh_trace_support.hpp: uploaded BLASes, ray sets, RayBatch, the comparison with the CPU): the
// scenes from ../shared (bunny, BrainStem) and the printed report.
#pragma once
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "bvh/raw_mesh.hpp"
#include "conformance/bvh_trace_support.hpp"
#include "scene/gltf_loader.hpp"

namespace idk::test {

using namespace idk::conformance;  // the shared ray sets, RayBatch and comparisons
using TestBlas = conformance::UploadedBlas;

inline std::string sharedPath(const std::string& relative) { return std::string(IDK_SHARED_DIR) + "/" + relative; }

inline render::TriangleMesh bunnyMesh() {
    const std::vector<bvh::Triangle> tris = bvh::loadRawTriangles(sharedPath("scenes/bunny/bunny.bin"));
    render::TriangleMesh mesh;
    for (uint32_t t = 0; t < tris.size(); ++t) {
        mesh.positions.insert(mesh.positions.end(), {tris[t].v0, tris[t].v1, tris[t].v2});
        mesh.indices.push_back({3 * t, 3 * t + 1, 3 * t + 2});
    }
    return mesh;
}

inline void report(const std::string& what, const Agreement& a) {
    std::printf("[ bvh gpu ] %s: %llu rays, %llu closest hits (%llu bit-exact), %llu any hits, %llu ties, %llu "
                "mismatches, %llu any-hit mismatches, %llu overflows\n",
                what.c_str(), (unsigned long long)a.rays, (unsigned long long)a.hits, (unsigned long long)a.bitExact,
                (unsigned long long)a.anyHits,
                (unsigned long long)a.ties, (unsigned long long)a.mismatches, (unsigned long long)a.anyMismatches,
                (unsigned long long)a.overflows);
    if (!a.firstProblems.empty()) std::printf("%s", a.firstProblems.c_str());
}

}  // namespace idk::test
