// voxel_oracle.cpp: the CPU voxelizer of voxel_oracle.hpp, in double precision.
#include "conformance/voxel_oracle.hpp"

#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>

#include "shared/vxgi_depth_key.h"
#include "vk/resources.hpp"
#include "vk/transfer.hpp"

namespace idk::conformance {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kTie = 1e-4;  // in voxels

// The same frame as placed_quads.cpp's quadAxes (the quad's local x and y in world space).
void quadAxes(const glm::dvec3& n, glm::dvec3& x, glm::dvec3& y) {
    glm::dvec3 helper = std::abs(n.y) < 0.9 ? glm::dvec3(0.0, 1.0, 0.0) : glm::dvec3(0.0, 0.0, -1.0);
    x = glm::normalize(glm::cross(helper, n));
    y = glm::cross(n, x);
}

int dominantAxis(const glm::dvec3& n) {
    glm::dvec3 a = glm::abs(n);
    if (a.x >= a.y && a.x >= a.z) return 0;
    return a.y >= a.z ? 1 : 2;
}

// The radiance a fragment of quad q at p leaves (the brighter side's) and its facing, as voxelize_fragment.glsl.
// With `occluders`: whether the segment p -> light is blocked by one of them (true), and `tie` set when it passes
// within `margin` of an occluder's edge (the GPU's float ray decides those).
bool blocked(const std::vector<PlacedQuad>& occluders, const glm::dvec3& p, const glm::dvec3& l, double dist,
             double margin, bool& tie) {
    bool hit = false;
    for (const PlacedQuad& q : occluders) {
        const glm::dvec3 n = glm::normalize(glm::dvec3(q.normal));
        const double dn = glm::dot(l, n);
        if (std::abs(dn) < 1e-12) continue;
        const double t = glm::dot(glm::dvec3(q.centre) - p, n) / dn;
        if (t <= 1e-6 || t >= dist - 1e-6) continue;
        glm::dvec3 ax, ay;
        quadAxes(n, ax, ay);
        const glm::dvec3 r = p + l * t - glm::dvec3(q.centre);
        const double ex = double(q.halfSize.x) - std::abs(glm::dot(r, ax));
        const double ey = double(q.halfSize.y) - std::abs(glm::dot(r, ay));
        if (std::abs(ex) < margin || std::abs(ey) < margin) tie = true;
        hit = hit || (ex > 0.0 && ey > 0.0);
    }
    return hit;
}

glm::dvec3 radiance(const PlacedQuad& q, const glm::dvec3& n, const glm::dvec3& p, const glm::dvec3& emission,
                    const std::vector<OracleLight>& lights, glm::dvec4& facing,
                    const std::vector<PlacedQuad>* occluders, double margin, bool& tie) {
    glm::dvec3 front(0.0), back(0.0);
    for (const OracleLight& light : lights) {
        glm::dvec3 d = light.position - p;
        double d2 = glm::dot(d, d);
        glm::dvec3 l = d / std::sqrt(d2);
        if (occluders && blocked(*occluders, p, l, std::sqrt(d2), margin, tie)) continue;
        double c = glm::dot(n, l);
        if (c > 0.0) front += light.intensity * (c / d2);
        else if (q.doubleSided && c < 0.0) back += light.intensity * (-c / d2);
    }
    front = glm::dvec3(q.baseColor) / kPi * front + emission;
    back = glm::dvec3(q.baseColor) / kPi * back + (q.doubleSided ? emission : glm::dvec3(0.0));
    const glm::dvec3 y(0.2126, 0.7152, 0.0722);
    const double lf = glm::dot(front, y), lb = glm::dot(back, y);
    if (lb > lf) {
        facing = glm::dvec4(-n, lf / lb);
        return back;
    }
    facing = glm::dvec4(n, lf > 0.0 ? lb / lf : (q.doubleSided ? 1.0 : 0.0));
    return front;
}

}  // namespace

