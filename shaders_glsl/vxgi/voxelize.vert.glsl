#version 460
// voxelize.vert.glsl: vertex pulling as the G-buffer's, then an orthographic projection of the grid's cube along
// push.axis: the two other axes become the N x N framebuffer (pixel centres = voxel centres), the axis itself the
// depth 0..1, so clipping drops what lies outside the grid. Ports IDKEngine's VXGI/Voxelize vertex shader (its
// 3-draw fallback, the swizzle chosen per draw; with kVoxelAxisSwizzled the viewport swizzle's input).
#extension GL_GOOGLE_include_directive : require
#include "scene_vertex.glsl"
#include "vxgi_types.h"
#include "voxelize_projection.glsl"

layout(push_constant, scalar) uniform Push { VoxelizePush p; };

void main() {
    emitSceneVertex(gl_DrawID, p.instances, p.vertices, p.colors, p.uv1, p.frame);
    // kVoxelAxisDominant: the geometry shader projects again per triangle; this one is then unused.
    // kVoxelAxisSwizzled: the grid coordinates (0..1 on all three axes, w = 1) that the passthrough geometry shader
    // forwards untouched; the viewport it picks swizzles them into its axis's projection (vxgi_axis_swizzle.hpp).
    uint axis = p.axis & kVoxelAxisMask;
    if (axis == kVoxelAxisSwizzled)
        gl_Position = vec4(voxelGridCoords(outWorldPosition, p.gridMin, p.voxelSize, p.gridSize), 1.0);
    else
        gl_Position = voxelProjection(outWorldPosition, p.gridMin, p.voxelSize, p.gridSize, min(axis, 2u));
}
