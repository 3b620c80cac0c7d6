// bvh_trace_support.hpp: what the BVH traversal conformance checks (bvh_checks.cpp, `idk conformance`) and the
// asset-based BVH tests (tests/conformance/bvh/) share: a BLAS built on the CPU and uploaded, ray sets
// (camera-like, random, segments, rays aimed at vertices and edges, axis-parallel with invalid rays), a ray/hit
// buffer pair that traces a batch on the device, and the comparison with the CPU traversal (engine/bvh/traverse.hpp)
// under the stated rule: same hit/miss, same triangle and instance, t within 1e-5 relative; different ids only as
// an exact tie (t equal within 1e-6 relative). Moved here from the tests so both run one comparison.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "bvh/blas.hpp"
#include "bvh/flatten.hpp"
#include "bvh/metrics.hpp"
#include "bvh/procedural.hpp"
#include "bvh/traverse.hpp"
#include "render/bvh_gpu.hpp"
#include "vk/context.hpp"
#include "vk/transfer.hpp"

namespace idk::conformance {

inline render::TriangleMesh fromIndexed(const bvh::IndexedMesh& m) { return {m.positions, m.indices}; }

inline std::vector<bvh::Triangle> trianglesOf(const render::TriangleMesh& mesh) {
    std::vector<bvh::Triangle> out(mesh.indices.size());
    for (size_t t = 0; t < out.size(); ++t) {
        const glm::uvec3 i = mesh.indices[t];
        out[t] = {mesh.positions[i.x], mesh.positions[i.y], mesh.positions[i.z]};
    }
    return out;
}

inline bvh::Box boundsOf(const std::vector<bvh::Triangle>& tris) {
    bvh::Box b;
    for (const bvh::Triangle& t : tris) b.grow(t.box());
    return b;
}

// A BLAS built on the CPU (SweepSAH, optional pre-splitting) and uploaded.
struct UploadedBlas {
    render::TriangleMesh mesh;
    std::vector<bvh::Triangle> triangles;
    bvh::Blas blas;
    std::unique_ptr<render::GpuBlas> gpu;

    UploadedBlas(vk::Context& ctx, render::TriangleMesh m, const bvh::BuildOptions& options, const std::string& name)
        : mesh(std::move(m)), triangles(trianglesOf(mesh)), blas(bvh::buildBlas(triangles, options)) {
        const std::vector<gpu::GpuBlasNode> nodes = bvh::flatten(blas);
        const std::vector<gpu::GpuBlasTriangle> refs = bvh::flattenTriangles(blas, mesh.indices);
        gpu = std::make_unique<render::GpuBlas>(
            ctx, render::BlasData{nodes, refs, mesh.positions, bvh::requiredStackSize(blas.nodes)}, name);
    }
};

inline glm::vec3 randomUnitVector(std::mt19937& rng) {
    std::normal_distribution<float> n(0.0f, 1.0f);
    for (;;) {
        const glm::vec3 v(n(rng), n(rng), n(rng));
        const float l = glm::length(v);
        if (l > 1e-6f) return v / l;
    }
}

// A pinhole camera at `eye` looking at `target`, width x height rays (~52 degree field of view).
inline std::vector<bvh::Ray> cameraRays(glm::vec3 eye, glm::vec3 target, uint32_t width, uint32_t height) {
    const glm::vec3 forward = glm::normalize(target - eye);
    const glm::vec3 right = glm::normalize(glm::cross(forward, std::abs(forward.y) > 0.99f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0)));
    const glm::vec3 up = glm::cross(right, forward);
    const float tanHalf = std::tan(0.5f * 0.9f);
    std::vector<bvh::Ray> rays;
    rays.reserve(size_t(width) * height);
    for (uint32_t y = 0; y < height; ++y) {
        for (uint32_t x = 0; x < width; ++x) {
            const float sx = (2.0f * (float(x) + 0.5f) / float(width) - 1.0f) * tanHalf;
            const float sy = (2.0f * (float(y) + 0.5f) / float(height) - 1.0f) * tanHalf;
            rays.push_back({eye, glm::normalize(forward + sx * right + sy * up)});
        }
    }
    return rays;
}

