// hiz_levels.hpp: what the sampler rung of the ladder "hiz-reduction" needs (passes/depth_pyramid_minmax.cpp): the
// MAX-reduction sampler and one R32F image per pyramid level for the frame size, kept between frames and re-created
// when the size changes. Created only when GPU culling builds pyramids on that rung.
#pragma once
#include <vector>

#include "passes/culling.hpp"
#include "vk/bindless.hpp"

namespace idk::frame {

class HizLevels {
public:
    explicit HizLevels(vk::Context& ctx) : ctx_(ctx) {}
    ~HizLevels() { release(); }
    HizLevels(const HizLevels&) = delete;
    HizLevels& operator=(const HizLevels&) = delete;

    // The sampler and level images for `size` (created or re-created as needed); valid until the next call.
    const passes::HizMinmaxResources* forSize(glm::uvec2 size);
    void release();

private:
    void releaseImages();
    vk::Context& ctx_;
    vk::SamplerIndex sampler_;
    glm::uvec2 size_{0};
    std::vector<vk::Image> images_;
    std::vector<vk::SampledIndex> sampled_;
    passes::HizMinmaxResources resources_;
};

}  // namespace idk::frame
