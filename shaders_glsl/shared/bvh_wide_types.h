// bvh_wide_types.h: GPU layout of the 8-wide compressed BLAS (engine/bvh/wide8.cpp writes it,
// include/bvh_traverse_wide.glsl reads it), scalar block layout. After Ylitie, Karras & Laine 2017 ("Efficient
// Incoherent Ray Traversal on GPUs Through Compressed Wide BVHs"): child boxes are quantised to 8 bits per plane
// relative to the node's box, with a power-of-two scale per axis.
//
// Node 0 is the root. Slot i of a node is used when it is inner (bit i of the inner mask) or a leaf (count > 0);
// unused slots are never tested. Inner children of a node are consecutive wide nodes from childBase in slot order;
// leaf children cover consecutive triangle references from triangleBase in slot order (a leaf's first reference is
// triangleBase + the counts of the leaf slots before it). The triangle references are a GpuBlasTriangle array of
// their own (the binary leaves' references, regrouped per wide node), read through GpuBlasDesc::triangles.
//
// Decoding slot i on axis a: lo = origin[a] + float(qmin byte) * 2^e, hi = origin[a] + float(qmax byte) * 2^e,
// 2^e = uintBitsToFloat(biased exponent << 23). The product of an 8-bit integer and a power of two is exact, so
// the decoded value is one correctly rounded addition on every device and in C++ (an FMA gives the same value),
// and the builder picks the bytes on those decoded values: the decoded box always contains the child's box.
#ifndef IDK_BVH_WIDE_TYPES_H
#define IDK_BVH_WIDE_TYPES_H
#include "interop.h"

IDK_GPU_BEGIN

IDK_CONST(uint, kWideArity, 8);

struct GpuWideNode {
    vec3 origin;      // the node's box minimum (the decode origin)
    uint exponents;   // byte a (a = 0, 1, 2): biased fp32 exponent of axis a's scale; byte 3: inner mask
    uint childBase;   // first inner child (wide node index)
    uint triangleBase;  // first triangle reference of the leaf children
    uint counts[2];   // byte i of counts[i / 4], bits 8 * (i % 4): triangle count of leaf slot i (0 otherwise)
    uint qmin[6];     // byte i of qmin[2 * axis + i / 4]: quantised minimum of slot i
    uint qmax[6];     // same for the maximum
};
IDK_GPU_SIZE(GpuWideNode, 80);

IDK_GPU_END

#endif
