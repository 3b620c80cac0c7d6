// bvh_types.h: GPU layout of the BVHs (engine/bvh/flatten.cpp writes it, the GLSL traversal reads it), scalar
// block layout. Port of IDKEngine GpuBlasNode / GpuBlasTriangle / GpuTlasNode.
//
// BLAS node array: node 0 is the root and is never a leaf; node 1 is unused padding, so every child pair starts at
// an even index (64-byte aligned when the buffer is) and a traversal can load both children of a pair in one
// 64-byte read. The children of an inner node are (triStartOrChild, triStartOrChild + 1). Leaf <=> triCount > 0:
// it covers GpuBlasTriangle entries [triStartOrChild, triStartOrChild + triCount); the two leaves of a leaf pair
// cover adjacent ranges, left first, so one loop can test both. A mesh whose whole tree is one leaf gets a root
// whose pair is (that leaf, an empty-box copy of it); an empty mesh gets a root with an empty box (min = +inf,
// max = -inf), which the slab test of intersect.hpp always rejects, and two empty-box nodes that are never entered.
// TLAS nodes have the same shape; a leaf covers instanceCount entries of the TLAS instance-order array.
#ifndef IDK_BVH_TYPES_H
#define IDK_BVH_TYPES_H
#include "interop.h"

IDK_GPU_BEGIN

IDK_CONST(uint, kBvhRootNode, 0);
IDK_CONST(uint, kBvhRootPair, 2);  // the first child pair of every GPU BLAS/TLAS

struct GpuBlasNode {
    vec3 min;
    uint triStartOrChild;
    vec3 max;
    uint triCount;  // 0 for inner nodes
};
IDK_GPU_SIZE(GpuBlasNode, 32);

// One triangle reference of a BLAS leaf, in leaf order: the vertex indices into the mesh's (or the scene's)
// vertex buffer and the triangle's index in its mesh (reported by hits; material and attribute lookups).
struct GpuBlasTriangle {
    uvec3 vertexIndices;
    uint triangleId;
};
IDK_GPU_SIZE(GpuBlasTriangle, 16);

struct GpuTlasNode {
    vec3 min;
    uint instanceStartOrChild;
    vec3 max;
    uint instanceCount;  // 0 for inner nodes
};
IDK_GPU_SIZE(GpuTlasNode, 32);

IDK_GPU_END

#endif
