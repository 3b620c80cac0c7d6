// walk.hpp (internal): the traversal loops shared by the BLAS and TLAS walks: the binary walk (nearer child first,
// the farther one pushed with its entry distance, popped entries skipped when they start beyond the current hit) and
// the same walk over the 4-wide copy of a BLAS (wide.hpp), which the CPU BLAS traversal uses when it exists.
#pragma once

#include "bvh/box_tree.hpp"
#include "bvh/intersect.hpp"
#include "bvh/wide.hpp"

#include <immintrin.h>

#include <cmath>
#include <limits>
#include <vector>

namespace idk::bvh::detail {

// 64 entries inline; deeper (degenerate) trees spill to the heap instead of overflowing.
class TraversalStack {
public:
    struct Entry {
        uint32_t node;
        float tNear;
    };
    void push(Entry e) {
        if (size_ < kInline) {
            inline_[size_] = e;
        } else {
            spill_.push_back(e);
        }
        ++size_;
    }
    bool empty() const { return size_ == 0; }
    Entry pop() {
        --size_;
        if (size_ < kInline) return inline_[size_];
        const Entry e = spill_.back();
        spill_.pop_back();
        return e;
    }

private:
    static constexpr uint32_t kInline = 64;
    Entry inline_[kInline];
    std::vector<Entry> spill_;
    uint32_t size_ = 0;
};

// Boxes are accepted up to a hair beyond the current hit so that a triangle tying with it (same t, smaller id)
// is still reached even when a box entry distance rounds up.
inline float boxLimit(float bestT) { return bestT + std::abs(bestT) * 0x1p-20f; }

// intersectBox (intersect.hpp) on one node with SSE: the same operations in the same order per axis, so the same
// answer. Lane 3 of a node load holds first/count bits; the inverse direction's lane 3 is NaN, so that lane always
// becomes NaN and is replaced by the interval bounds like any other NaN.
class SseBoxTest {
public:
    explicit SseBoxTest(const PreparedRay& r)
        : origin_(_mm_setr_ps(r.origin.x, r.origin.y, r.origin.z, 0.0f)),
          inv_(_mm_setr_ps(r.invDirection.x, r.invDirection.y, r.invDirection.z,
                           std::numeric_limits<float>::quiet_NaN())),
          negative_(_mm_castsi128_ps(_mm_setr_epi32(std::signbit(r.invDirection.x) ? -1 : 0,
                                                    std::signbit(r.invDirection.y) ? -1 : 0,
                                                    std::signbit(r.invDirection.z) ? -1 : 0, 0))),
          tMin_(_mm_set1_ps(r.tMin)) {}