std::vector<OracleVoxel> voxelizeOnCpu(const std::vector<PlacedQuad>& quads, const std::vector<glm::vec3>& emissive,
                                       const std::vector<OracleLight>& lights, const passes::VoxelGridBox& box,
                                       bool shadowed) {
    const int n = int(box.size);
    const double v = box.voxelSize;
    const glm::dvec3 gmin(box.gridMin);
    std::vector<OracleVoxel> grid(size_t(n) * n * n);
    // Every fragment first: the front-most rule needs each voxel's largest key per class before any is kept.
    struct Fragment {
        size_t voxel;
        uint32_t facingClass, key;
        glm::dvec3 value;
        glm::dvec4 facing;
    };
    std::vector<Fragment> fragments;
    for (size_t qi = 0; qi < quads.size(); ++qi) {
        const PlacedQuad& q = quads[qi];
        const glm::dvec3 nrm = glm::normalize(glm::dvec3(q.normal));
        glm::dvec3 ax, ay;
        quadAxes(nrm, ax, ay);
        const glm::dvec3 c(q.centre);
        const glm::dvec3 emission = qi < emissive.size() ? glm::dvec3(emissive[qi]) : glm::dvec3(0.0);
        const int a = dominantAxis(nrm), u = (a + 1) % 3, w = (a + 2) % 3;
        for (int i = 0; i < n; ++i) {
            for (int j = 0; j < n; ++j) {
                // The voxel-centre sample of this column, moved onto the quad's plane along axis a.
                glm::dvec3 p(0.0);
                p[u] = gmin[u] + (i + 0.5) * v;
                p[w] = gmin[w] + (j + 0.5) * v;
                p[a] = c[a] - (nrm[u] * (p[u] - c[u]) + nrm[w] * (p[w] - c[w])) / nrm[a];
                // Inside the quad: |local x| <= hx, |local y| <= hy. The distance to an edge, measured in the
                // projection (per voxel), decides ties.
                const glm::dvec3 r = p - c;
                const double lx = glm::dot(r, ax), ly = glm::dot(r, ay);
                const double ex = double(q.halfSize.x) - std::abs(lx), ey = double(q.halfSize.y) - std::abs(ly);
                const double t = (p[a] - gmin[a]) / v;
                const int k = int(std::floor(t));
                const bool tie = std::abs(ex) < 1e-3 * v || std::abs(ey) < 1e-3 * v ||
                                 std::abs(t - std::round(t)) < kTie;
                if ((ex < 0.0 || ey < 0.0) && !tie) continue;
                if (k < 0 || k >= n) continue;
                glm::ivec3 voxel;
                voxel[a] = k;
                voxel[u] = i;
                voxel[w] = j;
                const size_t index = (size_t(voxel.z) * n + voxel.y) * n + voxel.x;
                OracleVoxel& o = grid[index];
                if (tie) {
                    o.ambiguous = true;
                    continue;
                }
                glm::dvec4 facing;
                bool shadowTie = false;
                glm::dvec3 value =
                    radiance(q, nrm, p, emission, lights, facing, shadowed ? &quads : nullptr, 1e-3 * v, shadowTie);
                if (shadowTie) {
                    o.ambiguous = true;
                    continue;
                }
                // The class from the quad's front normal, the key from its position in the voxel along the axis.
                const uint32_t facingClass = gpu::voxelFacingClass(glm::vec3(nrm));
                fragments.push_back({index, facingClass, gpu::voxelDepthKey(float(t), k, facingClass), value, facing});
            }
        }
    }
    std::vector<uint32_t> keys(grid.size() * 6, 0u);
    for (const Fragment& f : fragments)
        keys[f.voxel * 6 + f.facingClass] = std::max(keys[f.voxel * 6 + f.facingClass], f.key);
    for (const Fragment& f : fragments) {
        OracleVoxel& o = grid[f.voxel];
        const int64_t margin = int64_t(f.key) + gpu::kVoxelKeyTolerance - int64_t(keys[f.voxel * 6 + f.facingClass]);
        if (margin >= -2 && margin <= 2) o.ambiguous = true;  // on the threshold: float rounding decides
        if (margin < 0) {
            ++o.hidden;
            continue;
        }
        o.sum += f.value;
        o.facing += f.facing;
        o.max = glm::max(o.max, f.value);
        o.classes |= 1u << f.facingClass;
        ++o.count;
    }
    return grid;
}

glm::vec4 decodeVoxelTexel(VkFormat format, const uint8_t* texel) {
    switch (format) {
        case VK_FORMAT_R16G16B16A16_SFLOAT: {
            uint16_t h[4];
            std::memcpy(h, texel, sizeof(h));
            return {glm::unpackHalf1x16(h[0]), glm::unpackHalf1x16(h[1]), glm::unpackHalf1x16(h[2]),
                    glm::unpackHalf1x16(h[3])};
        }
        case VK_FORMAT_B10G11R11_UFLOAT_PACK32: {
            uint32_t bits;
            std::memcpy(&bits, texel, sizeof(bits));
            return {glm::unpackF2x11_1x10(bits), 1.0f};  // r: bits 0..10, g: 11..21, b: 22..31
        }
        case VK_FORMAT_R8_UNORM: return glm::vec4(float(texel[0]) / 255.0f);
        default: throw std::runtime_error("decodeVoxelTexel: not a VXGI volume format (" + std::to_string(format) + ")");
    }
}

glm::vec4 directionStep(VkFormat colour, glm::vec4 value) {
    const glm::vec4 v = glm::abs(value);
    if (colour == VK_FORMAT_R16G16B16A16_SFLOAT) return v * 0x1p-10f + 0x1p-24f;  // 10 mantissa bits
    // 6 mantissa bits for r and g, 5 for b, 5-bit exponent (smallest step 2^-20, 2^-19); coverage in 1/255 steps.
    return {v.x * 0x1p-6f + 0x1p-20f, v.y * 0x1p-6f + 0x1p-20f, v.z * 0x1p-5f + 0x1p-19f, 1.0f / 255.0f};
}

std::vector<glm::vec4> readVoxelGrid(vk::Context& ctx, const vk::Image& grid, VkImageLayout layout) {
    const std::vector<uint8_t> bytes = vk::readbackImage(ctx, grid, layout);  // level 0, x fastest
    const uint32_t texel = vk::bytesPerTexel(grid.format);
    std::vector<glm::vec4> out(bytes.size() / texel);
    for (size_t i = 0; i < out.size(); ++i) out[i] = decodeVoxelTexel(grid.format, bytes.data() + i * texel);
    return out;
}

std::vector<glm::vec4> readDirectionGrid(vk::Context& ctx, const frame::DirectionVolume& direction,
                                         VkImageLayout layout) {
    std::vector<glm::vec4> out = readVoxelGrid(ctx, direction.colour.image, layout);
    if (!direction.packed()) return out;
    const std::vector<glm::vec4> opacity = readVoxelGrid(ctx, direction.opacity.image, layout);
    for (size_t i = 0; i < out.size(); ++i) out[i].a = opacity[i].r;
    return out;
}

}  // namespace idk::conformance