// The same camera outside the box, looking at its centre from direction `from`.
inline std::vector<bvh::Ray> outsideCameraRays(const bvh::Box& box, glm::vec3 from, uint32_t width, uint32_t height) {
    const glm::vec3 center = 0.5f * (box.min + box.max);
    const float radius = 0.5f * glm::length(box.extent());
    return cameraRays(center + 2.2f * radius * glm::normalize(from), center, width, height);
}

template <class T>
void append(std::vector<T>& to, const std::vector<T>& from) {
    to.insert(to.end(), from.begin(), from.end());
}

// Half from inside the grown box in random directions, half from a sphere around it aimed at a random inner point.
inline std::vector<bvh::Ray> randomRays(const bvh::Box& box, uint32_t count, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const glm::vec3 center = 0.5f * (box.min + box.max);
    const float radius = glm::length(box.extent());
    std::vector<bvh::Ray> rays(count);
    for (uint32_t i = 0; i < count; ++i) {
        const glm::vec3 inside = box.min + box.extent() * glm::vec3(u(rng), u(rng), u(rng));
        if (i % 2 == 0) {
            rays[i] = {center + 1.5f * (inside - center), randomUnitVector(rng)};
        } else {
            const glm::vec3 origin = center + radius * randomUnitVector(rng);
            rays[i] = {origin, glm::normalize(inside - origin)};
        }
    }
    return rays;
}

// Shadow-ray-like segments between two random points of the box: direction = b - a, interval (1e-4, 1).
inline std::vector<bvh::Ray> segmentRays(const bvh::Box& box, uint32_t count, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::vector<bvh::Ray> rays(count);
    for (uint32_t i = 0; i < count; ++i) {
        const glm::vec3 a = box.min + box.extent() * glm::vec3(u(rng), u(rng), u(rng));
        const glm::vec3 b = box.min + box.extent() * glm::vec3(u(rng), u(rng), u(rng));
        rays[i] = {a, b - a, 1e-4f, 1.0f};
    }
    return rays;
}

// Rays from random outside points aimed exactly at mesh vertices and edge midpoints (the watertightness cases).
inline std::vector<bvh::Ray> vertexEdgeRays(const std::vector<bvh::Triangle>& tris, const bvh::Box& box,
                                            uint32_t count, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_int_distribution<size_t> pick(0, tris.size() - 1);
    const glm::vec3 center = 0.5f * (box.min + box.max);
    const float radius = glm::length(box.extent());
    std::vector<bvh::Ray> rays(count);
    for (uint32_t i = 0; i < count; ++i) {
        const bvh::Triangle& t = tris[pick(rng)];
        const glm::vec3 target = i % 2 == 0 ? (i % 4 == 0 ? t.v0 : t.v1) : 0.5f * (t.v1 + t.v2);
        const glm::vec3 origin = center + radius * randomUnitVector(rng);
        rays[i] = {origin, target - origin};  // not normalised: t = 1 at the target
    }
    return rays;
}

// Axis-parallel rays (zero and negative-zero direction components) from a grid of points, origins snapped to the
// integer grid so that many start exactly on the planes of axis-aligned boxes; plus invalid rays.
inline std::vector<bvh::Ray> axisRays(const bvh::Box& box, uint32_t count, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::vector<bvh::Ray> rays(count);
    const float nan = std::nanf("");
    for (uint32_t i = 0; i < count; ++i) {
        glm::vec3 o = glm::floor(box.min + box.extent() * glm::vec3(u(rng), u(rng), u(rng)));
        glm::vec3 d(0.0f);
        const int axis = int(i % 3);
        d[axis] = (i / 3) % 2 == 0 ? 1.0f : -1.0f;
        for (int k = 0; k < 3; ++k) {
            if (k != axis && (i / 6) % 2 == 1) d[k] = -0.0f;
        }
        rays[i] = {o, d};
        if (i % 97 == 5) rays[i].direction = glm::vec3(0.0f);          // zero direction: hits nothing
        if (i % 97 == 7) rays[i].direction.x = nan;                     // NaN: hits nothing
        if (i % 97 == 9) rays[i].tMin = rays[i].tMax = 1.0f;            // empty interval
    }
    return rays;
}

