// meshlet_types.h: meshlets of the scene's meshes (render/meshlets.cpp builds them with meshoptimizer) and the
// push block of the mesh-shader G-buffer (gbuffer/gbuffer_mesh.task/.mesh.glsl). Ports IDKEngine's GpuMeshlet and
// MeshletTaskCmd (MeshPath, reference 2.6) with EXT_mesh_shader instead of NV.
#ifndef IDK_MESHLET_TYPES_H
#define IDK_MESHLET_TYPES_H
#include "interop.h"
#include "deferred_types.h"

IDK_GPU_BEGIN

IDK_CONST(uint, kMeshletMaxVertices, 64);
IDK_CONST(uint, kMeshletMaxTriangles, 124);  // meshoptimizer's recommendation for 64 vertices
IDK_CONST(uint, kTaskGroupSize, 32);         // one meshlet per task invocation
IDK_CONST(uint, kMeshGroupSize, 32);         // each mesh invocation emits 2 vertices and up to 4 triangles

// One meshlet: up to 64 vertices (indices relative to the mesh's baseVertex, in MeshletData::vertices) and up to
// 124 triangles (three byte-sized local vertex indices each, packed little-endian into uint words of
// MeshletData::triangles, starting at byte triangleOffset; the GPU copy appends them to the vertices). Bounds in
// object space (sphere and cone: meshopt_computeMeshletBounds).
struct GpuMeshlet {
    vec3 center;      // bounding sphere
    float radius;
    vec3 coneApex;    // normal cone: every triangle faces away from an eye inside the cone behind the apex
    float coneCutoff; // cos of the cone's half angle plus its spread; 1: no cone (never cone-culled)
    vec3 coneAxis;
    uint vertexOffset;    // first entry of its vertex indices
    uint triangleOffset;  // first byte of its triangles
    uint vertexCount;
    uint triangleCount;
    // The axis-aligned box of its vertices (object space): the late phase's Hi-Z footprint (tighter than the
    // sphere's box, most of all for flat meshlets).
    vec3 boxCenter;
    vec3 boxExtent;
    uint pad;
};
IDK_GPU_SIZE(GpuMeshlet, 88);

// The mesh rung's indirect command (VkDrawMeshTasksIndirectCommandEXT); the culling pass writes the instance of
// each into a parallel array (the task shader reads it as a storage buffer, the draw as indirect arguments).
struct MeshTaskCommand {
    uint groupCountX;  // ceil(meshletCount / kTaskGroupSize)
    uint groupCountY;
    uint groupCountZ;
};
IDK_GPU_SIZE(MeshTaskCommand, 12);

// gbuffer_mesh.task/.mesh: the G-buffer's push block (gbuffer.frag reads that prefix) and the meshlet tables.
struct GBufferMeshPush {
    GBufferPush gbuffer;
    DeviceAddress meshlets;          // GpuMeshlet[]
    DeviceAddress meshletIndices;    // uint[]: the meshlets' vertex indices, then their packed triangle bytes (the
                                     // uploaded GpuMeshlet::triangleOffset counts bytes from the buffer's start)
    DeviceAddress meshletVisibility; // uint[]: one bit per meshlet of each draw (GpuCullDraw::meshletVisibilityWord);
                                     // kCullEarly reads it, kCullLate rewrites it; 0 in kCullFrustum
    DeviceAddress drawInstance;      // uint[]: the instance of command gl_DrawID (| kDrawnEarly, late phase)
    DeviceAddress draws;             // GpuCullDraw[] (shared/culling_types.h)
    DeviceAddress views;             // GpuCullView[]
    DeviceAddress pyramid;           // float[]: Hi-Z pyramid (phase kCullLate only)
    DeviceAddress counters;          // GpuCullCounters: the task shader adds the meshlet and triangle counts
    uint view;
    uint phase;                      // kCull*: the late phase also tests meshlets against the pyramid
};
IDK_GPU_SIZE(GBufferMeshPush, 128);

IDK_GPU_END
#endif
