// hiz_levels.cpp: the sampler rung's sampler and level images (see hiz_levels.hpp).
#include "frame/hiz_levels.hpp"

#include <string>

#include "shared/depth_pyramid.h"

namespace idk::frame {

void HizLevels::releaseImages() {
    for (size_t i = 0; i < images_.size(); ++i) {
        ctx_.bindless().release(sampled_[i]);
        ctx_.destroyDeferred(images_[i]);
    }
    images_.clear();
    sampled_.clear();
    resources_.levels.clear();
    size_ = glm::uvec2(0);
}

void HizLevels::release() {
    releaseImages();
    if (sampler_.value != UINT32_MAX) ctx_.bindless().release(sampler_);
    sampler_ = {};
}

const passes::HizMinmaxResources* HizLevels::forSize(glm::uvec2 size) {
    if (sampler_.value == UINT32_MAX) {
        // One bilinear footprint of 2 x 2 texels reduced to their maximum (VK_EXT_sampler_filter_minmax).
        vk::SamplerDesc max;
        max.filter = VK_FILTER_LINEAR;
        max.mipmap = VK_SAMPLER_MIPMAP_MODE_NEAREST;
        max.address = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
        max.reduction = VK_SAMPLER_REDUCTION_MODE_MAX;
        sampler_ = ctx_.bindless().addSampler(max);
        resources_.sampler = sampler_.value;
    }
    if (size == size_) return &resources_;
    releaseImages();
    for (uint32_t level = 0; level < gpu::hizLevelCount(size); ++level) {
        const glm::uvec2 s = gpu::hizLevelSize(size, level);
        vk::ImageDesc desc;
        desc.format = VK_FORMAT_R32_SFLOAT;
        desc.extent = {s.x, s.y, 1};
        desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
        desc.name = "hiz level " + std::to_string(level);
        desc.category = "culling";
        images_.push_back(ctx_.createImage(desc));
        sampled_.push_back(ctx_.bindless().addSampled(images_.back().view));
        resources_.levels.push_back({images_.back().image, sampled_.back().value});
    }
    size_ = size;
    return &resources_;
}

}  // namespace idk::frame
