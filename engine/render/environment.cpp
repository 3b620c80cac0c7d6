// environment.cpp: equirectangular HDR environment: CPU SH9 irradiance projection, box-filtered mips, and the
// staged upload of every mip into one RGBA16F texture. Replaces IDKEngine's SkyBoxManager cubemap loading.
#include "render/environment.hpp"

#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "shader_manifest.hpp"
#include "vk/context.hpp"
#include "vk/transfer.hpp"

namespace idk::render {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Real SH basis up to l = 2 without its constants (they are folded into the coefficients).
std::array<double, 9> shPolynomials(const glm::dvec3& d) {
    return {1.0, d.y, d.z, d.x, d.x * d.y, d.y * d.z, 3.0 * d.z * d.z - 1.0, d.x * d.z, d.x * d.x - d.y * d.y};
}

// Y_lm = constant * polynomial, in the order of shPolynomials.
constexpr std::array<double, 9> kShConstants = {0.282094791773878, 0.488602511902920, 0.488602511902920,
                                                0.488602511902920, 1.092548430592079, 1.092548430592079,
                                                0.315391565252520, 1.092548430592079, 0.546274215296040};
constexpr std::array<double, 9> kCosineLobe = {kPi,       2.0 * kPi / 3.0, 2.0 * kPi / 3.0, 2.0 * kPi / 3.0, kPi / 4.0,
                                               kPi / 4.0, kPi / 4.0,       kPi / 4.0,       kPi / 4.0};

}  // namespace

glm::vec3 equirectDirection(glm::vec2 uv) {
    double phi = 2.0 * kPi * (double(uv.x) - 0.5), theta = kPi * double(uv.y);
    return glm::vec3(float(std::sin(theta) * std::sin(phi)), float(std::cos(theta)),
                     float(-std::sin(theta) * std::cos(phi)));
}

glm::vec2 equirectUv(const glm::vec3& d) {
    double phi = std::atan2(double(d.x), double(-d.z));
    double theta = std::acos(std::clamp(double(d.y), -1.0, 1.0));
    return glm::vec2(float(phi / (2.0 * kPi) + 0.5), float(theta / kPi));
}

// Each texel is constant over its patch of the sphere. A coarse map (the 1x1 constant environment) is integrated
// over sub-samples of each texel, at least kMinRows x 2 kMinRows over the sphere: a texel's centre direction alone
// would stand for its whole patch (one horizon direction for the 1x1 map, which made a floor's E 0.589 pi L).
// Each sub-row weighs its exact solid angle dPhi (cos t0 - cos t1).
ShIrradiance projectIrradianceSh(const core::ImageRgba32f& img) {
    constexpr uint32_t kMinRows = 128;
    const uint32_t subY = (kMinRows + img.height - 1) / img.height, subX = (2 * kMinRows + img.width - 1) / img.width;
    const uint32_t rows = img.height * subY, cols = img.width * subX;
    const double dPhi = 2.0 * kPi / cols, dTheta = kPi / rows;
    std::array<glm::dvec3, 9> sum{};
    for (uint32_t y = 0; y < rows; ++y) {
        double theta = (y + 0.5) * dTheta;
        double solidAngle = dPhi * (std::cos(y * dTheta) - std::cos((y + 1) * dTheta));
        for (uint32_t x = 0; x < cols; ++x) {
            double phi = 2.0 * kPi * ((x + 0.5) / cols - 0.5);
            glm::dvec3 d(std::sin(theta) * std::sin(phi), std::cos(theta), -std::sin(theta) * std::cos(phi));
            const float* p = &img.pixels[(size_t(y / subY) * img.width + x / subX) * 4];
            glm::dvec3 radiance(p[0], p[1], p[2]);
            std::array<double, 9> poly = shPolynomials(d);
            for (int k = 0; k < 9; ++k) sum[k] += radiance * (poly[k] * kShConstants[k] * solidAngle);
        }
    }
    ShIrradiance sh{};
    // E(n) = sum_k A_l(k) L_k Y_k(n) = sum_k (A_l L_k c_k) poly_k(n)
    for (int k = 0; k < 9; ++k) sh[k] = glm::vec3(sum[k] * (kCosineLobe[k] * kShConstants[k]));
    return sh;
}

glm::vec3 evaluateIrradianceSh(const ShIrradiance& sh, const glm::vec3& n) {
    std::array<double, 9> poly = shPolynomials(glm::dvec3(n));
    glm::dvec3 e(0.0);
    for (int k = 0; k < 9; ++k) e += glm::dvec3(sh[k]) * poly[k];
    return glm::max(glm::vec3(e), glm::vec3(0.0f));
}

