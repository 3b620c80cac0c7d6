// features.cpp: the capability-ladder table. Each ladder lists its rungs best-first; the first available one
// is chosen. The GL-interop rung needs both VK_KHR_external_memory_fd and an OpenGL context exposing the NV
// extension the pass uses; the feature that owns that pass probes GL, so here it reports what it needs.
#include "vk/features.hpp"

namespace idk::vk {

const char* rungName(Rung rung) {
    switch (rung) {
        case Rung::Native: return "native";
        case Rung::GlInterop: return "gl-interop";
        case Rung::Fallback: return "fallback";
    }
    return "?";
}

namespace {

Ladder choose(std::string feature, std::vector<RungOption> options, bool forceFallback) {
    Ladder ladder{std::move(feature), std::move(options), Rung::Fallback, {}};
    for (const RungOption& option : ladder.options) {
        bool isLast = &option == &ladder.options.back();
        if ((option.available && !forceFallback) || isLast) {
            ladder.chosen = option.rung;
            ladder.chosenMechanism = option.mechanism;
            break;
        }
    }
    return ladder;
}

std::string missing(bool available, const char* what) { return available ? "" : std::string("device lacks ") + what; }

}  // namespace

std::vector<Ladder> buildLadders(const DeviceCapabilities& c, bool forceFallback) {
    std::vector<Ladder> ladders;
    ladders.push_back(choose("mesh shading",
        {{Rung::Native, "VK_EXT_mesh_shader", c.meshShaderExt, missing(c.meshShaderExt, "VK_EXT_mesh_shader")},
         {Rung::Fallback, "multi-draw-indirect with count", true, ""}},
        forceFallback));
    ladders.push_back(choose("variable-rate shading",
        {{Rung::Native, "VK_KHR_fragment_shading_rate", c.fragmentShadingRate,
          missing(c.fragmentShadingRate, "VK_KHR_fragment_shading_rate")},
         {Rung::Fallback, "compute-side coarse shading", true, ""}},
        forceFallback));
    ladders.push_back(choose("voxel radiance atomics (VXGI)",
        {{Rung::Native, "float32 image atomic add", c.imageFloat32AtomicAdd,
          missing(c.imageFloat32AtomicAdd, "shaderImageFloat32AtomicAdd")},
         {Rung::GlInterop, "GL_NV_shader_atomic_fp16_vector via GL_EXT_memory_object_fd", false,
          c.externalMemoryFd ? "needs an OpenGL context with GL_NV_shader_atomic_fp16_vector"
                             : "device lacks VK_KHR_external_memory_fd"},
         {Rung::Fallback, "three r32ui images + merge", true, ""}},
        forceFallback));
    ladders.push_back(choose("conservative rasterization (voxelization)",
        {{Rung::Native, "VK_EXT_conservative_rasterization", c.conservativeRasterization,
          missing(c.conservativeRasterization, "VK_EXT_conservative_rasterization")},
         {Rung::Fallback, "geometry-shader triangle dilation", c.geometryShader,
          missing(c.geometryShader, "geometryShader")}},
        forceFallback));
    ladders.push_back(choose("point-shadow cube faces",
        {{Rung::Native, "vertex-shader gl_Layer (one instanced draw)", c.shaderOutputLayer,
          missing(c.shaderOutputLayer, "shaderOutputLayer")},
         {Rung::Fallback, "six draws, one per face", true, ""}},
        forceFallback));
    ladders.push_back(choose("ray traversal",
        {{Rung::Native, "VK_KHR_ray_query", c.rayQuery, missing(c.rayQuery, "VK_KHR_ray_query")},
         {Rung::Fallback, "compute BVH traversal", true, ""}},
        forceFallback));
    return ladders;
}

}  // namespace idk::vk
