// voxel_single_draw_test.cpp: the single-draw voxelization's native rung (VK_NV_geometry_shader_passthrough +
// VK_NV_viewport_swizzle) without a device that has it (lavapipe has neither extension):
//  * the "voxel-single-draw" ladder offers it only with both extensions, geometryShader and multiViewport, names
//    what is missing, and refuses a forced native rung with that reason;
//  * the per-viewport swizzles and viewport of passes/vxgi_axis_swizzle.hpp, applied on the CPU as the extension
//    specifies (component select/negate per viewport, then the viewport transform) to voxelize.vert's unswizzled
//    grid coordinates, give every vertex of sample triangles the same window coordinates and depth as the
//    three-draw path (voxelProjection of voxelize_projection.glsl, transcribed below, on the N x N viewport): depth
//    and the in/out decision (clip volume, plus the scissor on the native rung) exactly, x and y exactly on the voxel
//    lattice and else within the three-draw shader's own float rounding; a wrong table fails the check.
#include <gtest/gtest.h>

#include <glm/glm.hpp>

#include <array>
#include <cmath>
#include <random>
#include <stdexcept>

#include "passes/vxgi_axis_swizzle.hpp"
#include "vk/features.hpp"

namespace idk {
namespace {

const vk::Ladder& find(const std::vector<vk::Ladder>& ladders, const std::string& id) {
    for (const vk::Ladder& l : ladders)
        if (l.id == id) return l;
    throw std::logic_error("no ladder " + id);
}

vk::DeviceCapabilities lavapipeLike() {
    vk::DeviceCapabilities c;
    c.geometryShader = true;
    c.multiViewport = true;
    return c;
}

TEST(VoxelSingleDraw, LadderOffersPassthroughOnlyWithBothExtensions) {
    vk::DeviceCapabilities c = lavapipeLike();
    vk::Ladder l = find(vk::buildLadders(c), "voxel-single-draw");
    EXPECT_EQ(l.chosen, vk::Rung::Fallback);
    EXPECT_FALSE(l.options.front().available);
    EXPECT_EQ(l.reason, "device lacks VK_NV_geometry_shader_passthrough, VK_NV_viewport_swizzle");

    c.geometryShaderPassthroughNv = true;  // one of the two is not enough
    l = find(vk::buildLadders(c), "voxel-single-draw");
    EXPECT_EQ(l.chosen, vk::Rung::Fallback);
    EXPECT_EQ(l.reason, "device lacks VK_NV_viewport_swizzle");

    c.viewportSwizzleNv = true;
    l = find(vk::buildLadders(c), "voxel-single-draw");
    EXPECT_EQ(l.chosen, vk::Rung::Native);
    EXPECT_EQ(l.chosenMechanism, "VK_NV_geometry_shader_passthrough + VK_NV_viewport_swizzle");
    EXPECT_EQ(find(vk::buildLadders(c, true), "voxel-single-draw").chosen, vk::Rung::Fallback);  // --fallback

    c.multiViewport = false;  // three viewports are needed
    l = find(vk::buildLadders(c), "voxel-single-draw");
    EXPECT_EQ(l.chosen, vk::Rung::Fallback);
    EXPECT_EQ(l.reason, "device lacks multiViewport");
}

TEST(VoxelSingleDraw, ForcingTheAbsentNativeRungNamesTheExtensions) {
    std::string error;
    const std::vector<vk::Ladder> l = vk::buildLadders(
        lavapipeLike(), vk::LadderChoice{false, {vk::parseRungForce("voxel-single-draw=native")}}, &error);
    EXPECT_EQ(error,
              "--rung voxel-single-draw=native: device lacks VK_NV_geometry_shader_passthrough, "
              "VK_NV_viewport_swizzle (rungs this device can run: voxel-single-draw=fallback)");
    EXPECT_EQ(find(l, "voxel-single-draw").chosen, vk::Rung::Fallback);
    EXPECT_EQ(vk::ladderRungs("voxel-single-draw"), (std::vector<vk::Rung>{vk::Rung::Native, vk::Rung::Fallback}));
}

// --- The swizzle on the CPU ---

float component(VkViewportCoordinateSwizzleNV s, const glm::vec4& p) {
    switch (s) {
        case VK_VIEWPORT_COORDINATE_SWIZZLE_POSITIVE_X_NV: return p.x;
        case VK_VIEWPORT_COORDINATE_SWIZZLE_NEGATIVE_X_NV: return -p.x;
        case VK_VIEWPORT_COORDINATE_SWIZZLE_POSITIVE_Y_NV: return p.y;
        case VK_VIEWPORT_COORDINATE_SWIZZLE_NEGATIVE_Y_NV: return -p.y;
        case VK_VIEWPORT_COORDINATE_SWIZZLE_POSITIVE_Z_NV: return p.z;
        case VK_VIEWPORT_COORDINATE_SWIZZLE_NEGATIVE_Z_NV: return -p.z;
        case VK_VIEWPORT_COORDINATE_SWIZZLE_POSITIVE_W_NV: return p.w;
        case VK_VIEWPORT_COORDINATE_SWIZZLE_NEGATIVE_W_NV: return -p.w;
        default: throw std::logic_error("bad swizzle");
    }
}

glm::vec4 swizzled(const VkViewportSwizzleNV& s, const glm::vec4& p) {
    return {component(s.x, p), component(s.y, p), component(s.z, p), component(s.w, p)};
}

// Transcriptions of voxelize_projection.glsl (float, as the shaders compute).
glm::vec3 gridCoords(glm::vec3 world, glm::vec3 gridMin, float voxelSize, uint32_t n) {
    return (world - gridMin) / (voxelSize * float(n));
}
glm::vec4 voxelProjection(glm::vec3 g, uint32_t axis) {
    const glm::vec3 s = axis == 0 ? glm::vec3(g.y, g.z, g.x) : (axis == 1 ? glm::vec3(g.z, g.x, g.y) : g);
    return {s.x * 2.0f - 1.0f, s.y * 2.0f - 1.0f, s.z, 1.0f};
}
uint32_t dominantAxis(glm::vec3 n) {
    const glm::vec3 a = glm::abs(n);
    if (a.x >= a.y && a.x >= a.z) return 0;
    return a.y >= a.z ? 1 : 2;
}

// A vertex after clipping's inside test, the viewport transform (Vulkan: xf = px/2 xd + ox, ox = x + px/2) and the
// scissor, in double: exact for these float inputs, so the two paths' only difference is the three-draw shader's
// own float rounding of 2s - 1 (none on the voxel lattice).
struct Window {
    glm::dvec3 xyz;
    bool kept;
};
Window toWindow(const glm::vec4& clip, const VkViewport& v, const VkRect2D& scissor) {
    const glm::dvec4 c(clip);
    const glm::dvec3 ndc = glm::dvec3(c) / c.w;
    Window w;
    w.xyz = {double(v.width) / 2.0 * ndc.x + (double(v.x) + double(v.width) / 2.0),
             double(v.height) / 2.0 * ndc.y + (double(v.y) + double(v.height) / 2.0),
             (double(v.maxDepth) - double(v.minDepth)) * ndc.z + double(v.minDepth)};
    const bool inClip = std::abs(c.x) <= c.w && std::abs(c.y) <= c.w && c.z >= 0.0 && c.z <= c.w;
    w.kept = inClip && w.xyz.x >= scissor.offset.x && w.xyz.y >= scissor.offset.y &&
             w.xyz.x <= double(scissor.offset.x) + scissor.extent.width &&
             w.xyz.y <= double(scissor.offset.y) + scissor.extent.height;
    return w;
}

// Mismatching vertices of `triangles` random triangles (inside and around the grid) between the three-draw
// projection and the swizzled single draw with the given table.
uint32_t mismatches(const std::array<VkViewportSwizzleNV, 3>& table, uint32_t n, uint32_t triangles,
                    std::array<uint32_t, 3>* axisCounts) {
    const glm::vec3 gridMin(-1.25f, 0.5f, -3.0f);
    const float voxelSize = 0.0625f;
    const float side = voxelSize * float(n);
    std::mt19937 rng(1234);
    std::uniform_real_distribution<float> u(-0.25f, 1.25f);  // a quarter of the grid beyond each face
    const VkViewport threeDraw{0.0f, 0.0f, float(n), float(n), 0.0f, 1.0f};
    const VkViewport single = passes::voxelSwizzleViewport(n);
    const VkRect2D square{{0, 0}, {n, n}};
    // The three-draw shader rounds 2s - 1 to float (|2s - 1| < 2: at most 2^-24 in NDC, N/2 * 2^-24 px, 2^-16 px at
    // N = 512, far below the 1/256 px sub-pixel grid rasterizers snap to); the swizzled path takes s as it is.
    // Exact on the lattice, where 2s - 1 is exact.
    const double roundingPx = double(n) * std::ldexp(1.0, -24);
    uint32_t bad = 0;
    for (uint32_t t = 0; t < triangles; ++t) {
        std::array<glm::vec3, 3> world;
        for (glm::vec3& p : world) p = gridMin + side * glm::vec3(u(rng), u(rng), u(rng));
        const bool lattice = t % 4 == 0;  // on the voxel lattice too (exact grid coordinates)
        if (lattice)
            for (glm::vec3& p : world) p = gridMin + voxelSize * glm::floor((p - gridMin) / voxelSize);
        const uint32_t axis = dominantAxis(glm::cross(world[1] - world[0], world[2] - world[0]));
        ++(*axisCounts)[axis];
        for (const glm::vec3& p : world) {
            const glm::vec3 g = gridCoords(p, gridMin, voxelSize, n);
            const Window a = toWindow(voxelProjection(g, axis), threeDraw, square);  // voxelize.vert, draw `axis`
            const Window b = toWindow(swizzled(table[axis], glm::vec4(g, 1.0f)), single, square);
            const double tolerance = lattice ? 0.0 : roundingPx;
            if (std::abs(a.xyz.x - b.xyz.x) > tolerance || std::abs(a.xyz.y - b.xyz.y) > tolerance ||
                a.xyz.z != b.xyz.z || a.kept != b.kept)
                ++bad;
        }
    }
    return bad;
}

TEST(VoxelSingleDraw, SwizzledViewportsReproduceTheThreeDrawProjection) {
    for (uint32_t n : {64u, 128u, 512u}) {
        std::array<uint32_t, 3> axes{};
        EXPECT_EQ(mismatches(passes::voxelAxisSwizzles(), n, 4000, &axes), 0u) << n;
        for (uint32_t a = 0; a < 3; ++a) EXPECT_GT(axes[a], 1000u) << "axis " << a << " barely sampled at " << n;
    }
}

TEST(VoxelSingleDraw, AWrongSwizzleTableIsCaught) {
    std::array<VkViewportSwizzleNV, 3> swapped = passes::voxelAxisSwizzles();
    std::swap(swapped[0], swapped[1]);  // axis x and y exchanged
    std::array<uint32_t, 3> axes{};
    EXPECT_GT(mismatches(swapped, 64, 400, &axes), 400u);
    std::array<VkViewportSwizzleNV, 3> mirrored = passes::voxelAxisSwizzles();
    mirrored[2].y = VK_VIEWPORT_COORDINATE_SWIZZLE_NEGATIVE_Y_NV;  // axis z flipped in v
    EXPECT_GT(mismatches(mirrored, 64, 400, &axes), 100u);
}

}  // namespace
}  // namespace idk
