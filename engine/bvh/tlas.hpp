// tlas.hpp: top-level BVH over BLAS instances: the same SweepSAH builder over the instances' world boxes (one
// instance per leaf), rebuilt whenever an instance moves, and closest/any-hit traversal that moves the ray into
// each instance's object space. Deviation from IDKEngine TLAS.cs (serial PLOC over Morton codes): reusing the
// BLAS builder gives a better SAH at the instance counts of our scenes and one code path to test.
#pragma once

#include "bvh/blas.hpp"
#include "bvh/traverse.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace idk::bvh {

struct BlasInstance {
    glm::mat4 objectToWorld{1.0f};  // affine
    uint32_t blasIndex = 0;         // into the Blas span given to buildTlas/closestHit
};

struct Tlas {
    std::vector<Node> nodes;                // leaves: instanceOrder[first .. first + count)
    std::vector<uint32_t> instanceOrder;
    std::vector<glm::mat4> worldToObject;   // per instance (same indexing as the instance span)
    std::vector<Box> worldBoxes;            // per instance
};

// World box of a transformed object box (Arvo's method), widened by a few ulps so rounding never shrinks it.
Box transformBox(const glm::mat4& objectToWorld, const Box& box);

// Instances whose BLAS is empty get no leaf. `threadCount` as in BuildOptions.
Tlas buildTlas(std::span<const BlasInstance> instances, std::span<const Blas> blases, uint32_t threadCount = 0);

// Hit::instanceId is the index into `instances`, Hit::triangleId the triangle of that instance's BLAS.
Hit closestHit(const Tlas& tlas, std::span<const BlasInstance> instances, std::span<const Blas> blases,
               const Ray& ray);
bool anyHit(const Tlas& tlas, std::span<const BlasInstance> instances, std::span<const Blas> blases, const Ray& ray);

}  // namespace idk::bvh
