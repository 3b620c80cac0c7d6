#version 460
// voxelize_passthrough.geom.glsl: native rung of the "voxel-single-draw" ladder (--gi-voxel-draws single on a device
// with VK_NV_geometry_shader_passthrough + VK_NV_viewport_swizzle; IDKEngine's VXGI/Voxelize geometry shader, its
// GL_NV_geometry_shader_passthrough + GL_NV_viewport_swizzle path). Every input passes through untouched; the shader
// only writes the primitive's gl_ViewportIndex = its dominant axis, and that viewport's swizzle (set in the pipeline,
// passes/vxgi_axis_swizzle.hpp) turns voxelize.vert's unswizzled grid coordinates into the axis's projection, as
// voxelize_axis.geom does by re-emitting. What it saves on a real GPU: a passthrough geometry shader emits no
// vertices, so the hardware forwards the vertex shader's outputs to the rasterizer unchanged and only attaches the
// primitive's viewport index: no per-vertex copy of the seven attributes into the geometry stage's output storage
// and back, no variable-size output to allocate (the cost that makes a general geometry shader such as
// voxelize_axis.geom slow, and made IDKEngine measure three draws faster than it); and, unlike three draws, the
// index fetch and vertex shading run once per vertex instead of three times, with no triangle culled twice.
// Not combinable with the dilation fallback (a passthrough shader cannot move vertices): it needs centre raster or
// VK_EXT_conservative_rasterization, which every GPU with the NV extensions has.
#extension GL_GOOGLE_include_directive : require
#extension GL_NV_geometry_shader_passthrough : require
#include "voxelize_projection.glsl"

layout(triangles) in;

// Passthrough inputs: forwarded to the rasterizer as they come (the vertex shader's interface, scene_vertex.glsl).
layout(passthrough) in gl_PerVertex { vec4 gl_Position; } gl_in[];
layout(passthrough, location = 0) in vec3 inWorldPosition[];
layout(passthrough, location = 1) in vec3 inNormal[];
layout(passthrough, location = 2) in vec4 inTangent[];
layout(passthrough, location = 3) in vec2 inUv[];
layout(passthrough, location = 4) flat in uint inInstance[];
layout(passthrough, location = 5) in vec4 inColor[];
layout(passthrough, location = 6) in vec2 inUv1[];

void main() {
    // The axis from the world positions, as voxelize_axis.geom and the CPU oracle take it (same ties).
    vec3 plane = cross(inWorldPosition[1] - inWorldPosition[0], inWorldPosition[2] - inWorldPosition[0]);
    gl_ViewportIndex = int(dominantAxis(plane));
}
