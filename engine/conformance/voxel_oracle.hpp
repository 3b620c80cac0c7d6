// voxel_oracle.hpp: a CPU voxelizer for scenes of planar quads (placed_quads.hpp): the oracle of the VXGI
// voxelization passes. It does what the GPU does, exactly: each quad is projected along the dominant axis of its
// normal onto the grid's N x N raster; every voxel-centre sample inside the quad gives one "fragment" at the
// quad's point there, whose voxel is found along the axis; the fragment carries the outgoing diffuse radiance of
// the quad at that point (albedo / pi times each point light's irradiance, plus emission; for a double-sided quad
// the brighter side's) and its facing (shared/vxgi_types.h, as the voxelization shader computes it). Samples
// within 1e-4 voxel of a quad edge or of a voxel face along the axis are "ambiguous" (the GPU's tie rules decide
// them) and mark their voxels so the comparison leaves them out. Unshadowed unless asked (see voxelizeOnCpu).
// The front-most rule as the voxelization's key pass applies it (shared/vxgi_depth_key.h, the same functions): per
// voxel and facing class (the quad's front normal's dominant axis and sign) only the fragments whose depth key lies
// within kVoxelKeyTolerance of the largest are kept; the others count as hidden. A voxel where a fragment's key
// lies within 2 steps of that threshold is ambiguous (the GPU's float position decides it).
#pragma once
#include <glm/glm.hpp>

#include <vector>

#include "conformance/placed_quads.hpp"
#include "frame/voxel_volume.hpp"
#include "passes/vxgi_passes.hpp"
#include "vk/context.hpp"

namespace idk::conformance {

struct OracleVoxel {
    glm::dvec3 sum{0.0};
    glm::dvec3 max{0.0};
    glm::dvec4 facing{0.0};  // sum of the fragments' facings
    uint32_t count = 0;   // the kept (front-most) fragments
    uint32_t hidden = 0;  // fragments behind a surface of their class in the voxel, dropped
    uint32_t classes = 0; // bit c: a kept fragment of facing class c (voxelFacingClass)
    bool ambiguous = false;
};

struct OracleLight {
    glm::dvec3 position{0.0};
    glm::dvec3 intensity{0.0};  // colour * candela
};

// quads[i] with emission emissive[i] (linear radiance; missing entries: none). `shadowed`: each light is blocked
// where a quad lies between the fragment and it (hard shadows, as the voxelization's shadow rays); a ray that
// passes within 1e-3 voxel of a quad's edge marks its voxel ambiguous.
std::vector<OracleVoxel> voxelizeOnCpu(const std::vector<PlacedQuad>& quads, const std::vector<glm::vec3>& emissive,
                                       const std::vector<OracleLight>& lights, const passes::VoxelGridBox& box,
                                       bool shadowed = false);

// The RGBA16F voxel grid a frame left in `layout` (GENERAL for the grid; level 0), as RGBA floats, x fastest; the
// GPU side of every comparison with the oracle (the registry's vxgi checks and the gl-interop rung's tests).
// Also reads level 0 of the directional volumes' images (decodeVoxelTexel's formats).
std::vector<glm::vec4> readVoxelGrid(vk::Context& ctx, const vk::Image& grid,
                                     VkImageLayout layout = VK_IMAGE_LAYOUT_GENERAL);
// Level 0 of a directional volume as the cone tracer sees it: rgb from its colour image, alpha from its opacity
// image (or the colour image's alpha on the RGBA16F rung of "vxgi-volume-format").
std::vector<glm::vec4> readDirectionGrid(vk::Context& ctx, const frame::DirectionVolume& direction,
                                         VkImageLayout layout);

// One texel of VXGI's volume formats as floats: RGBA16F; B10G11R11_UFLOAT_PACK32 (alpha 1, as sampling returns);
// R8_UNORM (in every channel). Throws on another format.
glm::vec4 decodeVoxelTexel(VkFormat format, const uint8_t* texel);
// One storage step of a directional voxel `value` (premultiplied rgb, coverage) in `colour`'s format (RGBA16F, or
// B10G11R11_UFLOAT with coverage in R8_UNORM), per channel: the rounding a GPU's store may add (round to nearest or
// toward zero), which a comparison with a CPU value computed in float must allow.
glm::vec4 directionStep(VkFormat colour, glm::vec4 value);

}  // namespace idk::conformance