inline gpu::GpuBvhRay toGpu(const bvh::Ray& r) { return {r.origin, r.tMin, r.direction, r.tMax}; }

// Device buffers for up to `capacity` rays and hits; trace() uploads, dispatches, waits and downloads.
class RayBatch {
public:
    RayBatch(vk::Context& ctx, vk::ShaderLibrary& shaders, uint32_t capacity) : ctx_(ctx), shaders_(shaders), capacity_(capacity) {
        rays_ = ctx.createBuffer({VkDeviceSize(capacity) * sizeof(gpu::GpuBvhRay), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                  vk::MemoryUsage::GpuOnly, "test rays", "test"});
        hits_ = ctx.createBuffer({VkDeviceSize(capacity) * sizeof(gpu::GpuBvhHit), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                  vk::MemoryUsage::GpuOnly, "test hits", "test"});
    }
    ~RayBatch() {
        ctx_.destroyDeferred(rays_);
        ctx_.destroyDeferred(hits_);
    }
    RayBatch(const RayBatch&) = delete;
    RayBatch& operator=(const RayBatch&) = delete;

    using Recorder = std::function<void(VkCommandBuffer, VkDeviceAddress rays, VkDeviceAddress hits, uint32_t count)>;

    std::vector<gpu::GpuBvhHit> trace(const std::vector<bvh::Ray>& rays, const Recorder& record) {
        std::vector<gpu::GpuBvhHit> out;
        out.reserve(rays.size());
        for (size_t start = 0; start < rays.size(); start += capacity_) {
            const uint32_t n = uint32_t(std::min<size_t>(capacity_, rays.size() - start));
            std::vector<gpu::GpuBvhRay> batch(n);
            for (uint32_t i = 0; i < n; ++i) batch[i] = toGpu(rays[start + i]);
            vk::uploadBuffer(ctx_, rays_, std::span<const gpu::GpuBvhRay>(batch));
            ctx_.runImmediate([&](VkCommandBuffer cmd) { record(cmd, rays_.address, hits_.address, n); });
            const std::vector<gpu::GpuBvhHit> hits = vk::downloadBuffer<gpu::GpuBvhHit>(ctx_, hits_, n);
            out.insert(out.end(), hits.begin(), hits.end());
        }
        return out;
    }

    std::vector<gpu::GpuBvhHit> trace(const render::GpuBlas& blas, render::TraceMode mode,
                                      const std::vector<bvh::Ray>& rays, uint32_t stackSize = 0) {
        return trace(rays, [&](VkCommandBuffer cmd, VkDeviceAddress r, VkDeviceAddress h, uint32_t n) {
            render::recordTraceRays(cmd, {ctx_, shaders_}, blas, mode, r, h, n, stackSize);
        });
    }
    std::vector<gpu::GpuBvhHit> trace(const render::GpuTlas& tlas, render::TraceMode mode,
                                      const std::vector<bvh::Ray>& rays) {
        return trace(rays, [&](VkCommandBuffer cmd, VkDeviceAddress r, VkDeviceAddress h, uint32_t n) {
            render::recordTraceRays(cmd, {ctx_, shaders_}, tlas, mode, r, h, n);
        });
    }

private:
    vk::Context& ctx_;
    vk::ShaderLibrary& shaders_;
    uint32_t capacity_;
    vk::Buffer rays_, hits_;
};

// Runs fn(i) for i in [0, count) on all hardware threads (the CPU oracle of a batch).
inline void parallelFor(size_t count, const std::function<void(size_t)>& fn) {
    const size_t threads = std::max(1u, std::thread::hardware_concurrency());
    std::vector<std::thread> pool;
    for (size_t t = 0; t < threads; ++t) {
        pool.emplace_back([&, t] {
            for (size_t i = t; i < count; i += threads) fn(i);
        });
    }
    for (std::thread& th : pool) th.join();
}

