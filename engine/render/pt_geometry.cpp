// pt_geometry.cpp: uploads PT-A's BLAS/TLAS and shading data for the GPU path tracer (see pt_geometry.hpp).
#include "render/pt_geometry.hpp"

#include <stdexcept>

#include "bvh/flatten.hpp"
#include "bvh/metrics.hpp"
#include "bvh/wide8.hpp"
#include "render/pt_tables.hpp"
#include "vk/context.hpp"
#include "vk/transfer.hpp"

namespace idk::render {
namespace {

template <class T>
vk::Buffer upload(vk::Context& ctx, const std::vector<T>& v, const std::string& name) {
    return uploadPtBuffer(ctx, v.data(), v.size() * sizeof(T), name);
}

// The GPU trees of `tlas` over g.placed (binary, and wide when g has wide BLASes).
void uploadTlas(vk::Context& ctx, PtGpuGeometry& g, const bvh::Tlas& tlas) {
    std::vector<gpu::GpuBvhInstance> bvhInstances;
    for (size_t i = 0; i < g.placed.size(); ++i) {
        const bvh::BlasInstance& inst = g.placed[i];
        // An instance of an empty geometry has no TLAS leaf (bvh::buildTlas) and is never visited: any valid
        // BLAS index keeps the GPU descriptor consistent.
        const int32_t blas = g.geometryBlas[inst.blasIndex];
        bvhInstances.push_back(makeGpuInstance(inst.objectToWorld, tlas.worldToObject[i], uint32_t(std::max(blas, 0))));
    }
    std::vector<const GpuBlas*> blasPointers;
    for (const auto& b : g.blases) blasPointers.push_back(b.get());
    const std::vector<gpu::GpuTlasNode> nodes = bvh::flatten(tlas);
    g.tlasStackSize = std::max(1u, bvh::requiredStackSize(tlas.nodes));
    g.tlas = std::make_unique<GpuTlas>(
        ctx, TlasData{nodes, tlas.instanceOrder, bvhInstances, blasPointers, g.tlasStackSize}, "pt tlas");
    if (!g.wideBlases.empty()) {
        std::vector<const GpuWideBlas*> widePointers;
        for (const auto& w : g.wideBlases) widePointers.push_back(w.get());
        g.wideTlas = std::make_unique<GpuWideTlas>(ctx, nodes, tlas.instanceOrder, bvhInstances, widePointers,
                                                   g.tlasStackSize, "pt wide tlas");
    }
}

}  // namespace

PtGpuGeometry uploadPtGeometry(vk::Context& ctx, const pathtrace::PathTraceScene& pts, bool wide) {
    PtGpuGeometry g;
    std::vector<gpu::GpuPtGeometry> table;
    g.geometryBlas.assign(pts.geometries.size(), -1);
    for (size_t i = 0; i < pts.geometries.size(); ++i) {
        const pathtrace::PtGeometry& geo = pts.geometries[i];
        std::vector<gpu::GpuPtVertex> vertices(geo.positions.size());
        for (size_t v = 0; v < vertices.size(); ++v) {
            vertices[v].position = geo.positions[v];
            vertices[v].normal = geo.normals[v];
            vertices[v].tangent = geo.tangents[v];
            vertices[v].uv0 = geo.uv0[v];
            vertices[v].uv1 = geo.uv1[v];
            vertices[v].color = geo.colors[v];
        }
        const std::string n = std::to_string(i);
        gpu::GpuPtGeometry entry{};
        entry.vertices = g.buffers.emplace_back(upload(ctx, vertices, "pt vertices " + n)).address;
        entry.triangles = g.buffers.emplace_back(upload(ctx, geo.triangles, "pt triangles " + n)).address;
        entry.materials = g.buffers.emplace_back(upload(ctx, geo.triangleMaterial, "pt triangle materials " + n)).address;
        table.push_back(entry);
        g.bounds.push_back(pts.blases[i].bounds());
        if (geo.triangles.empty()) continue;
        const std::vector<gpu::GpuBlasNode> nodes = bvh::flatten(pts.blases[i]);
        const std::vector<gpu::GpuBlasTriangle> refs = bvh::flattenTriangles(pts.blases[i], geo.triangles);
        const uint32_t stack = bvh::requiredStackSize(pts.blases[i].nodes);
        g.blasStackSize = std::max(g.blasStackSize, stack);
        g.geometryBlas[i] = int32_t(g.blases.size());
        g.blases.push_back(std::make_unique<GpuBlas>(ctx, BlasData{nodes, refs, geo.positions, stack}, "pt blas " + n));
        if (wide) {
            const bvh::Bvh8& w = g.wideTrees.emplace_back(bvh::buildBvh8(nodes, refs));
            g.wideStackSize = std::max(g.wideStackSize, w.stackSize);
            g.wideBlases.push_back(std::make_unique<GpuWideBlas>(ctx, w, *g.blases.back(), "pt wide blas " + n));
        }
    }
    if (g.blases.empty()) throw std::runtime_error("path tracer: the scene has no triangles to trace");
    for (size_t i = 0; i < pts.instances.size(); ++i) {
        const bvh::BlasInstance& inst = pts.instances[i];
        gpu::GpuPtTraceInstance ti{};
        for (int c = 0; c < 4; ++c) ti.objectToWorld[c] = glm::vec3(inst.objectToWorld[c]);
        for (int c = 0; c < 3; ++c) ti.normalToWorld[c] = pts.normalMatrices[i][c];
        ti.geometry = inst.blasIndex;
        ti.firstLight = i < pts.instanceLights.size() ? pts.instanceLights[i].firstLight : gpu::kPtNoLight;
        ti.flags = pts.mirrored[i] ? gpu::kPtInstanceMirrored : 0u;
        g.instances.push_back(ti);
    }
    g.placed = pts.instances;
    uploadTlas(ctx, g, pts.tlas);  // PT-A's own tree: both tracers walk the same TLAS
    g.geometryTable = upload(ctx, table, "pt geometries");
    g.instanceTable = upload(ctx, g.instances, "pt instances");
    return g;
}

void rebuildPtTlas(vk::Context& ctx, PtGpuGeometry& g) {
    // bvh::buildTlas reads only each BLAS's root box (Blas::bounds) and whether it has nodes: one-node stand-ins
    // carry the refit boxes without a CPU copy of the refit trees.
    std::vector<bvh::Blas> boxes(g.bounds.size());
    for (size_t i = 0; i < boxes.size(); ++i) {
        if (g.geometryBlas[i] < 0) continue;
        boxes[i].nodes.resize(1);
        boxes[i].nodes[0].setBox(g.bounds[i]);
    }
    const bvh::Tlas tlas = bvh::buildTlas(g.placed, boxes);
    // The trace of the previous pose may still reference the old trees' buffers: their destructors defer.
    uploadTlas(ctx, g, tlas);
}

void destroyPtGeometry(vk::Context& ctx, PtGpuGeometry& g) {
    g.wideTlas.reset();
    g.wideBlases.clear();
    g.tlas.reset();
    g.blases.clear();
    for (vk::Buffer& b : g.buffers) ctx.destroyDeferred(b);
    g.buffers.clear();
    if (g.geometryTable.buffer) ctx.destroyDeferred(g.geometryTable);
    if (g.instanceTable.buffer) ctx.destroyDeferred(g.instanceTable);
}

}  // namespace idk::render
