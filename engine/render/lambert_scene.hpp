// lambert_scene.hpp: the scene as the minimal Lambert rasterizer sees it: every instanced triangle expanded to
// world-space vertices (non-indexed), one albedo/emission per material, and the point lights. The CPU packing
// is a pure function (unit-tested); GpuLambertScene uploads it and registers the buffers as bindless.
#pragma once
#include <vector>

#include "scene/scene.hpp"
#include "shared/lambert_types.h"
#include "vk/bindless.hpp"
#include "vk/resources.hpp"

namespace idk::vk { class Context; }

namespace idk::render {

struct LambertSceneData {
    std::vector<gpu::GpuLambertVertex> vertices;    // 3 per triangle, world space
    std::vector<gpu::GpuLambertMaterial> materials; // scene materials, then one default material last
    std::vector<gpu::GpuLambertLight> lights;       // point and spot lights (spots as points), at most kLambertMaxLights
};

LambertSceneData packLambertScene(const scene::Scene& scene);

struct GpuLambertScene {
    vk::Buffer vertices, materials, lights;
    vk::StorageBufferIndex vertexIndex, materialIndex, lightIndex;
    uint32_t vertexCount = 0;
    uint32_t lightCount = 0;
};

GpuLambertScene uploadLambertScene(vk::Context& ctx, const LambertSceneData& data);
void destroyLambertScene(vk::Context& ctx, GpuLambertScene& scene);

}  // namespace idk::render
