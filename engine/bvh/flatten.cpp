// flatten.cpp: the GPU node and triangle arrays (layout described in shaders_glsl/shared/bvh_types.h).
#include "bvh/flatten.hpp"

namespace idk::bvh {
namespace {

template <class GpuNode>
GpuNode toGpu(const Box& box, uint32_t first, uint32_t count) {
    return GpuNode{box.min, first, box.max, count};
}

template <class GpuNode>
std::vector<GpuNode> flattenNodes(const std::vector<Node>& nodes) {
    const Box empty;
    std::vector<GpuNode> out;
    if (nodes.empty()) {  // never entered: the root's empty box fails every slab test
        out.assign(4, toGpu<GpuNode>(empty, gpu::kBvhRootPair, 0));
        return out;
    }
    if (nodes[0].isLeaf()) {  // the root must be inner: pair it with an empty-box copy
        out.push_back(toGpu<GpuNode>(nodes[0].box(), gpu::kBvhRootPair, 0));
        out.push_back(toGpu<GpuNode>(empty, 0, 0));
        out.push_back(toGpu<GpuNode>(nodes[0].box(), nodes[0].first, nodes[0].count));
        out.push_back(toGpu<GpuNode>(empty, nodes[0].first, nodes[0].count));
        return out;
    }
    out.reserve(nodes.size() + 1);
    for (size_t i = 0; i < nodes.size(); ++i) {
        const Node& n = nodes[i];
        out.push_back(toGpu<GpuNode>(n.box(), n.isLeaf() ? n.first : n.first + 1, n.count));
        if (i == 0) out.push_back(toGpu<GpuNode>(empty, 0, 0));  // padding: pairs start at even indices
    }
    return out;
}

}  // namespace

std::vector<gpu::GpuBlasNode> flatten(const Blas& blas) { return flattenNodes<gpu::GpuBlasNode>(blas.nodes); }

std::vector<gpu::GpuTlasNode> flatten(const Tlas& tlas) { return flattenNodes<gpu::GpuTlasNode>(tlas.nodes); }

std::vector<gpu::GpuBlasTriangle> flattenTriangles(const Blas& blas, std::span<const glm::uvec3> indices) {
    std::vector<gpu::GpuBlasTriangle> out;
    out.reserve(blas.triIds.size());
    for (uint32_t id : blas.triIds) out.push_back({indices[id], id});
    return out;
}

}  // namespace idk::bvh
