#version 460
// voxelize_axis.geom.glsl: the single-draw rasterisation of the voxelization (--gi-voxel-draws single) without
// dilation (centre raster, or VK_EXT_conservative_rasterization): each triangle projected along its own dominant
// axis by the geometry shader, in one draw where voxelize.vert alone needs three swizzled ones. The fallback rung of
// the "voxel-single-draw" ladder: a GPU with VK_NV_geometry_shader_passthrough + VK_NV_viewport_swizzle runs
// voxelize_passthrough.geom instead (no re-emission).
#extension GL_GOOGLE_include_directive : require
#include "voxelize_geometry.glsl"
