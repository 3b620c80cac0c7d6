// blas.hpp: bottom-level BVH over one mesh's triangles: optional pre-splitting, the SweepSAH build
// (box_tree.hpp), the optional stack-size optimisation, and de-duplicated triangle references in the leaves.
// Port of IDKEngine Bvh/BLAS.cs + GetUnindexedTriangles. Deviations: leaves reference original triangle ids and
// the BLAS keeps a leaf-ordered copy of the triangles for the CPU traversal (the GPU re-orders vertex indices,
// flatten.hpp); the build is deterministic for any thread count.
#pragma once

#include "bvh/box_tree.hpp"
#include "bvh/geometry.hpp"
#include "bvh/wide.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace idk::bvh {

struct BuildOptions {
    float splitFactor = 0.0f;        // pre-splitting: up to this fraction of extra fragments (0 = off; IDKEngine 0.3)
    // Spatial splits (SBVH, sbvh.hpp) instead of the SweepSAH box tree: at most splitBudget references per fragment.
    bool spatialSplits = false;
    float splitBudget = 2.0f;    // as the room the benchmark gives Embree-high's spatial splits
    uint32_t maxLeafSize = 8;        // readme results: "I forced a maximum primitive count of 8 per leaf"
    float triangleCost = kTriangleCost;
    uint32_t threadCount = 0;        // 0: hardware concurrency
    uint32_t parallelThreshold = 8192;
    // Stack-size optimisation (IDKEngine OptimizeStackSize, off by default as in the readme's tables): while the
    // required traversal stack is >= stackSizeThreshold, collapse the deepest leaf pairs into their parent as long
    // as the SAH rises by at most stackSahBudget (relative). Collapsed leaves may exceed maxLeafSize.
    bool optimizeStackSize = false;
    uint32_t stackSizeThreshold = 16;
    float stackSahBudget = 0.0009745f;
};

struct BuildStats {
    uint32_t triangleCount = 0;      // input triangles
    uint32_t skippedTriangles = 0;   // triangles with a non-finite coordinate (never referenced, never hit)
    uint32_t fragmentCount = 0;      // boxes given to the builder (= finite triangles without pre-splitting)
    uint32_t referenceCount = 0;     // triangle references in the leaves after de-duplication
    uint32_t nodeCount = 0;
    uint32_t leafCount = 0;
    uint32_t maxDepth = 0;           // root = depth 0
    uint32_t requiredStackSize = 0;  // see requiredStackSize() in metrics.hpp
    uint32_t collapsedPairs = 0;     // by the stack-size optimisation
    uint32_t spatialSplits = 0;      // nodes split by a spatial split (spatialSplits option)
    float sah = 0.0f;                // computeSah() of the final nodes
    double presplitMs = 0.0;
    double buildMs = 0.0;            // whole buildBlas, pre-splitting included
};

// Node 0 is the root (it is a leaf only when the mesh is tiny). Leaf ranges index triIds; they follow depth-first
// order, so a subtree covers one contiguous range and the two leaves of a leaf pair are adjacent (left first).
// No id repeats inside one leaf. An empty mesh gives no nodes.
struct Blas {
    std::vector<Node> nodes;
    std::vector<uint32_t> triIds;          // original triangle id of each leaf reference
    std::vector<Triangle> leafTriangles;   // the triangle of each reference (leaf order: traversal reads them
                                           // contiguously instead of gathering from the mesh)
    std::vector<WideNode> wideNodes;       // 4-wide copy of `nodes` for the CPU traversal (wide.hpp), made by
                                           // buildBlas and refitBlas; code that edits `nodes` by hand must call
                                           // updateWideNodes() or clear it (empty: the binary walk is used)
    uint32_t triangleCount = 0;            // size of the triangle array the BLAS was built from
    BuildStats stats;

    Box bounds() const { return nodes.empty() ? Box{} : nodes[0].box(); }
};

Blas buildBlas(std::span<const Triangle> triangles, const BuildOptions& options = {});

// Rebuilds blas.wideNodes from blas.nodes.
void updateWideNodes(Blas& blas);

// The stack-size optimisation on a box tree (exposed for tests): returns the number of leaf pairs collapsed.
uint32_t optimizeStackSize(BoxTree& tree, const BuildOptions& options);

}  // namespace idk::bvh
