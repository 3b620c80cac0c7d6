// renderer.hpp: renders one frame of a scene into an offscreen image and reads it back (the headless path of
// `idk render` and of the GPU tests). Builds the frame's render graph, executes it in a frame slot, waits,
// and returns linear HDR pixels with the passes that ran and their GPU times.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "core/image_file.hpp"
#include "graph/resource_pool.hpp"
#include "render/lambert_scene.hpp"
#include "render/vk_graph_backend.hpp"
#include "scene/camera.hpp"
#include "vk/frames.hpp"
#include "vk/shader_library.hpp"

namespace idk::render {

struct FrameResult {
    core::ImageRgba32f image;
    std::vector<std::string> passesRun;     // execution order after culling
    std::vector<vk::ScopeTiming> passTimes;  // GPU time per pass
    std::string graphText;                   // RenderGraph::toText() of the frame
    std::string graphDot;                    // RenderGraph::toGraphviz() of the frame
};

class Renderer {
public:
    Renderer(vk::Context& ctx, vk::ShaderLibrary& shaders);
    ~Renderer();

    void setScene(const scene::Scene& scene);  // packs and uploads; replaces the previous scene
    FrameResult renderOffscreen(const scene::CameraView& camera, uint32_t width, uint32_t height);

private:
    vk::Context& ctx_;
    vk::ShaderLibrary& shaders_;
    VkGraphBackend backend_;
    graph::ResourcePool pool_;
    vk::FrameRing frames_;
    GpuLambertScene scene_;
    bool hasScene_ = false;
};

}  // namespace idk::render
