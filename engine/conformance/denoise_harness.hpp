// denoise_harness.hpp: what the denoiser checks (denoise_checks.cpp) and tests (tests/conformance/denoise/) share:
// runs addDenoisePass on the Vulkan device over CPU-made input images (imported into a render graph, result copied
// back by a readback pass), builds the synthetic scene with a known clean image (albedo, normal and depth edges, a
// sky band, seeded noise, optional per-pixel variance), and compares a GPU result with the CPU oracle.
#pragma once
#include <glm/glm.hpp>
#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "conformance/denoise_oracle.hpp"
#include "graph/render_graph.hpp"
#include "passes/denoise.hpp"
#include "render/vk_graph_backend.hpp"
#include "vk/bindless.hpp"
#include "vk/transfer.hpp"

namespace idk::conformance {

// Rounds through half precision, as an RGBA16F image stores the values.
inline std::vector<glm::vec4> roundToHalf(const std::vector<glm::vec4>& v) {
    std::vector<glm::vec4> out(v.size());
    for (size_t i = 0; i < v.size(); ++i)
        for (int c = 0; c < 4; ++c) out[i][c] = glm::unpackHalf1x16(glm::packHalf1x16(v[i][c]));
    return out;
}

// Uploads the inputs (albedo and normal as RGBA16F when halfGuides), denoises on the GPU, reads the result back.
inline std::vector<glm::vec4> denoiseOnGpu(vk::Context& ctx, vk::ShaderLibrary& shaders, const DenoiseImages& in,
                                           const passes::DenoiseSettings& settings, bool halfGuides = false) {
    const VkExtent3D extent{in.width, in.height, 1};
    const size_t count = size_t(in.width) * in.height;
    std::vector<vk::Image> images;
    std::vector<vk::StorageImageIndex> slots;
    auto upload = [&](VkFormat format, const void* data, size_t bytes, const char* name) {
        vk::ImageDesc desc;
        desc.format = format;
        desc.extent = extent;
        desc.usage = VK_IMAGE_USAGE_STORAGE_BIT;
        desc.name = name;
        images.push_back(ctx.createImage(desc));
        vk::uploadImage(ctx, images.back(), data, bytes, VK_IMAGE_LAYOUT_GENERAL);
        slots.push_back(ctx.bindless().addStorage(images.back().view));
    };
    auto uploadRgba = [&](const std::vector<glm::vec4>& v, bool half, const char* name) {
        if (!half) return upload(VK_FORMAT_R32G32B32A32_SFLOAT, v.data(), count * sizeof(glm::vec4), name);
        std::vector<uint16_t> halves(count * 4);
        for (size_t i = 0; i < count; ++i)
            for (int c = 0; c < 4; ++c) halves[i * 4 + c] = glm::packHalf1x16(v[i][c]);
        upload(VK_FORMAT_R16G16B16A16_SFLOAT, halves.data(), halves.size() * sizeof(uint16_t), name);
    };
    uploadRgba(in.color, false, "denoise test color");
    uploadRgba(in.albedo, halfGuides, "denoise test albedo");
    uploadRgba(in.normal, halfGuides, "denoise test normal");
    upload(VK_FORMAT_R32_SFLOAT, in.depth.data(), count * sizeof(float), "denoise test depth");
    if (!in.variance.empty()) upload(VK_FORMAT_R32_SFLOAT, in.variance.data(), count * sizeof(float), "denoise test variance");
    vk::BufferDesc bufferDesc;
    bufferDesc.size = count * sizeof(glm::vec4);
    bufferDesc.memory = vk::MemoryUsage::Readback;
    bufferDesc.name = "denoise test readback";
    vk::Buffer readback = ctx.createBuffer(bufferDesc);
    {
        render::VkGraphBackend backend(ctx);
        graph::ResourcePool pool(backend);
        graph::RenderGraph graph(pool, {in.width, in.height});
        graph::ResourceState general;
        general.layout = VK_IMAGE_LAYOUT_GENERAL;
        graph::TextureHandle handles[5];
        const char* names[5] = {"color", "albedo", "normal", "depth", "variance"};
        for (size_t i = 0; i < images.size(); ++i) {
            graph::PhysicalTexture p;
            p.image = images[i].image;
            p.view = images[i].view;
            p.format = images[i].format;
            p.extent = extent;
            p.storageIndex = slots[i].value;
            handles[i] = graph.importTexture(names[i], p, general);
        }
        graph::TextureHandle denoised = passes::addDenoisePass(
            graph, ctx, shaders, {handles[0], handles[1], handles[2], handles[3], handles[4]}, settings);
        graph::PhysicalBuffer pb;
        pb.buffer = readback.buffer;
        pb.size = readback.size;
        pb.address = readback.address;
        graph::BufferHandle target = graph.importBuffer("readback", pb, graph::ResourceState{});
        auto copied = std::make_shared<graph::BufferHandle>();
        graph.addPass(
            "readback",
            [&](graph::PassBuilder& b) {
                b.read(denoised, graph::Access::TransferSrc);
                *copied = b.write(target, graph::Access::TransferDst);
            },
            [denoised, copied, extent](graph::PassContext& pc) {
                VkBufferImageCopy region{};
                region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
                region.imageExtent = extent;
                vkCmdCopyImageToBuffer(pc.commandBuffer(), pc.image(denoised), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                                       pc.vkBuffer(*copied), 1, &region);
            });
        graph.markOutput(*copied);
        ctx.runImmediate([&](VkCommandBuffer cmd) { graph.execute(cmd); });
        ctx.waitIdle();
    }
    std::vector<glm::vec4> out = vk::downloadBuffer<glm::vec4>(ctx, readback, count);
    ctx.destroy(readback);
    for (vk::StorageImageIndex s : slots) ctx.bindless().release(s);
    for (vk::Image& image : images) ctx.destroy(image);
    return out;
}

// The synthetic scene (width x height, any size >= 48x48): a sky band (rows < height/8: depth inf, normal 0,
// albedo 1), a slanted wall on the left (two albedos, top/bottom: an albedo edge), a wall facing another way on
// the right (a normal edge at x = width/2, continuous depth), and a near box on the right (a depth edge).
// Irradiance varies smoothly. `clean` is albedo * irradiance; `noisy` adds seeded per-channel multiplicative
// Gaussian noise of relative strength `noise` (clamped at 0, like radiance).
struct SyntheticScene {
    DenoiseImages noisy;
    std::vector<glm::vec4> clean;
    std::vector<int> edgeDistance;  // pixels to the nearest albedo / normal / depth / sky edge (capped at 8)
};

inline SyntheticScene makeSyntheticScene(uint32_t width, uint32_t height, float noise, uint32_t seed) {
    SyntheticScene s;
    DenoiseImages& d = s.noisy;
    d.width = width;
    d.height = height;
    const size_t count = size_t(width) * height;
    d.color.resize(count), d.albedo.resize(count), d.normal.resize(count), d.depth.resize(count);
    s.clean.resize(count);
    std::vector<int> region(count);
    const int w = int(width), h = int(height);
    const glm::vec3 tilted = glm::normalize(glm::vec3(0.7f, 0.0f, 0.7f));
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            size_t k = size_t(y) * width + x;
            glm::vec3 albedo(1.0f), normal(0.0f), radiance(0.3f, 0.5f, 1.0f);
            float depth = INFINITY;
            int id = 0;
            float irradiance = 1.0f + 0.5f * std::sin(0.15f * x) * std::cos(0.11f * y);
            if (y >= h / 8) {
                bool box = x >= w * 5 / 8 && x < w * 7 / 8 && y >= h / 2 && y < h * 13 / 16;
                if (box) {
                    albedo = {0.9f, 0.9f, 0.1f}, normal = {0, 0, 1}, depth = 1.5f, id = 1;
                    irradiance *= 2.0f;
                } else if (x < w / 2) {
                    bool top = y < h / 2;
                    albedo = top ? glm::vec3(0.8f, 0.2f, 0.2f) : glm::vec3(0.2f, 0.8f, 0.2f);
                    normal = {0, 0, 1}, depth = 3.0f + 0.01f * float(x), id = top ? 2 : 3;
                } else {
                    albedo = {0.5f, 0.5f, 0.9f}, normal = tilted, depth = 3.0f + 0.01f * float(x), id = 4;
                    irradiance *= 0.4f;
                }
                radiance = albedo * irradiance;
            }
            d.albedo[k] = glm::vec4(albedo, 1.0f);
            d.normal[k] = glm::vec4(normal, 0.0f);
            d.depth[k] = depth;
            s.clean[k] = glm::vec4(radiance, 1.0f);
            region[k] = id;
        }
    std::mt19937 rng(seed);
    std::normal_distribution<float> gauss(0.0f, 1.0f);
    for (size_t k = 0; k < count; ++k) {
        glm::vec3 c = glm::vec3(s.clean[k]);
        if (region[k] != 0)
            for (int i = 0; i < 3; ++i) c[i] = std::fmax(0.0f, c[i] * (1.0f + noise * gauss(rng)));
        d.color[k] = glm::vec4(c, 1.0f);
    }
    s.edgeDistance.assign(count, 8);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int dy = -8; dy <= 8; ++dy)
                for (int dx = -8; dx <= 8; ++dx) {
                    int qx = x + dx, qy = y + dy;
                    if (qx < 0 || qy < 0 || qx >= w || qy >= h) continue;
                    if (region[size_t(qy) * width + qx] == region[size_t(y) * width + x]) continue;
                    int& e = s.edgeDistance[size_t(y) * width + x];
                    e = std::min(e, std::max(std::abs(dx), std::abs(dy)));
                }
    return s;
}

