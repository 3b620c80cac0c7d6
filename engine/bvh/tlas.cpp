// tlas.cpp: instance world boxes, the TLAS build over them, and the two-level traversal.
#include "bvh/tlas.hpp"

#include "bvh/walk.hpp"

#include <algorithm>
#include <cmath>

namespace idk::bvh {

Box transformBox(const glm::mat4& m, const Box& box) {
    if (box.isEmpty()) return {};
    Box out;
    for (int row = 0; row < 3; ++row) {
        float lo = m[3][row], hi = m[3][row];
        float magnitude = std::abs(m[3][row]);
        for (int col = 0; col < 3; ++col) {
            const float a = m[col][row] * box.min[col];
            const float b = m[col][row] * box.max[col];
            lo += std::min(a, b);
            hi += std::max(a, b);
            magnitude += std::max(std::abs(a), std::abs(b));
        }
        // Four additions and a product per term: a relative 1e-6 of the largest magnitude covers the rounding.
        const float pad = magnitude * 1e-6f;
        out.min[row] = lo - pad;
        out.max[row] = hi + pad;
    }
    return out;
}

Tlas buildTlas(std::span<const BlasInstance> instances, std::span<const Blas> blases, uint32_t threadCount) {
    Tlas tlas;
    tlas.worldToObject.resize(instances.size());
    tlas.worldBoxes.resize(instances.size());
    std::vector<Box> boxes;
    std::vector<uint32_t> ids;
    for (uint32_t i = 0; i < instances.size(); ++i) {
        const BlasInstance& inst = instances[i];
        tlas.worldToObject[i] = glm::inverse(inst.objectToWorld);
        const Blas* blas = &blases[inst.blasIndex];
        tlas.worldBoxes[i] = transformBox(inst.objectToWorld, blas->bounds());
        if (blas->nodes.empty() || tlas.worldBoxes[i].isEmpty()) continue;
        boxes.push_back(tlas.worldBoxes[i]);
        ids.push_back(i);
    }
    BoxTreeOptions options;
    options.maxLeafSize = 1;
    options.threadCount = threadCount;
    BoxTree tree = buildBoxTree(boxes, options);
    tlas.nodes = std::move(tree.nodes);
    tlas.instanceOrder.resize(ids.size());
    for (size_t k = 0; k < ids.size(); ++k) tlas.instanceOrder[k] = ids[tree.primOrder[k]];
    return tlas;
}

namespace {

Hit traceTlas(const Tlas& tlas, std::span<const BlasInstance> instances, std::span<const Blas> blases,
              const Ray& ray, bool any, bool& anyFound) {
    Hit best;
    anyFound = false;
    const PreparedRay prepared = prepareRay(ray);
    if (!prepared.valid || tlas.nodes.empty()) return best;
    best.t = ray.tMax;
    auto leaf = [&](const Node& node) {
        for (uint32_t k = node.first; k < node.first + node.count; ++k) {
            const uint32_t id = tlas.instanceOrder[k];
            const glm::mat4& toObject = tlas.worldToObject[id];
            // Affine: t is the same parameter in both spaces because the direction is not renormalised.
            Ray local = ray;
            local.origin = glm::vec3(toObject * glm::vec4(ray.origin, 1.0f));
            local.direction = glm::vec3(toObject * glm::vec4(ray.direction, 0.0f));
            if (detail::traverseBlas(blases[instances[id].blasIndex], prepareRay(local), id, any, best)) {
                anyFound = true;
                return true;
            }
        }
        return false;
    };
    detail::walkTree(tlas.nodes.data(), prepared, leaf, [&] { return best.t; }, [&](const Node& node) {
        return static_cast<const void*>(&tlas.worldToObject[tlas.instanceOrder[node.first]]);
    });
    if (!best.hit()) best = Hit{};
    return best;
}

}  // namespace

Hit closestHit(const Tlas& tlas, std::span<const BlasInstance> instances, std::span<const Blas> blases,
               const Ray& ray) {
    bool unused = false;
    return traceTlas(tlas, instances, blases, ray, false, unused);
}

bool anyHit(const Tlas& tlas, std::span<const BlasInstance> instances, std::span<const Blas> blases, const Ray& ray) {
    bool found = false;
    traceTlas(tlas, instances, blases, ray, true, found);
    return found;
}

}  // namespace idk::bvh