// GPU vs CPU closest hits. Rule: same hit/miss, same triangle and instance, t within 1e-5 relative. Different ids
// are accepted only as an exact tie: both t equal within 1e-6 relative (counted).
struct Agreement {
    uint64_t rays = 0, hits = 0, anyHits = 0;
    uint64_t bitExact = 0;     // hits whose t and barycentrics are bit-identical
    uint64_t ties = 0;         // different ids at the same t (allowed)
    uint64_t mismatches = 0;   // anything else
    uint64_t anyMismatches = 0;
    uint64_t overflows = 0;
    double maxRelativeT = 0.0;  // the largest relative t difference of same-triangle hits
    std::string firstProblems;

    void add(const Agreement& o) {
        rays += o.rays, hits += o.hits, anyHits += o.anyHits, bitExact += o.bitExact, ties += o.ties, mismatches += o.mismatches;
        anyMismatches += o.anyMismatches, overflows += o.overflows, maxRelativeT = std::max(maxRelativeT, o.maxRelativeT);
        if (firstProblems.size() < 2000) firstProblems += o.firstProblems;
    }
};

inline bool relClose(float a, float b, float tol) {
    return std::abs(a - b) <= tol * std::max(std::abs(a), std::abs(b));
}

inline Agreement compareClosest(const std::vector<bvh::Ray>& rays, const std::vector<gpu::GpuBvhHit>& gpuHits,
                                const std::function<bvh::Hit(const bvh::Ray&)>& cpu) {
    std::vector<bvh::Hit> expected(rays.size());
    parallelFor(rays.size(), [&](size_t i) { expected[i] = cpu(rays[i]); });
    Agreement a;
    a.rays = rays.size();
    for (size_t i = 0; i < rays.size(); ++i) {
        const bvh::Hit& c = expected[i];
        const gpu::GpuBvhHit& g = gpuHits[i];
        const bool gpuHit = (g.flags & gpu::kBvhHitFlagHit) != 0;
        a.overflows += (g.flags & gpu::kBvhHitFlagStackOverflow) ? 1 : 0;
        bool ok = gpuHit == c.hit();
        if (ok && c.hit()) {
            ++a.hits;
            if (g.triangleId == c.triangleId && g.instanceId == c.instanceId) {
                ok = relClose(g.t, c.t, 1e-5f);
                const float scale = std::max(std::abs(g.t), std::abs(c.t));
                if (scale > 0.0f) a.maxRelativeT = std::max(a.maxRelativeT, double(std::abs(g.t - c.t) / scale));
                a.bitExact += (g.t == c.t && g.u == c.u && g.v == c.v) ? 1 : 0;
            } else if (relClose(g.t, c.t, 1e-6f)) {
                ++a.ties;
            } else {
                ok = false;
            }
        }
        if (!ok && a.mismatches++ < 5) {
            char line[256];
            std::snprintf(line, sizeof line, "  ray %zu: gpu tri %u inst %u t %.9g, cpu tri %u inst %u t %.9g\n", i,
                          g.triangleId, g.instanceId, double(g.t), c.triangleId, c.instanceId, double(c.t));
            a.firstProblems += line;
        }
    }
    return a;
}

inline Agreement compareAny(const std::vector<bvh::Ray>& rays, const std::vector<gpu::GpuBvhHit>& gpuHits,
                            const std::function<bool(const bvh::Ray&)>& cpu) {
    std::vector<char> expected(rays.size());
    parallelFor(rays.size(), [&](size_t i) { expected[i] = cpu(rays[i]) ? 1 : 0; });
    Agreement a;
    a.rays = rays.size();
    for (size_t i = 0; i < rays.size(); ++i) {
        const bool gpuHit = (gpuHits[i].flags & gpu::kBvhHitFlagHit) != 0;
        a.anyHits += expected[i];
        a.overflows += (gpuHits[i].flags & gpu::kBvhHitFlagStackOverflow) ? 1 : 0;
        if (gpuHit != bool(expected[i]) && a.anyMismatches++ < 5) {
            a.firstProblems += "  any-hit ray " + std::to_string(i) + ": gpu " + std::to_string(gpuHit) + ", cpu " +
                               std::to_string(int(expected[i])) + "\n";
        }
    }
    return a;
}

}  // namespace idk::conformance
