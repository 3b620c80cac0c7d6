// blend_draws.hpp: the BLEND draws of the GPU scene in back-to-front order, sorted on the CPU every frame by the
// distance from the eye to each draw's world-box centre, written as a second indirect buffer (one per frame slot,
// host-visible, category "transparency") whose commands name their instance in firstInstance. Exists only for
// scenes with BLEND draws. Ports IDKEngine's transparent draw list (reference 2.14), sorted instead of a k-buffer.
#pragma once
#include <vector>

#include "render/gpu_scene.hpp"
#include "vk/resources.hpp"

namespace idk::render {

// Which forward draws: BLEND materials (the transparency pass) or transmissive non-BLEND ones (drawnByTransmission,
// the screen-space transmission pass), sorted alike.
enum class ForwardDraws : uint8_t { Blend, Transmission };

// The BLEND draws of `scene` (material alphaMode BLEND), farthest first: each the scene's command with
// instanceCount 1 and firstInstance = its draw index. Ties keep the draw order (stable sort).
std::vector<VkDrawIndexedIndirectCommand> sortBlendDraws(const GpuSceneData& scene,
                                                         const std::vector<scene::Aabb>& meshBoxes, glm::vec3 eye,
                                                         ForwardDraws kind = ForwardDraws::Blend);

class BlendDraws {
public:
    BlendDraws(vk::Context& ctx, const GpuSceneData& scene, uint32_t framesInFlight,
               ForwardDraws kind = ForwardDraws::Blend);
    ~BlendDraws();
    BlendDraws(const BlendDraws&) = delete;
    BlendDraws& operator=(const BlendDraws&) = delete;

    uint32_t count() const noexcept { return count_; }
    // Sorts for `eye` into frame slot `slot`'s buffer (the slot's previous frame has completed) and returns it.
    const vk::Buffer& sort(uint32_t slot, const GpuSceneData& scene, glm::vec3 eye);

private:
    vk::Context& ctx_;
    ForwardDraws kind_;
    std::vector<scene::Aabb> meshBoxes_;
    uint32_t count_ = 0;
    std::vector<vk::Buffer> slots_;
};

// Number of draws the transparency pass would draw (0: no pass, no buffers).
uint32_t blendDrawCount(const GpuSceneData& scene, ForwardDraws kind = ForwardDraws::Blend);

}  // namespace idk::render
