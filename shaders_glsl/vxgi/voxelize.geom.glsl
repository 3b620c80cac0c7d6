#version 460
// voxelize.geom.glsl: fallback rung of the "conservative-raster" ladder: geometry-shader triangle dilation (Crassin
// & Green, "Octree-Based Sparse Voxelization", OpenGL Insights 2012), so that every voxel a triangle touches in its
// dominant projection gets a fragment, not only those whose centre it covers: thin walls then never leak. Each
// edge moves out by the pixel's semi-diagonal along its 2D normal, the new corners are the offset edges'
// intersections, and every attribute is extrapolated affinely (barycentrics of the new corner in the original
// triangle), so the world position stays on the triangle's plane. The fragment shader drops what lies outside the
// triangle's 2D bounds grown by half a pixel (the sharp corners' overshoot). Triangles of another draw's dominant
// axis are culled here (the fragment shader's check stays for the other rungs); in the single draw
// (--gi-voxel-draws single) each triangle takes its own. No IDKEngine counterpart (it
// relies on GL_NV_conservative_raster). A real GPU would take VK_EXT_conservative_rasterization (native rung).
#extension GL_GOOGLE_include_directive : require
#define IDK_VOXELIZE_DILATE
#include "voxelize_geometry.glsl"

