// pt_tables.hpp: the light-transport tables of PT-A's PathTraceScene uploaded unchanged for the GPU tracer: the NEE
// light list and its power alias table, the environment's texel radiance and alias table, and the path-tracing
// material fields (transmission, IOR, volume) with the transmission texture turned into a bindless index.
#pragma once
#include <vector>

#include "pathtrace/pt_scene.hpp"
#include "shared/pt_wavefront.h"
#include "vk/resources.hpp"

namespace idk::vk {
class Context;
}  // namespace idk::vk

namespace idk::render {

// Bindless slots of one scene texture (from the texture streamer); UINT32_MAX when it has none.
struct PtTextureBinding {
    uint32_t texture = UINT32_MAX;
    uint32_t sampler = UINT32_MAX;
};

struct PtTables {
    gpu::GpuPtSceneDesc desc{};  // the table addresses and counts (geometry and material fields left 0)
    std::vector<vk::Buffer> buffers;
};

// `textures`: per Scene::textures entry. `white`: a 1x1 white texture + sampler for materials without one.
PtTables uploadPtTables(vk::Context& ctx, const pathtrace::PathTraceScene& pts,
                        const std::vector<PtTextureBinding>& textures, PtTextureBinding white);
void destroyPtTables(vk::Context& ctx, PtTables& tables);

}  // namespace idk::render
