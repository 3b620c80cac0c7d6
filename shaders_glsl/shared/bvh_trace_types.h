// bvh_trace_types.h: what the GLSL BVH traversal (include/bvh_traverse.glsl) and the BVH kernels
// (shaders_glsl/bvh/) read through buffer device addresses: BLAS/TLAS descriptors, instances, rays and hits, and
// the push blocks of the trace-rays test kernel and the refit kernel (engine/render/bvh_gpu.cpp records both).
// Counterpart of IDKEngine's GpuBlasInstance / BVHIntersect.glsl HitInfo and BLASRefit/compute.glsl. Scalar layout.
#ifndef IDK_BVH_TRACE_TYPES_H
#define IDK_BVH_TRACE_TYPES_H
#include "bvh_types.h"

IDK_GPU_BEGIN

// Specialization-constant ids of trace_rays.comp.glsl.
IDK_CONST(uint, kSpecBvhStackSize, 0);      // BLAS traversal stack entries (>= bvh::requiredStackSize)
IDK_CONST(uint, kSpecBvhTlasStackSize, 1);  // TLAS traversal stack entries
IDK_CONST(uint, kSpecBvhTraceMode, 2);      // kBvhTraceClosest or kBvhTraceAny
IDK_CONST(uint, kSpecBvhUseTlas, 3);        // 0: one BLAS (TracePush::blas), 1: TLAS (TracePush::tlas)

IDK_CONST(uint, kBvhTraceClosest, 0);
IDK_CONST(uint, kBvhTraceAny, 1);
IDK_CONST(uint, kBvhInvalidIndex, 0xFFFFFFFFu);
IDK_CONST(uint, kBvhTraceGroupSize, 64);
IDK_CONST(uint, kBvhRefitGroupSize, 64);

// GpuBvhHit::flags
IDK_CONST(uint, kBvhHitFlagHit, 1);            // closest: a triangle was hit; any: some triangle was hit
IDK_CONST(uint, kBvhHitFlagStackOverflow, 2);  // a push found the stack full: the subtree was skipped (result may
                                               // miss triangles; the stack size constant is too small)

// One BLAS: its flattened nodes (bvh::flatten), leaf-ordered triangle references (bvh::flattenTriangles) and the
// vertex positions the references index. Vertex i is at positions + 4 * i * vertexStride bytes (3 floats).
struct GpuBlasDesc {
    DeviceAddress nodes;      // GpuBlasNode[]
    DeviceAddress triangles;  // GpuBlasTriangle[]
    DeviceAddress positions;  // float[]
    uint vertexStride;        // in floats (3 for packed vec3)
    uint nodeCount;
};
IDK_GPU_SIZE(GpuBlasDesc, 32);

// One BLAS instance. Columns of the affine matrices (glm column order); the ray is moved into object space with
// worldToObject exactly as bvh::closestHit(Tlas...) does: (c0 * x + c1 * y) + (c2 * z + c3 * w).
struct GpuBvhInstance {
    vec3 objectToWorld[4];
    vec3 worldToObject[4];
    uint blasIndex;  // into TlasDesc::blases
};
IDK_GPU_SIZE(GpuBvhInstance, 100);

struct GpuTlasDesc {
    DeviceAddress nodes;          // GpuTlasNode[]; leaves cover instanceOrder ranges
    DeviceAddress instanceOrder;  // uint[]: instance index of each leaf entry
    DeviceAddress instances;      // GpuBvhInstance[]
    DeviceAddress blases;         // GpuBlasDesc[]
};
IDK_GPU_SIZE(GpuTlasDesc, 32);

// A ray with the open interval (tMin, tMax), as bvh::Ray.
struct GpuBvhRay {
    vec3 origin;
    float tMin;
    vec3 direction;
    float tMax;
};
IDK_GPU_SIZE(GpuBvhRay, 32);

// Closest hit: t, triangle id (kBvhInvalidIndex on a miss) and instance id (kBvhInvalidIndex without a TLAS) as
// bvh::Hit; u, v barycentric weights of v1 and v2. Any hit: flags only (t = tMax, ids invalid).
struct GpuBvhHit {
    float t;
    uint triangleId;
    uint instanceId;
    uint flags;
    float u;
    float v;
};
IDK_GPU_SIZE(GpuBvhHit, 24);

struct BvhTracePush {
    GpuBlasDesc blas;    // kSpecBvhUseTlas = 0
    DeviceAddress tlas;  // GpuTlasDesc, kSpecBvhUseTlas = 1
    DeviceAddress rays;  // GpuBvhRay[count]
    DeviceAddress hits;  // GpuBvhHit[count]
    uint count;
    uint pad;            // keeps the C++ size (8-byte aligned) equal to the GLSL block's
};
IDK_GPU_SIZE(BvhTracePush, 64);

// refit.comp.glsl: one invocation per entry of order[levelStart, levelStart + levelCount): a leaf's box becomes the
// union of its triangles' boxes, an inner node's the union of its pair's boxes (children refit by an earlier
// dispatch: levels are recorded deepest first).
struct BvhRefitPush {
    GpuBlasDesc blas;
    DeviceAddress order;  // uint[]: node indices grouped by depth, deepest level first
    uint levelStart;
    uint levelCount;
};
IDK_GPU_SIZE(BvhRefitPush, 48);

// offset_ray_origin.comp.glsl (conformance of bvhOffsetRayOrigin): results[i] = offset(points[i], normals[i]).
struct BvhOffsetPush {
    DeviceAddress points;   // vec3[count]
    DeviceAddress normals;  // vec3[count]
    DeviceAddress results;  // vec3[count]
    uint count;
    uint pad;
};
IDK_GPU_SIZE(BvhOffsetPush, 32);

IDK_GPU_END

#endif
