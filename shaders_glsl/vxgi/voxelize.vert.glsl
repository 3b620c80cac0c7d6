#version 460
// voxelize.vert.glsl: vertex pulling as the G-buffer's, then an orthographic projection of the grid's cube along
// push.axis: the two other axes become the N x N framebuffer (pixel centres = voxel centres), the axis itself the
// depth 0..1, so clipping drops what lies outside the grid. Ports IDKEngine's VXGI/Voxelize vertex shader (its
// 3-draw fallback, the swizzle chosen per draw).
#extension GL_GOOGLE_include_directive : require
#include "scene_vertex.glsl"
#include "vxgi_types.h"

layout(push_constant, scalar) uniform Push { VoxelizePush p; };

void main() {
    emitSceneVertex(gl_DrawID, p.instances, p.vertices, p.colors, p.uv1, p.frame);
    vec3 g = (outWorldPosition - p.gridMin) / (p.voxelSize * float(p.gridSize));  // 0..1 inside the grid
    vec3 s = p.axis == 0u ? g.yzx : (p.axis == 1u ? g.zxy : g.xyz);                // (u, v, depth)
    gl_Position = vec4(s.xy * 2.0 - 1.0, s.z, 1.0);
}
