// vxgi_depth_key.h: the voxelization's front-most rule, ONE source compiled as GLSL (include/voxelize_key.glsl) and
// as C++ (the CPU voxel oracle, engine/conformance/voxel_oracle.cpp). A voxel shows, per facing class, only its
// front-most surface: the fragments whose offset along their facing lies within kVoxelKeyTolerance of the largest
// one there. A facing class is the dominant axis of the fragment's front geometric normal and its sign (6 classes);
// the offset is the fragment's position inside its voxel along that axis, counted along the normal (0 at the
// voxel's back face, 1 at its front), quantised to kVoxelKeyBits bits. So a light panel hung under a ceiling in the
// same voxel layer (both facing down) shows the panel, not the mean of the panel and the dark ceiling it hides,
// while a corner voxel holding a floor (+y) and a wall (+x) keeps both (different classes).
// Why per class and not per voxel: the surfaces of one class all come from the same projection axis, whose voxel
// column holds at most one fragment per surface; two fragments of one class in a voxel are stacked surfaces (or a
// dilated triangle's overshoot onto its neighbour's plane), and the one in front is what a cone arriving against
// the facing meets first.
// The keys of a voxel: two R32UI words (sign + then sign -), each packing the three axes' keys in 10-bit fields
// (axis a at bits 10a..10a+9), raised field-wise by a compare-and-swap loop (include/voxelize_key.glsl).
#ifndef IDK_VXGI_DEPTH_KEY_H
#define IDK_VXGI_DEPTH_KEY_H
#include "interop.h"
#ifdef __cplusplus
#include <cmath>
#endif

IDK_GPU_BEGIN

#ifdef __cplusplus
using std::abs;
#endif

IDK_CONST(uint, kVoxelKeyBits, 10u);
IDK_CONST(uint, kVoxelKeyMax, 1023u);  // (1 << kVoxelKeyBits) - 1
// Kept: key + kVoxelKeyTolerance >= the voxel's key, i.e. within 1/64 voxel of the front-most fragment. It absorbs
// float differences between the key pass's and the accumulation pass's pipelines (each computes the offset itself)
// and a curved surface's neighbouring triangles meeting in a voxel; surfaces further apart are hidden (the Cornell
// box's panel lies 0.057 voxel under its ceiling at 64^3, 0.23 at 256^3).
IDK_CONST(uint, kVoxelKeyTolerance, 16u);

// The facing class of a front geometric normal g: its dominant axis (the lower on ties, as dominantAxis) times two,
// plus 1 where it points down that axis.
IDK_INLINE uint voxelFacingClass(vec3 g) {
    float ax = abs(g.x), ay = abs(g.y), az = abs(g.z);
    uint axis = (ax >= ay && ax >= az) ? 0u : (ay >= az ? 1u : 2u);
    return axis * 2u + (g[int(axis)] < 0.0f ? 1u : 0u);
}

// The quantised offset of a fragment at grid coordinate t (world / voxel size, from the grid's corner) along its
// class's axis, inside voxel `cell` (= floor(t)), counted along the facing: larger is further in front.
IDK_INLINE uint voxelDepthKey(float t, int cell, uint facingClass) {
    float inside = t - float(cell);  // 0..1 inside the voxel
    float scaled = inside * float(kVoxelKeyMax + 1u);
    uint q = scaled <= 0.0f ? 0u : (scaled >= float(kVoxelKeyMax) ? kVoxelKeyMax : uint(scaled));
    return (facingClass & 1u) != 0u ? kVoxelKeyMax - q : q;
}

IDK_GPU_END
#endif
