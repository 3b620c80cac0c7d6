// refit.cpp: bottom-up box update. Children always follow their parent in the node array, so one reverse pass
// sees both children of a node before the node itself.
#include "bvh/refit.hpp"

#include "bvh/metrics.hpp"

#include <stdexcept>
#include <string>

namespace idk::bvh {

void refitBlas(Blas& blas, std::span<const Triangle> triangles) {
    if (triangles.size() != blas.triangleCount) {
        throw std::invalid_argument("refitBlas: " + std::to_string(triangles.size()) + " triangles given, BLAS built with " +
                                    std::to_string(blas.triangleCount));
    }
    for (size_t k = 0; k < blas.triIds.size(); ++k) blas.leafTriangles[k] = triangles[blas.triIds[k]];
    for (size_t i = blas.nodes.size(); i-- > 0;) {
        Node& node = blas.nodes[i];
        Box box;
        if (node.isLeaf()) {
            for (uint32_t k = node.first; k < node.first + node.count; ++k) box.grow(blas.leafTriangles[k].box());
        } else {
            box = blas.nodes[node.first].box();
            box.grow(blas.nodes[node.first + 1].box());
        }
        node.setBox(box);
    }
    updateWideNodes(blas);
    blas.stats.sah = computeSah(blas.nodes);
}

}  // namespace idk::bvh