// GPU vs CPU oracle: per channel |gpu - cpu| <= kDenoiseAbs + kDenoiseRel * |cpu|. The two differ by exp/pow
// rounding and FMA contraction only; 5 iterations of weighted means keep that near 1e-6 relative, 1e-4 leaves room.
constexpr float kDenoiseRel = 1e-4f, kDenoiseAbs = 1e-5f;

struct DenoiseDiff {
    float worst = 0.0f;  // largest |gpu - cpu| / (kDenoiseAbs + kDenoiseRel |cpu|): <= 1 passes
    size_t nonFinite = 0;
};
inline DenoiseDiff compareDenoised(const std::vector<glm::vec4>& gpu, const std::vector<glm::vec4>& cpu) {
    DenoiseDiff d;
    for (size_t i = 0; i < gpu.size(); ++i)
        for (int c = 0; c < 4; ++c) {
            if (!std::isfinite(gpu[i][c])) ++d.nonFinite;
            d.worst = std::max(d.worst, std::fabs(gpu[i][c] - cpu[i][c]) / (kDenoiseAbs + kDenoiseRel * std::fabs(cpu[i][c])));
        }
    return d;
}

// The synthetic scene's per-pixel variance input: the luminance variance of its multiplicative noise (relative
// `noise` per channel, independent channels), as the tracer's second moments estimate it; with
// `someUnknown`, unknown (-1) in the first column so that both branches run.
inline void addVariance(SyntheticScene& s, float noise, bool someUnknown) {
    s.noisy.variance.assign(s.clean.size(), 0.0f);
    for (size_t k = 0; k < s.clean.size(); ++k) {
        const glm::vec3 c(s.clean[k]);
        const glm::vec3 w(0.2126f, 0.7152f, 0.0722f);
        const glm::vec3 sd = noise * c * w;
        s.noisy.variance[k] = someUnknown && k % s.noisy.width == 0 ? -1.0f : glm::dot(sd, sd);
    }
}

}  // namespace idk::conformance
