// voxelize_projection.glsl: the voxelization's orthographic projection of the grid's cube along one axis (voxelize.vert,
// and the geometry shaders that pick each triangle's axis): the two other axes become the N x N framebuffer (pixel
// centres = voxel centres), the axis itself the depth 0..1, so clipping drops what lies outside the grid.
#ifndef IDK_VOXELIZE_PROJECTION_GLSL
#define IDK_VOXELIZE_PROJECTION_GLSL
#include "vxgi_types.h"

// World position -> grid coordinates, 0..1 inside the grid on every axis.
vec3 voxelGridCoords(vec3 world, vec3 gridMin, float voxelSize, uint gridSize) {
    return (world - gridMin) / (voxelSize * float(gridSize));
}

vec4 voxelProjection(vec3 world, vec3 gridMin, float voxelSize, uint gridSize, uint axis) {
    vec3 g = voxelGridCoords(world, gridMin, voxelSize, gridSize);
    vec3 s = axis == 0u ? g.yzx : (axis == 1u ? g.zxy : g.xyz);      // (u, v, depth)
    return vec4(s.xy * 2.0 - 1.0, s.z, 1.0);
}

// The z-slab a voxelization draw covers, from VoxelizePush::axis (its kVoxelSlab* bits, packed by
// passes/vxgi_voxelize.cpp recordVoxelDraws): its first grid z and its depth, in voxels.
uint voxelSlabZ(uint axisBits) { return (axisBits >> kVoxelSlabZShift) & kVoxelSlabMask; }
uint voxelSlabDepth(uint axisBits) { return (axisBits >> kVoxelSlabDepthShift) & kVoxelSlabMask; }

// Whether a triangle whose grid z (in voxels) spans [zMin, zMax] may have fragments in the slab of `slab`
// (VoxelizePush::axis, its kVoxelSlab* bits): a cull of whole triangles only, the fragment shader's slab test
// decides. (Clipping the projection to the slab instead would re-interpolate the clipped pieces' attributes and
// change the fragments' bits.) The margin of 2 voxels covers the dilation's overshoot: at most half a pixel on each
// screen axis, along which z changes by at most a voxel per voxel for a triangle of that projection.
bool voxelTriangleInSlab(float zMin, float zMax, uint slab) {
    float first = float(voxelSlabZ(slab));
    float depth = float(voxelSlabDepth(slab));
    return zMax >= first - 2.0 && zMin <= first + depth + 2.0;
}

// Dominant axis of a plane's normal: the largest |component|, the lower axis on ties (the CPU oracle's rule).
uint dominantAxis(vec3 n) {
    vec3 a = abs(n);
    if (a.x >= a.y && a.x >= a.z) return 0u;
    return a.y >= a.z ? 1u : 2u;
}

#endif
