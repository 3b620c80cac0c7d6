// wide8.cpp: collapse of a flattened binary BLAS into 8-wide nodes and the quantisation of their child boxes
// (layout and decoding rule: shaders_glsl/shared/bvh_wide_types.h).
#include "bvh/wide8.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <stdexcept>
#include <string>

namespace idk::bvh {
namespace {

bool emptyBox(const gpu::GpuBlasNode& n) { return !(n.min.x <= n.max.x && n.min.y <= n.max.y && n.min.z <= n.max.z); }

float halfArea(const gpu::GpuBlasNode& n) { return Box{n.min, n.max}.halfArea(); }

uint32_t byteOf(uint32_t word, uint32_t i) { return (word >> (8u * i)) & 0xFFu; }
void setByte(uint32_t& word, uint32_t i, uint32_t value) { word = (word & ~(0xFFu << (8u * i))) | (value << (8u * i)); }

float scaleOf(uint32_t biased) { return std::bit_cast<float>(biased << 23); }
// The shader's decode: the product is exact (8-bit integer times a power of two), one rounded addition.
float decode(float origin, uint32_t q, float scale) { return origin + float(q) * scale; }

// Biased exponent (1..254, a normal power of two) of the smallest scale whose 255 steps from `lo` reach `hi`.
uint32_t pickExponent(float lo, float hi) {
    const double extent = double(hi) - double(lo);
    int e = -126;
    if (extent > 0.0) e = std::clamp(int(std::ceil(std::log2(extent / 255.0))), -126, 127);
    while (e < 127 && decode(lo, 255, std::ldexp(1.0f, e)) < hi) ++e;
    return uint32_t(e + 127);
}

// The largest q whose decoded value is <= value, and the smallest whose decoded value is >= value. decode(0) = lo
// and decode(255) >= hi bound every child, so both exist.
uint32_t quantizeDown(float origin, float scale, float value) {
    const double guess = std::floor((double(value) - double(origin)) / double(scale));
    uint32_t q = uint32_t(std::clamp(guess, 0.0, 255.0));
    while (q > 0 && decode(origin, q, scale) > value) --q;
    while (q < 255 && decode(origin, q + 1, scale) <= value) ++q;
    return q;
}
uint32_t quantizeUp(float origin, float scale, float value) {
    const double guess = std::ceil((double(value) - double(origin)) / double(scale));
    uint32_t q = uint32_t(std::clamp(guess, 0.0, 255.0));
    while (q < 255 && decode(origin, q, scale) < value) ++q;
    while (q > 0 && decode(origin, q - 1, scale) >= value) --q;
    return q;
}

// Binary nodes that become the slots of the wide node made from binary inner node `index`.
std::vector<uint32_t> collapse(std::span<const gpu::GpuBlasNode> nodes, uint32_t index) {
    std::vector<uint32_t> slots;
    auto addChildren = [&](uint32_t parent, size_t at) {
        const uint32_t first = nodes[parent].triStartOrChild;
        if (size_t(first) + 1 >= nodes.size()) throw std::invalid_argument("buildBvh8: child index past the node array");
        std::vector<uint32_t> kids;
        for (uint32_t c : {first, first + 1}) {
            if (!emptyBox(nodes[c])) kids.push_back(c);  // never entered by the binary walk either
        }
        slots.insert(slots.begin() + std::ptrdiff_t(at), kids.begin(), kids.end());
    };
    addChildren(index, 0);
    while (slots.size() < gpu::kWideArity) {
        size_t best = slots.size();
        for (size_t s = 0; s < slots.size(); ++s) {
            if (nodes[slots[s]].triCount == 0 && (best == slots.size() || halfArea(nodes[slots[s]]) > halfArea(nodes[slots[best]]))) best = s;
        }
        if (best == slots.size()) break;  // only leaves
        const uint32_t opened = slots[best];
        slots.erase(slots.begin() + std::ptrdiff_t(best));
        addChildren(opened, best);  // in place: slots keep the binary depth-first order
    }
    return slots;
}

// Origin, exponents and quantised boxes of a wide node whose slots stand for binary nodes `slots` (in order).
void quantize(gpu::GpuWideNode& wn, std::span<const gpu::GpuBlasNode> nodes, std::span<const uint32_t> slots) {
    Box bounds;
    for (uint32_t s : slots) bounds.grow(Box{nodes[s].min, nodes[s].max});
    if (slots.empty()) bounds = Box{glm::vec3(0.0f), glm::vec3(0.0f)};
    wn.origin = bounds.min;
    for (uint32_t a = 0; a < 3; ++a) setByte(wn.exponents, a, pickExponent(bounds.min[int(a)], bounds.max[int(a)]));
    for (uint32_t i = 0; i < gpu::kWideArity; ++i) {
        for (uint32_t a = 0; a < 3; ++a) {
            const float scale = scaleOf(byteOf(wn.exponents, a));
            const bool used = i < slots.size();
            setByte(wn.qmin[2 * a + i / 4], i % 4, used ? quantizeDown(wn.origin[int(a)], scale, nodes[slots[i]].min[int(a)]) : 0);
            setByte(wn.qmax[2 * a + i / 4], i % 4, used ? quantizeUp(wn.origin[int(a)], scale, nodes[slots[i]].max[int(a)]) : 0);
        }
    }
}

}  // namespace

bool wideSlotInner(const gpu::GpuWideNode& node, uint32_t slot) { return ((node.exponents >> (24u + slot)) & 1u) != 0; }
uint32_t wideSlotCount(const gpu::GpuWideNode& node, uint32_t slot) { return byteOf(node.counts[slot / 4], slot % 4); }

Box wideSlotBox(const gpu::GpuWideNode& node, uint32_t slot) {
    Box box;
    for (uint32_t a = 0; a < 3; ++a) {
        const float scale = scaleOf(byteOf(node.exponents, a));
        box.min[int(a)] = decode(node.origin[int(a)], byteOf(node.qmin[2 * a + slot / 4], slot % 4), scale);
        box.max[int(a)] = decode(node.origin[int(a)], byteOf(node.qmax[2 * a + slot / 4], slot % 4), scale);
    }
    return box;
}

Bvh8 buildBvh8(std::span<const gpu::GpuBlasNode> nodes, std::span<const gpu::GpuBlasTriangle> triangles) {
    if (nodes.size() < 4 || nodes[gpu::kBvhRootNode].triCount != 0) {
        throw std::invalid_argument("buildBvh8: not a flattened BLAS (needs >= 4 nodes and an inner root)");
    }
    Bvh8 out;
    out.nodes.resize(1);
    // Work items: (binary inner node, its wide node, wide depth); the per-node stack need is computed bottom-up.
    struct Item {
        uint32_t binary, wide, depth;
    };
    std::vector<Item> work{{gpu::kBvhRootNode, 0, 1}};
    std::vector<uint32_t> usedSlots;  // per wide node, for the stack bound
    for (size_t w = 0; w < work.size(); ++w) {
        const Item item = work[w];
        const std::vector<uint32_t> slots = collapse(nodes, item.binary);
        gpu::GpuWideNode wn{};
        quantize(wn, nodes, slots);
        wn.childBase = uint32_t(out.nodes.size());
        wn.triangleBase = uint32_t(out.triangles.size());
        uint32_t inner = 0;
        for (uint32_t i = 0; i < slots.size(); ++i) {
            const gpu::GpuBlasNode& child = nodes[slots[i]];
            if (child.triCount == 0) {
                wn.exponents |= 1u << (24u + i);
                work.push_back({slots[i], wn.childBase + inner++, item.depth + 1});
                continue;
            }
            if (child.triCount > 255) {
                throw std::invalid_argument("buildBvh8: a leaf of " + std::to_string(child.triCount) +
                                            " triangle references (the wide node's count is 8 bits)");
            }
            if (size_t(child.triStartOrChild) + child.triCount > triangles.size()) {
                throw std::invalid_argument("buildBvh8: leaf range past the triangle array");
            }
            setByte(wn.counts[i / 4], i % 4, child.triCount);
            out.triangles.insert(out.triangles.end(), triangles.begin() + child.triStartOrChild,
                                 triangles.begin() + child.triStartOrChild + child.triCount);
        }
        out.nodes[item.wide] = wn;
        out.slotSources.emplace_back();
        out.slotSources.back().fill(kInvalidIndex);
        std::copy(slots.begin(), slots.end(), out.slotSources.back().begin());
        out.nodes.resize(out.nodes.size() + inner);
        usedSlots.push_back(uint32_t(slots.size()));
        out.depth = std::max(out.depth, item.depth);
    }
    // Stack bound: a node pushes all its hit slots but the nearest (<= used - 1) and then walks one child at a
    // time with those below it, so need(node) = (used - 1) + max need(inner child); leaves push nothing. Children
    // have larger indices than their parent: one reverse pass.
    std::vector<uint32_t> need(out.nodes.size(), 0);
    for (size_t w = out.nodes.size(); w-- > 0;) {
        const gpu::GpuWideNode& wn = out.nodes[w];
        uint32_t deepest = 0, inner = 0;
        for (uint32_t i = 0; i < gpu::kWideArity; ++i) {
            if (wideSlotInner(wn, i)) deepest = std::max(deepest, need[wn.childBase + inner++]);
        }
        need[w] = (usedSlots[w] > 0 ? usedSlots[w] - 1 : 0) + deepest;
    }
    out.stackSize = need[0];
    return out;
}

void refitBvh8(Bvh8& bvh, std::span<const gpu::GpuBlasNode> nodes) {
    for (size_t w = 0; w < bvh.nodes.size(); ++w) {
        uint32_t used = 0;
        while (used < gpu::kWideArity && bvh.slotSources[w][used] != kInvalidIndex) {
            if (bvh.slotSources[w][used] >= nodes.size()) throw std::invalid_argument("refitBvh8: fewer binary nodes than at conversion");
            ++used;
        }
        const uint32_t mask = bvh.nodes[w].exponents & 0xFF000000u;
        bvh.nodes[w].exponents = 0;
        quantize(bvh.nodes[w], nodes, std::span(bvh.slotSources[w]).first(used));
        bvh.nodes[w].exponents |= mask;
    }
}

}  // namespace idk::bvh
