// wide8_traverse.cpp: the ordered walk of the 8-wide compressed BVH on the CPU, the same steps as
// include/bvh_traverse_wide.glsl (its oracle in tests): per node, the robust slab test on every used slot's decoded
// box, hit slots sorted nearest first (equal distances keep slot order), all but the nearest pushed with their
// entry distance, entries popped beyond the current hit skipped; leaves are intersected when they are reached.
#include "bvh/wide8.hpp"

#include "bvh/intersect.hpp"

#include <cmath>
#include <vector>

namespace idk::bvh {
namespace {

struct Entry {
    uint32_t first;  // inner: wide node index; leaf: first triangle reference
    uint32_t count;  // 0: inner
    float tNear;
};

bool closer(float t, uint32_t triangleId, const Hit& best) {
    if (t != best.t) return t < best.t;
    return triangleId < best.triangleId;
}

float boxLimit(float bestT) { return bestT + std::abs(bestT) * 0x1p-20f; }  // walk.hpp boxLimit

// Returns true when anyHit is set and a hit was found; sets *overflowed when a push found the stack full.
bool walk(const Bvh8& bvh, std::span<const glm::vec3> positions, const PreparedRay& r, bool anyHit, uint32_t stackSize,
          Hit& best, bool& overflowed) {
    if (!r.valid || bvh.nodes.empty()) return false;
    std::vector<Entry> stack;
    stack.reserve(stackSize);
    Entry current{0, 0, r.tMin};
    for (;;) {
        if (current.count > 0) {
            for (uint32_t k = current.first; k < current.first + current.count; ++k) {
                const gpu::GpuBlasTriangle& ref = bvh.triangles[k];
                const Triangle tri{positions[ref.vertexIndices.x], positions[ref.vertexIndices.y],
                                   positions[ref.vertexIndices.z]};
                TriangleHit h;
                if (!intersectTriangle(r, tri, h) || !(h.t < r.tMax)) continue;
                if (!closer(h.t, ref.triangleId, best)) continue;
                best = {ref.triangleId, kInvalidIndex, h.t, h.u, h.v};
                if (anyHit) return true;
            }
        } else {
            const gpu::GpuWideNode& node = bvh.nodes[current.first];
            const float limit = boxLimit(best.t);
            Entry hits[gpu::kWideArity];
            uint32_t hitCount = 0, inner = 0, triangle = node.triangleBase;
            for (uint32_t i = 0; i < gpu::kWideArity; ++i) {
                const bool isInner = wideSlotInner(node, i);
                const uint32_t count = wideSlotCount(node, i);
                if (!isInner && count == 0) continue;
                const Entry e{isInner ? node.childBase + inner : triangle, count, 0.0f};
                inner += isInner ? 1 : 0;
                triangle += count;
                const Box box = wideSlotBox(node, i);
                float t = 0.0f;
                if (!intersectBox(r, box.min, box.max, limit, t)) continue;
                uint32_t k = hitCount++;
                while (k > 0 && hits[k - 1].tNear > t) {
                    hits[k] = hits[k - 1];
                    --k;
                }
                hits[k] = {e.first, e.count, t};
            }
            if (hitCount > 0) {
                for (uint32_t k = hitCount; k-- > 1;) {
                    if (stack.size() < stackSize) {
                        stack.push_back(hits[k]);
                    } else {
                        overflowed = true;
                    }
                }
                current = hits[0];
                continue;
            }
        }
        bool found = false;
        while (!stack.empty()) {
            const Entry e = stack.back();
            stack.pop_back();
            if (e.tNear <= boxLimit(best.t)) {
                current = e;
                found = true;
                break;
            }
        }
        if (!found) return false;
    }
}

}  // namespace

Hit closestHitWide(const Bvh8& bvh, std::span<const glm::vec3> positions, const Ray& ray, uint32_t stackSize,
                   bool* overflowed) {
    const PreparedRay prepared = prepareRay(ray);
    Hit best;
    best.t = prepared.valid ? ray.tMax : kInfinity;
    bool overflow = false;
    walk(bvh, positions, prepared, false, stackSize != 0 ? stackSize : bvh.stackSize, best, overflow);
    if (overflowed) *overflowed = overflow;
    if (!best.hit()) best = Hit{};
    return best;
}

bool anyHitWide(const Bvh8& bvh, std::span<const glm::vec3> positions, const Ray& ray) {
    const PreparedRay prepared = prepareRay(ray);
    Hit best;
    best.t = prepared.valid ? ray.tMax : kInfinity;
    bool overflow = false;
    return walk(bvh, positions, prepared, true, bvh.stackSize, best, overflow);
}

}  // namespace idk::bvh
