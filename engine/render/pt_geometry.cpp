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

}  // namespace

PtGpuGeometry uploadPtGeometry(vk::Context& ctx, const pathtrace::PathTraceScene& pts, bool wide) {
    PtGpuGeometry g;
    std::vector<gpu::GpuPtGeometry> table;
    std::vector<uint32_t> blasOf(pts.geometries.size(), 0);
    std::vector<const GpuBlas*> blasPointers;
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
        if (geo.triangles.empty()) continue;
        const std::vector<gpu::GpuBlasNode> nodes = bvh::flatten(pts.blases[i]);
        const std::vector<gpu::GpuBlasTriangle> refs = bvh::flattenTriangles(pts.blases[i], geo.triangles);
        const uint32_t stack = bvh::requiredStackSize(pts.blases[i].nodes);
        g.blasStackSize = std::max(g.blasStackSize, stack);
        blasOf[i] = uint32_t(g.blases.size());
        g.blases.push_back(std::make_unique<GpuBlas>(ctx, BlasData{nodes, refs, geo.positions, stack}, "pt blas " + n));
        blasPointers.push_back(g.blases.back().get());
        if (wide) {
            const bvh::Bvh8 w = bvh::buildBvh8(nodes, refs);
            g.wideStackSize = std::max(g.wideStackSize, w.stackSize);
            g.wideBlases.push_back(std::make_unique<GpuWideBlas>(ctx, w, *g.blases.back(), "pt wide blas " + n));
        }
    }
    if (g.blases.empty()) throw std::runtime_error("path tracer: the scene has no triangles to trace");
    std::vector<gpu::GpuBvhInstance> bvhInstances;
    for (size_t i = 0; i < pts.instances.size(); ++i) {
        const bvh::BlasInstance& inst = pts.instances[i];
        // An instance of an empty geometry has no TLAS leaf (bvh::buildTlas) and is never visited: any valid
        // BLAS index keeps the GPU descriptor consistent.
        bvhInstances.push_back(makeGpuInstance(inst.objectToWorld, pts.tlas.worldToObject[i], blasOf[inst.blasIndex]));
        gpu::GpuPtTraceInstance ti{};
        for (int c = 0; c < 4; ++c) ti.objectToWorld[c] = glm::vec3(inst.objectToWorld[c]);
        for (int c = 0; c < 3; ++c) ti.normalToWorld[c] = pts.normalMatrices[i][c];
        ti.geometry = inst.blasIndex;
        ti.firstLight = i < pts.instanceLights.size() ? pts.instanceLights[i].firstLight : gpu::kPtNoLight;
        ti.flags = pts.mirrored[i] ? gpu::kPtInstanceMirrored : 0u;
        g.instances.push_back(ti);
    }
    const std::vector<gpu::GpuTlasNode> nodes = bvh::flatten(pts.tlas);
    g.tlasStackSize = std::max(1u, bvh::requiredStackSize(pts.tlas.nodes));
    g.tlas = std::make_unique<GpuTlas>(
        ctx, TlasData{nodes, pts.tlas.instanceOrder, bvhInstances, blasPointers, g.tlasStackSize}, "pt tlas");
    if (wide) {
        std::vector<const GpuWideBlas*> widePointers;
        for (const auto& w : g.wideBlases) widePointers.push_back(w.get());
        g.wideTlas = std::make_unique<GpuWideTlas>(ctx, nodes, pts.tlas.instanceOrder, bvhInstances, widePointers,
                                                   g.tlasStackSize, "pt wide tlas");
    }
    g.geometryTable = upload(ctx, table, "pt geometries");
    g.instanceTable = upload(ctx, g.instances, "pt instances");
    return g;
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
