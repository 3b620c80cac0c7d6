// renderer.cpp: the frame graph of the foundation renderer: Lambert raster into an imported HDR target that
// the graph leaves ready for the readback copy.
#include "render/renderer.hpp"

#include <glm/gtc/packing.hpp>

#include "passes/passes.hpp"
#include "vk/transfer.hpp"

namespace idk::render {

Renderer::Renderer(vk::Context& ctx, vk::ShaderLibrary& shaders)
    : ctx_(ctx), shaders_(shaders), backend_(ctx), pool_(backend_), frames_(ctx) {}

Renderer::~Renderer() {
    ctx_.waitIdle();
    if (hasScene_) destroyLambertScene(ctx_, scene_);
}

void Renderer::setScene(const scene::Scene& scene) {
    if (hasScene_) destroyLambertScene(ctx_, scene_);
    scene_ = uploadLambertScene(ctx_, packLambertScene(scene));
    hasScene_ = true;
}

FrameResult Renderer::renderOffscreen(const scene::CameraView& camera, uint32_t width, uint32_t height) {
    vk::ImageDesc desc;
    desc.format = VK_FORMAT_R16G16B16A16_SFLOAT;
    desc.extent = {width, height, 1};
    desc.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
    desc.name = "offscreen output";
    desc.category = "render targets";
    vk::Image target = ctx_.createImage(desc);
    struct DestroyOnExit {
        vk::Context& ctx;
        vk::Image& image;
        ~DestroyOnExit() { ctx.destroyDeferred(image); }
    } guard{ctx_, target};

    graph::RenderGraph graph(pool_, {width, height});
    graph::PhysicalTexture physical;
    physical.image = target.image;
    physical.view = target.view;
    physical.format = target.format;
    physical.extent = target.extent;
    graph::TextureHandle output = graph.importTexture("output", physical, graph::ResourceState{},
                                                      graph::FinalUse{graph::Access::TransferSrc});
    passes::LambertSettings settings;
    settings.colorFormat = desc.format;
    float aspect = float(width) / float(height);
    settings.viewProjection = scene::projectionMatrix(camera, aspect) * scene::viewMatrix(camera);
    passes::LambertOutputs lambert = passes::addLambertPass(graph, ctx_, shaders_, scene_, output, settings);
    graph.markOutput(lambert.color);
    graph.compile();

    FrameResult result;
    result.passesRun = graph.executionOrder();
    result.graphText = graph.toText();
    result.graphDot = graph.toGraphviz();
    VkCommandBuffer cmd = frames_.begin();
    graph.execute(cmd);
    ctx_.waitFor(frames_.end());
    result.passTimes = backend_.passTimings();

    std::vector<uint8_t> bytes = vk::readbackImage(ctx_, target, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    const auto* halves = reinterpret_cast<const uint16_t*>(bytes.data());
    result.image.width = width;
    result.image.height = height;
    result.image.pixels.resize(size_t(width) * height * 4);
    for (size_t i = 0; i < result.image.pixels.size(); ++i) result.image.pixels[i] = glm::unpackHalf1x16(halves[i]);
    return result;
}

}  // namespace idk::render
