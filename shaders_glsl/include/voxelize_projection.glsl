// voxelize_projection.glsl: the voxelization's orthographic projection of the grid's cube along one axis (voxelize.vert,
// and the geometry shaders that pick each triangle's axis): the two other axes become the N x N framebuffer (pixel
// centres = voxel centres), the axis itself the depth 0..1, so clipping drops what lies outside the grid.
#ifndef IDK_VOXELIZE_PROJECTION_GLSL
#define IDK_VOXELIZE_PROJECTION_GLSL

// World position -> grid coordinates, 0..1 inside the grid on every axis.
vec3 voxelGridCoords(vec3 world, vec3 gridMin, float voxelSize, uint gridSize) {
    return (world - gridMin) / (voxelSize * float(gridSize));
}

vec4 voxelProjection(vec3 world, vec3 gridMin, float voxelSize, uint gridSize, uint axis) {
    vec3 g = voxelGridCoords(world, gridMin, voxelSize, gridSize);
    vec3 s = axis == 0u ? g.yzx : (axis == 1u ? g.zxy : g.xyz);      // (u, v, depth)
    return vec4(s.xy * 2.0 - 1.0, s.z, 1.0);
}

// Dominant axis of a plane's normal: the largest |component|, the lower axis on ties (the CPU oracle's rule).
uint dominantAxis(vec3 n) {
    vec3 a = abs(n);
    if (a.x >= a.y && a.x >= a.z) return 0u;
    return a.y >= a.z ? 1u : 2u;
}

#endif
