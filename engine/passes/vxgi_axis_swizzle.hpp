// vxgi_axis_swizzle.hpp: the viewport state of the single-draw voxelization's native rung ("voxel-single-draw" =
// native: VK_NV_geometry_shader_passthrough + VK_NV_viewport_swizzle; passes/vxgi_voxelize.cpp). voxelize.vert
// emits the unswizzled grid coordinates g = (world - gridMin) / (voxelSize * N), 0..1 inside the grid, w = 1;
// voxelize_passthrough.geom sends each triangle to viewport = its dominant axis, and that viewport's swizzle makes
// the clip position voxelProjection() gives for the axis in the three-draw path (voxelize_projection.glsl):
// axis x (u, v, depth) = g.yzx, axis y g.zxy, axis z g.xyz (the port of IDKEngine's NV fast path of Voxelizer.cs).
// tests/unit/passes/vxgi_axis_swizzle_test.cpp checks them against the three-draw projection on the CPU.
// A swizzle can only permute and negate, so it cannot also apply the three-draw shader's 2g - 1 to x and y but
// not to depth: the viewport does that part instead. Each of the three viewports spans [-N, N) in x and y, so NDC
// 0..1 (the grid) lands on pixels 0..N exactly as NDC -1..1 does on the three-draw path's [0, N) viewport; the
// scissor (0, 0, N, N) keeps the grid's square (the clip volume's x, y >= -1 half of it lies left/below the render
// area). Depth is the swizzled component itself, clipped to 0..1 as before.
#pragma once
#include <volk.h>

#include <array>
#include <cstdint>

namespace idk::passes {

// Viewport i's swizzle (i = the projection axis, gl_ViewportIndex of voxelize_passthrough.geom).
inline std::array<VkViewportSwizzleNV, 3> voxelAxisSwizzles() {
    constexpr VkViewportCoordinateSwizzleNV X = VK_VIEWPORT_COORDINATE_SWIZZLE_POSITIVE_X_NV;
    constexpr VkViewportCoordinateSwizzleNV Y = VK_VIEWPORT_COORDINATE_SWIZZLE_POSITIVE_Y_NV;
    constexpr VkViewportCoordinateSwizzleNV Z = VK_VIEWPORT_COORDINATE_SWIZZLE_POSITIVE_Z_NV;
    constexpr VkViewportCoordinateSwizzleNV W = VK_VIEWPORT_COORDINATE_SWIZZLE_POSITIVE_W_NV;
    return {{{Y, Z, X, W},    // axis x: (g.y, g.z, g.x)
             {Z, X, Y, W},    // axis y: (g.z, g.x, g.y)
             {X, Y, Z, W}}};  // axis z: (g.x, g.y, g.z)
}

// The viewport of every axis for an N^3 grid (see the header: NDC 0..1 -> pixels 0..N).
inline VkViewport voxelSwizzleViewport(uint32_t n) {
    const float side = float(n);
    return VkViewport{-side, -side, 2.0f * side, 2.0f * side, 0.0f, 1.0f};
}

}  // namespace idk::passes
