// wide.cpp: binary tree -> 4-wide SoA nodes (see wide.hpp), depth first so a subtree's wide nodes stay close.
#include "bvh/wide.hpp"

#include <algorithm>

namespace idk::bvh {

std::vector<WideNode> buildWideNodes(std::span<const Node> nodes) {
    std::vector<WideNode> wide;
    if (nodes.empty() || nodes[0].isLeaf()) return wide;
    wide.reserve(nodes.size() / 3 + 1);
    struct Item {
        uint32_t binary;  // an inner node of the binary tree
        uint32_t wide;    // its WideNode
    };
    std::vector<Item> stack{{0, 0}};
    wide.emplace_back();
    while (!stack.empty()) {
        const Item item = stack.back();
        stack.pop_back();
        // Slots: each child of the binary node, replaced by its own two children when it is an inner node.
        uint32_t slots[4];
        uint32_t used = 0;
        const Node& parent = nodes[item.binary];
        for (uint32_t c = parent.first; c < parent.first + 2; ++c) {
            if (nodes[c].isLeaf()) {
                slots[used++] = c;
            } else {
                slots[used++] = nodes[c].first;
                slots[used++] = nodes[c].first + 1;
            }
        }
        WideNode w;
        for (uint32_t s = 0; s < 4; ++s) {
            for (int axis = 0; axis < 3; ++axis) {
                w.bounds[axis][s] = kInfinity;
                w.bounds[3 + axis][s] = -kInfinity;
            }
            w.first[s] = 0;
            w.count[s] = 0;
        }
        // Children are pushed in reverse so the left-most slot's subtree is laid out first (depth first).
        uint32_t innerSlots[4];
        uint32_t innerCount = 0;
        for (uint32_t s = 0; s < used; ++s) {
            const Node& n = nodes[slots[s]];
            for (int axis = 0; axis < 3; ++axis) {
                w.bounds[axis][s] = n.min[axis];
                w.bounds[3 + axis][s] = n.max[axis];
            }
            if (n.isLeaf()) {
                w.first[s] = n.first;
                w.count[s] = n.count;
            } else {
                innerSlots[innerCount++] = s;
            }
        }
        for (uint32_t k = 0; k < innerCount; ++k) {
            const uint32_t s = innerSlots[k];
            w.first[s] = uint32_t(wide.size());
            wide.emplace_back();
            stack.push_back({slots[s], w.first[s]});
        }
        wide[item.wide] = w;
        // Visit the left-most inner slot next (the stack is LIFO).
        std::reverse(stack.end() - innerCount, stack.end());
    }
    return wide;
}

}  // namespace idk::bvh
