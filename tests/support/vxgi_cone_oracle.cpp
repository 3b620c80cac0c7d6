// vxgi_cone_oracle.cpp: the CPU cone tracer (vxgi_cone_oracle.hpp).
#include "vxgi_cone_oracle.hpp"

#include <algorithm>
#include <cmath>

#include "conformance/voxel_oracle.hpp"
#include "graph/barrier_planner.hpp"
#include "shared/pt_common.h"
#include "shared/vxgi_cone.h"
#include "vk/transfer.hpp"

namespace idk::test {

VoxelVolumeData readVoxelVolume(vk::Context& ctx, const vk::Image& image, uint32_t levels, VkImageLayout layout) {
    VoxelVolumeData out;
    out.size = image.extent.width;
    const uint32_t texel = vk::bytesPerTexel(image.format);
    size_t total = 0;
    for (uint32_t l = 0; l < levels; ++l) total += size_t(std::max(1u, out.size >> l)) * std::max(1u, out.size >> l) *
                                                   std::max(1u, out.size >> l);
    vk::BufferDesc desc;
    desc.size = total * texel;
    desc.memory = vk::MemoryUsage::Readback;
    desc.name = "voxel volume readback";
    vk::Buffer staging = ctx.createBuffer(desc);
    ctx.runImmediate([&](VkCommandBuffer cmd) {
        vk::transitionImage(cmd, image, layout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
        VkDeviceSize offset = 0;
        for (uint32_t l = 0; l < levels; ++l) {
            const uint32_t s = std::max(1u, out.size >> l);
            VkBufferImageCopy copy{};
            copy.bufferOffset = offset;  // a multiple of the texel size, as Vulkan requires
            copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, l, 0, 1};
            copy.imageExtent = {s, s, s};
            vkCmdCopyImageToBuffer(cmd, image.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, staging.buffer, 1, &copy);
            offset += VkDeviceSize(s) * s * s * texel;
        }
        vk::transitionImage(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, layout);
    });
    std::vector<uint8_t> bytes(desc.size);
    vk::downloadBuffer(ctx, staging, bytes.data(), desc.size);
    ctx.destroy(staging);
    size_t at = 0;
    for (uint32_t l = 0; l < levels; ++l) {
        const size_t s = std::max(1u, out.size >> l);
        std::vector<glm::vec4> level(s * s * s);
        for (glm::vec4& v : level) v = conformance::decodeVoxelTexel(image.format, bytes.data() + texel * at++);
        out.levels.push_back(std::move(level));
    }
    return out;
}

VoxelVolumeData readDirectionVolume(vk::Context& ctx, const frame::DirectionVolume& direction, VkImageLayout layout) {
    VoxelVolumeData out = readVoxelVolume(ctx, direction.colour.image, direction.levels(), layout);
    if (!direction.packed()) return out;
    const VoxelVolumeData opacity = readVoxelVolume(ctx, direction.opacity.image, direction.levels(), layout);
    for (size_t l = 0; l < out.levels.size(); ++l)
        for (size_t i = 0; i < out.levels[l].size(); ++i) out.levels[l][i].a = opacity.levels[l][i].r;
    return out;
}

namespace {

glm::vec4 texel(const std::vector<glm::vec4>& level, int s, int x, int y, int z) {
    x = std::clamp(x, 0, s - 1);  // clamp to edge
    y = std::clamp(y, 0, s - 1);
    z = std::clamp(z, 0, s - 1);
    return level[(size_t(z) * s + y) * s + x];
}

glm::vec4 sampleLevel(const VoxelVolumeData& v, glm::vec3 uvw, uint32_t l) {
    const int s = int(std::max(1u, v.size >> l));
    const glm::vec3 u = uvw * float(s) - 0.5f;
    const glm::vec3 base = glm::floor(u);
    const glm::vec3 f = u - base;
    const glm::ivec3 i = glm::ivec3(base);
    glm::vec4 sum(0.0f);
    for (int k = 0; k < 8; ++k) {
        const glm::ivec3 o(k & 1, (k >> 1) & 1, k >> 2);
        const float w = (o.x ? f.x : 1.0f - f.x) * (o.y ? f.y : 1.0f - f.y) * (o.z ? f.z : 1.0f - f.z);
        if (w > 0.0f) sum += w * texel(v.levels[l], s, i.x + o.x, i.y + o.y, i.z + o.z);
    }
    return sum;
}

}  // namespace

glm::vec4 sampleVolumeOnCpu(const VoxelVolumeData& v, glm::vec3 uvw, float lod) {
    const float top = float(v.levels.size() - 1);
    lod = glm::clamp(lod, 0.0f, top);
    const uint32_t l0 = uint32_t(std::floor(lod));
    const float f = lod - float(l0);
    const glm::vec4 a = sampleLevel(v, uvw, l0);
    if (f <= 0.0f || l0 + 1 >= v.levels.size()) return a;
    return a * (1.0f - f) + sampleLevel(v, uvw, l0 + 1) * f;
}

glm::vec3 traceConeOnCpu(const ConeGridData& grid, const gpu::ConeTracePush& c, glm::vec3 origin, glm::vec3 plane,
                         glm::vec3 dir, float tanHalf, glm::vec3 sky) {
    gpu::VxgiMarch m = gpu::vxgiMarchBegin(origin, plane, dir, tanHalf, c.voxelSize);
    while (gpu::vxgiMarchNext(m, c.gridMin, c.voxelSize, c.gridSize, c.maxLod)) {
        const glm::vec4 sx = sampleVolumeOnCpu(grid.directions[gpu::vxgiDirectionIndex(dir, 0u)], m.uvw, m.lod);
        const glm::vec4 sy = sampleVolumeOnCpu(grid.directions[gpu::vxgiDirectionIndex(dir, 1u)], m.uvw, m.lod);
        const glm::vec4 sz = sampleVolumeOnCpu(grid.directions[gpu::vxgiDirectionIndex(dir, 2u)], m.uvw, m.lod);
        gpu::vxgiMarchTake(m, gpu::vxgiCombine(dir, sx, sy, sz), c.stepFactor);
    }
    return m.radiance + (1.0f - m.opacity) * sky;
}

glm::vec3 diffuseIrradianceOnCpu(const ConeGridData& grid, const gpu::ConeTracePush& c, glm::vec3 origin,
                                 glm::vec3 plane, glm::vec3 n, glm::vec3 sky) {
    glm::vec3 t, b;
    gpu::vxgiTangents(n, t, b);
    glm::vec3 e(0.0f);
    const uint32_t count = gpu::vxgiDiffuseConeCount(c.ringCones, c.footprintCones);
    for (uint32_t k = 0; k < count; ++k) {
        glm::vec3 dir;
        float tanHalf = 0.0f;
        const float w = gpu::vxgiDiffuseCone(k, c.ringCones, c.footprintCones, n, t, b, dir, tanHalf);
        e += w * traceConeOnCpu(grid, c, origin, plane, dir, tanHalf, sky);
    }
    return e * 3.14159265358979f;
}

ConeGridData readConeGrid(vk::Context& ctx, const frame::VxgiFeature& vxgi) {
    ConeGridData grid;
    grid.grid = readVoxelVolume(ctx, *vxgi.grid(), 1, VK_IMAGE_LAYOUT_GENERAL);
    // The directional volumes end where the cone tracer sampled them (the feature's final use).
    const VkImageLayout sampled = graph::stateAfterAccess(graph::Access::SampledRead, graph::ResourceKind::Image,
                                                          VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT)
                                      .layout;
    for (uint32_t d = 0; d < 6; ++d) grid.directions[d] = readDirectionVolume(ctx, vxgi.directions()[d], sampled);
    grid.directionFormat = vxgi.directions()[0].colour.image.format;
    return grid;
}

gpu::ConeTracePush conePush(const frame::VxgiFeature& vxgi, const frame::VxgiSettings& settings) {
    gpu::ConeTracePush c{};
    c.gridMin = vxgi.box().gridMin;
    c.voxelSize = vxgi.box().voxelSize;
    c.gridSize = vxgi.box().size;
    c.maxLod = float(vxgi.directions()[0].levels() - 1);
    c.stepFactor = settings.stepFactor;
    c.ringCones = settings.ringCones;
    c.footprintCones = settings.footprintCones;
    return c;
}

namespace {

// The G-buffer stores the base colour as 8-bit sRGB: the albedo the lighting pass decodes.
float gbufferAlbedo(float linear) {
    const double e = linear <= 0.0031308f ? 12.92 * linear : 1.055 * std::pow(double(linear), 1.0 / 2.4) - 0.055;
    const double q = std::round(e * 255.0) / 255.0;
    return float(q <= 0.04045 ? q / 12.92 : std::pow((q + 0.055) / 1.055, 2.4));
}

}  // namespace

std::vector<PredictedPixel> predictDiffuseFrame(const std::vector<PlacedQuad>& quads, int emitter,
                                                const scene::CameraView& camera, uint32_t size,
                                                const ConeGridData& grid, const gpu::ConeTracePush& c, glm::vec3 sky) {
    const glm::mat4 inverseViewProjection =
        glm::inverse(scene::projectionMatrix(camera, 1.0f) * scene::viewMatrix(camera));
    auto hit = [&](int x, int y, glm::vec3& o, glm::vec3& d) {
        gpu::ptCameraRay(inverseViewProjection, glm::vec2(float(x) + 0.5f, float(y) + 0.5f), glm::vec2(float(size)), o,
                         d);
        return castRay(quads, glm::dvec3(o), glm::dvec3(d), 0.0, 1e9);
    };
    std::vector<PredictedPixel> out;
    for (int y = 1; y + 1 < int(size); ++y) {
        for (int x = 1; x + 1 < int(size); ++x) {
            glm::vec3 o, d, o2, d2;
            const auto h = hit(x, y, o, d);
            if (!h || int(h->quad) == emitter) continue;
            bool interior = true;
            for (glm::ivec2 q : {glm::ivec2(x - 1, y), glm::ivec2(x + 1, y), glm::ivec2(x, y - 1), glm::ivec2(x, y + 1)}) {
                const auto hq = hit(q.x, q.y, o2, d2);
                interior = interior && hq && hq->quad == h->quad;
            }
            if (!interior) continue;
            const PlacedQuad& quad = quads[h->quad];
            const glm::vec3 p = o + d * float(h->t);
            const glm::vec3 n = glm::dot(quad.normal, d) < 0.0f ? quad.normal : -quad.normal;
            const glm::vec3 e = diffuseIrradianceOnCpu(grid, c, p, n, n, sky);
            const glm::vec3 albedo(gbufferAlbedo(quad.baseColor.r), gbufferAlbedo(quad.baseColor.g),
                                   gbufferAlbedo(quad.baseColor.b));
            out.push_back({uint32_t(x), uint32_t(y), albedo / 3.14159265358979f * e});
        }
    }
    return out;
}

}  // namespace idk::test
