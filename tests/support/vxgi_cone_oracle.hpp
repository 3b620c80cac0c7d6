// vxgi_cone_oracle.hpp: a CPU voxel cone tracer over a grid and mip chain read back from the GPU: the oracle of
// the cone-tracing pass (passes/vxgi_cone_trace.cpp). The cone set, the march and the compositing are the shader's
// own source (shared/vxgi_cone.h compiled as C++); what this file adds is Vulkan's trilinear fetch (clamp to edge,
// linear between mip levels) over the read-back volumes, and a constant sky. Test
// support, no IDKEngine counterpart.
#pragma once
#include <glm/glm.hpp>

#include <array>
#include <vector>

#include "frame/vxgi_feature.hpp"
#include "frame/vxgi_settings.hpp"
#include "scene/camera.hpp"
#include "shared/vxgi_types.h"
#include "support/placed_quads.hpp"
#include "vk/context.hpp"
#include "vk/resources.hpp"

namespace idk::test {

// An RGBA volume with its mip levels (level l is (size >> l)^3, x fastest).
struct VoxelVolumeData {
    uint32_t size = 0;
    std::vector<std::vector<glm::vec4>> levels;
};

// The grid (level 0) and the six directional volumes (+x -x +y -y +z -z) as the cone tracer samples them.
struct ConeGridData {
    VoxelVolumeData grid;
    std::array<VoxelVolumeData, 6> directions;
    VkFormat directionFormat = VK_FORMAT_R16G16B16A16_SFLOAT;  // their colour images' (conformance::directionStep)
};

// Reads `levels` mip levels of a 3D image of VXGI's formats (conformance::decodeVoxelTexel) left in `layout` (it
// is left there again).
VoxelVolumeData readVoxelVolume(vk::Context& ctx, const vk::Image& image, uint32_t levels, VkImageLayout layout);
// All levels of a directional volume: rgb from its colour image, alpha from its opacity image (RGBA16F rung: the
// colour image's), the values the cone tracer's fetch filters.
VoxelVolumeData readDirectionVolume(vk::Context& ctx, const frame::DirectionVolume& direction, VkImageLayout layout);

// Vulkan's linear-mipmap trilinear fetch at normalized `uvw`, level `lod`, clamp to edge.
glm::vec4 sampleVolumeOnCpu(const VoxelVolumeData& v, glm::vec3 uvw, float lod);

// The cone from receiver `origin` (geometric normal `plane`) along unit `dir`: the radiance it gathers, the rest
// from a constant `sky`. `c` carries the grid placement, maxLod and stepFactor exactly as the GPU pass sets them.
glm::vec3 traceConeOnCpu(const ConeGridData& grid, const gpu::ConeTracePush& c, glm::vec3 origin, glm::vec3 plane,
                         glm::vec3 dir, float tanHalf, glm::vec3 sky);

// The diffuse cone set's irradiance E at `origin` with shading normal `n` (c.ringCones ring cones).
glm::vec3 diffuseIrradianceOnCpu(const ConeGridData& grid, const gpu::ConeTracePush& c, glm::vec3 origin,
                                 glm::vec3 plane, glm::vec3 n, glm::vec3 sky);

// A renderer's last grid and directional mips read back, and the push fields its cone tracer used.
ConeGridData readConeGrid(vk::Context& ctx, const frame::VxgiFeature& vxgi);
gpu::ConeTracePush conePush(const frame::VxgiFeature& vxgi, const frame::VxgiSettings& settings);

// The frame the cone tracer predicts for a scene of quads without specular layers (KHR_materials_specular 0) lit
// only through the cones: albedo (as the 8-bit sRGB G-buffer holds it) / pi * E per pixel of a size x size view.
// Left out: pixels that see nothing or quad `emitter`, and those a neighbour pixel sees on another quad (the GPU's
// geometric normal comes from the depth buffer's neighbours).
struct PredictedPixel {
    uint32_t x = 0, y = 0;
    glm::vec3 radiance{0.0f};
};
std::vector<PredictedPixel> predictDiffuseFrame(const std::vector<PlacedQuad>& quads, int emitter,
                                                const scene::CameraView& camera, uint32_t size,
                                                const ConeGridData& grid, const gpu::ConeTracePush& c, glm::vec3 sky);

}  // namespace idk::test