    bool operator()(const Node& node, float tLimit, float& tNear) const {
        const __m128 bmin = _mm_loadu_ps(&node.min.x);
        const __m128 bmax = _mm_loadu_ps(&node.max.x);
        const __m128 lo = _mm_or_ps(_mm_and_ps(negative_, bmax), _mm_andnot_ps(negative_, bmin));
        const __m128 hi = _mm_or_ps(_mm_and_ps(negative_, bmin), _mm_andnot_ps(negative_, bmax));
        __m128 t0 = _mm_mul_ps(_mm_sub_ps(lo, origin_), inv_);
        __m128 t1 = _mm_mul_ps(_mm_mul_ps(_mm_sub_ps(hi, origin_), inv_), _mm_set1_ps(kBoxRobustScale));
        t0 = _mm_max_ps(t0, tMin_);                // maxps/minps return the second operand for a NaN
        t1 = _mm_min_ps(t1, _mm_set1_ps(tLimit));
        t0 = _mm_max_ps(t0, _mm_shuffle_ps(t0, t0, _MM_SHUFFLE(2, 3, 0, 1)));
        t0 = _mm_max_ps(t0, _mm_shuffle_ps(t0, t0, _MM_SHUFFLE(1, 0, 3, 2)));
        t1 = _mm_min_ps(t1, _mm_shuffle_ps(t1, t1, _MM_SHUFFLE(2, 3, 0, 1)));
        t1 = _mm_min_ps(t1, _mm_shuffle_ps(t1, t1, _MM_SHUFFLE(1, 0, 3, 2)));
        tNear = _mm_cvtss_f32(t0);
        return tNear <= _mm_cvtss_f32(t1);
    }

private:
    __m128 origin_, inv_, negative_, tMin_;
};

// Walks `nodes` (root 0, pairs at first/first + 1). `leaf(node)` intersects a leaf and returns true to stop the
// walk (any hit found); `bestT()` is the current closest distance; `leafData(node)` is the address of a leaf's
// first primitive (prefetched).
template <class LeafFn, class BestFn, class LeafDataFn>
bool walkTree(const Node* nodes, const PreparedRay& ray, LeafFn&& leaf, BestFn&& bestT, LeafDataFn&& leafData) {
    const SseBoxTest boxTest(ray);
    float tNear = 0.0f;
    if (!boxTest(nodes[0], boxLimit(bestT()), tNear)) return false;
    TraversalStack stack;
    uint32_t current = 0;
    for (;;) {
        const Node& node = nodes[current];
        if (node.isLeaf()) {
            if (leaf(node)) return true;
        } else {
            const uint32_t a = node.first;
            const uint32_t b = node.first + 1;
            // The next level (an inner child's pair, a leaf child's primitives) is the latency chain of the walk:
            // start fetching it before the box tests.
            for (const Node* child : {&nodes[a], &nodes[b]}) {
                const void* next = child->isLeaf() ? leafData(*child) : static_cast<const void*>(&nodes[child->first]);
                _mm_prefetch(static_cast<const char*>(next), _MM_HINT_T0);
            }
            float tA = 0.0f, tB = 0.0f;
            const float limit = boxLimit(bestT());
            const bool hitA = boxTest(nodes[a], limit, tA);
            const bool hitB = boxTest(nodes[b], limit, tB);
            if (hitA && hitB) {
                const bool aFirst = tA <= tB;
                stack.push(aFirst ? TraversalStack::Entry{b, tB} : TraversalStack::Entry{a, tA});
                current = aFirst ? a : b;
                continue;
            }
            if (hitA || hitB) {
                current = hitA ? a : b;
                continue;
            }
        }
        bool found = false;
        while (!stack.empty()) {
            const TraversalStack::Entry e = stack.pop();
            if (e.tNear <= boxLimit(bestT())) {
                current = e.node;
                found = true;
                break;
            }
        }
        if (!found) return false;
    }
}

// Walks the 4-wide copy of a binary tree (wide.hpp). `root` is the binary root (its box is tested first, as in
// walkTree); `leaf(first, count)` intersects a leaf's triangle references and returns true to stop (any hit).
// Per wide node, one SSE pass applies intersectBox to the four slots with the same operations in the same order
// (maxps/minps keep the bound for a NaN, as the scalar comparisons do); hit slots are visited nearest first, the
// others pushed with their entry distances and skipped when popped beyond the current hit. `leafData(first)` is the
// address of a leaf's first primitive (prefetched).
template <class LeafFn, class BestFn, class LeafDataFn>
bool walkWide(const WideNode* wide, const Node& root, const PreparedRay& ray, LeafFn&& leaf, BestFn&& bestT,
              LeafDataFn&& leafData) {
    float tRoot = 0.0f;
    if (!SseBoxTest(ray)(root, boxLimit(bestT()), tRoot)) return false;
    int loRow[3], hiRow[3];
    __m128 origin[3], inv[3];
    for (int axis = 0; axis < 3; ++axis) {
        const bool negative = std::signbit(ray.invDirection[axis]);
        loRow[axis] = negative ? 3 + axis : axis;
        hiRow[axis] = negative ? axis : 3 + axis;
        origin[axis] = _mm_set1_ps(ray.origin[axis]);
        inv[axis] = _mm_set1_ps(ray.invDirection[axis]);
    }
    const __m128 tMin = _mm_set1_ps(ray.tMin);
    const __m128 scale = _mm_set1_ps(kBoxRobustScale);

    struct Entry {
        uint32_t first;
        uint32_t count;  // 0: a wide node
        float tNear;
    };
    constexpr uint32_t kInline = 96;
    Entry inlineStack[kInline];
    std::vector<Entry> spill;  // degenerate trees only
    uint32_t size = 0;
    auto push = [&](const Entry& e) {
        if (size < kInline) {
            inlineStack[size] = e;
        } else {
            spill.push_back(e);
        }
        ++size;
    };
    auto pop = [&]() -> Entry {
        --size;
        if (size < kInline) return inlineStack[size];
        const Entry e = spill.back();
        spill.pop_back();
        return e;
    };

    Entry current{0, 0, tRoot};
    for (;;) {
        if (current.count > 0) {
            if (leaf(current.first, current.count)) return true;
        } else {
            const WideNode& node = wide[current.first];
            __m128 nearT = tMin;
            __m128 farT = _mm_set1_ps(boxLimit(bestT()));
            for (int axis = 0; axis < 3; ++axis) {
                const __m128 lo = _mm_load_ps(node.bounds[loRow[axis]]);
                const __m128 hi = _mm_load_ps(node.bounds[hiRow[axis]]);
                const __m128 t0 = _mm_mul_ps(_mm_sub_ps(lo, origin[axis]), inv[axis]);
                const __m128 t1 = _mm_mul_ps(_mm_mul_ps(_mm_sub_ps(hi, origin[axis]), inv[axis]), scale);
                nearT = _mm_max_ps(t0, nearT);  // t0 > near ? t0 : near (near kept for a NaN t0)
                farT = _mm_min_ps(t1, farT);    // t1 < far ? t1 : far
            }
            uint32_t mask = uint32_t(_mm_movemask_ps(_mm_cmple_ps(nearT, farT)));
            if (mask != 0) {
                alignas(16) float tNear[4];
                _mm_store_ps(tNear, nearT);
                Entry hits[4];
                uint32_t count = 0;
                while (mask != 0) {
                    const uint32_t s = uint32_t(__builtin_ctz(mask));
                    mask &= mask - 1;
                    Entry e{node.first[s], node.count[s], tNear[s]};
                    // Every hit slot is likely visited: start fetching its node (two lines) or its first triangles.
                    const char* data = e.count > 0 ? static_cast<const char*>(leafData(e.first))
                                                   : reinterpret_cast<const char*>(&wide[e.first]);
                    _mm_prefetch(data, _MM_HINT_T0);
                    _mm_prefetch(data + 64, _MM_HINT_T0);
                    // Insertion by distance (nearest first); equal distances keep slot order.
                    uint32_t k = count++;
                    while (k > 0 && hits[k - 1].tNear > e.tNear) {
                        hits[k] = hits[k - 1];
                        --k;
                    }
                    hits[k] = e;
                }
                for (uint32_t k = count; k-- > 1;) push(hits[k]);
                current = hits[0];
                continue;
            }
        }
        bool found = false;
        while (size > 0) {
            const Entry e = pop();
            if (e.tNear <= boxLimit(bestT())) {
                current = e;
                found = true;
                break;
            }
        }
        if (!found) return false;
    }
}

}  // namespace idk::bvh::detail