std::vector<core::ImageRgba32f> buildMipChain(core::ImageRgba32f level0) {
    std::vector<core::ImageRgba32f> mips;
    mips.push_back(std::move(level0));
    while (mips.back().width > 1 || mips.back().height > 1) {
        const core::ImageRgba32f& src = mips.back();
        core::ImageRgba32f dst;
        dst.width = std::max(1u, src.width / 2);
        dst.height = std::max(1u, src.height / 2);
        dst.pixels.assign(size_t(dst.width) * dst.height * 4, 0.0f);
        uint32_t fx = src.width > 1 ? 2 : 1, fy = src.height > 1 ? 2 : 1;
        for (uint32_t y = 0; y < dst.height; ++y)
            for (uint32_t x = 0; x < dst.width; ++x)
                for (uint32_t sy = 0; sy < fy; ++sy)
                    for (uint32_t sx = 0; sx < fx; ++sx)
                        for (int c = 0; c < 4; ++c)
                            dst.pixels[(size_t(y) * dst.width + x) * 4 + c] +=
                                src.pixels[(size_t(y * fy + sy) * src.width + x * fx + sx) * 4 + c] / float(fx * fy);
        mips.push_back(std::move(dst));
    }
    return mips;
}

std::filesystem::path defaultEnvironmentPath() {
    if (const char* env = std::getenv("IDK_ENVIRONMENT")) return env;
    // shaders_glsl/ -> repository root -> ../shared/environments
    return std::filesystem::path(shaders::kShaderSourceDir).parent_path().parent_path() / "shared" / "environments" /
           "snow_field_puresky_1k.hdr";
}

GpuEnvironment createEnvironment(vk::Context& ctx, const std::filesystem::path& file, glm::vec3 constant) {
    core::ImageRgba32f level0;
    if (file.empty()) {
        level0 = {1, 1, {constant.r, constant.g, constant.b, 1.0f}};
    } else {
        level0 = core::readImage(file);
    }
    return createEnvironment(ctx, std::move(level0),
                             file.empty() ? "constant environment" : "environment " + file.filename().string());
}

GpuEnvironment createEnvironment(vk::Context& ctx, core::ImageRgba32f level0, const std::string& name) {
    for (float& v : level0.pixels) v = std::isfinite(v) ? std::clamp(v, 0.0f, 65504.0f) : 0.0f;  // half range
    GpuEnvironment env;
    env.irradianceSh = projectIrradianceSh(level0);
    std::vector<core::ImageRgba32f> mips = buildMipChain(std::move(level0));
    env.width = float(mips[0].width);
    env.height = float(mips[0].height);
    env.maxLod = float(mips.size() - 1);

    vk::ImageDesc desc;
    desc.format = VK_FORMAT_R16G16B16A16_SFLOAT;
    desc.extent = {mips[0].width, mips[0].height, 1};
    desc.mipLevels = uint32_t(mips.size());
    desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT;
    desc.name = name;
    desc.category = "environment";
    env.image = ctx.createImage(desc);

    // All mips in one staging buffer as half floats, copied in one submission.
    std::vector<uint16_t> halves;
    std::vector<VkBufferImageCopy> copies;
    for (uint32_t level = 0; level < mips.size(); ++level) {
        VkBufferImageCopy copy{};
        copy.bufferOffset = halves.size() * sizeof(uint16_t);
        copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, level, 0, 1};
        copy.imageExtent = {mips[level].width, mips[level].height, 1};
        copies.push_back(copy);
        for (float v : mips[level].pixels) halves.push_back(glm::packHalf1x16(v));
    }
    vk::BufferDesc stagingDesc;
    stagingDesc.size = halves.size() * sizeof(uint16_t);
    stagingDesc.usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
    stagingDesc.memory = vk::MemoryUsage::Upload;
    stagingDesc.name = "environment staging";
    stagingDesc.category = "staging";
    vk::Buffer staging = ctx.createBuffer(stagingDesc);
    vk::uploadBuffer(ctx, staging, halves.data(), stagingDesc.size);  // mapped: a memcpy (+ flush if needed)
    ctx.runImmediate([&](VkCommandBuffer cmd) {
        vk::transitionImage(cmd, env.image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
        vkCmdCopyBufferToImage(cmd, staging.buffer, env.image.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                               uint32_t(copies.size()), copies.data());
        vk::transitionImage(cmd, env.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                            VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    });
    ctx.destroy(staging);

    env.texture = ctx.bindless().addSampled(env.image.view);
    vk::SamplerDesc sampler;  // linear, mip linear, repeat; v is clamped in include/environment.glsl
    env.sampler = ctx.bindless().addSampler(sampler);
    return env;
}

void destroyEnvironment(vk::Context& ctx, GpuEnvironment& env) {
    if (!env.image) return;
    ctx.bindless().release(env.texture);
    ctx.bindless().release(env.sampler);
    ctx.destroyDeferred(env.image);
    env = {};
}

}  // namespace idk::render
