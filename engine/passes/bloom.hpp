// bloom.hpp: the bloom passes (bloom.cpp): a 13-tap downsample chain from the HDR image, a tent upsample chain
// back to half resolution, and an energy-conserving blend into the HDR image.
#pragma once
#include <cstdint>

#include "graph/render_graph.hpp"
#include "vk/context.hpp"
#include "vk/shader_library.hpp"

namespace idk::passes {

struct BloomParams {
    float strength = 0.04f;
    bool karis = true;
};

// Number of half-resolution levels for a width x height image: IDKEngine's max(mips(half size) - 3, 2), capped
// so the smallest level keeps at least one texel.
uint32_t bloomLevels(uint32_t width, uint32_t height);

// Blends the bloom of `hdr` (RGBA16F storage, width x height) into it; returns its new version.
graph::TextureHandle addBloomPasses(graph::RenderGraph& graph, vk::Context& ctx, vk::ShaderLibrary& shaders,
                                    graph::TextureHandle hdr, uint32_t width, uint32_t height,
                                    const BloomParams& params);

}  // namespace idk::passes
