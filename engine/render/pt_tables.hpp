// pt_tables.hpp: the light-transport tables of PT-A's PathTraceScene uploaded unchanged for the GPU tracer: the NEE
// light list and its power alias table, the environment's texel radiance and alias table, and the path-tracing
// material fields (transmission, IOR, volume) with the transmission texture turned into a bindless index.
#pragma once
#include <string>
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

// A device-local storage buffer (category "path tracer", at least 16 bytes) holding `bytes` of `data`, read by
// device address: every table and geometry buffer of the GPU tracer is made by this one function.
vk::Buffer uploadPtBuffer(vk::Context& ctx, const void* data, size_t bytes, const std::string& name);

}  // namespace idk::render
