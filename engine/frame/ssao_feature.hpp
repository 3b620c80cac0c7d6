// ssao_feature.hpp: screen-space ambient occlusion (passes/ssao.cpp) from the G-buffer's depth and normals, read by
// deferred lighting as a factor of the ambient light (FrameContext::ambientOcclusion). Nothing is created while
// --ssao is off.
#pragma once
#include <vector>

#include "frame/frame_context.hpp"

namespace idk::frame {

class SsaoFeature {
public:
    explicit SsaoFeature(vk::Context& ctx) : ctx_(ctx) {}
    ~SsaoFeature();
    SsaoFeature(const SsaoFeature&) = delete;
    SsaoFeature& operator=(const SsaoFeature&) = delete;

    void addPasses(FrameContext& f);  // f.ambientOcclusion

    // Tests: copy each frame's visibility, depth and normal images into a host-visible buffer; captured() returns
    // the last completed frame's as three planes of width * height 32-bit values (float, float, octahedral uint).
    void capture(bool on) { capture_ = on; }
    std::vector<uint32_t> captured() const;

private:
    vk::Context& ctx_;
    uint32_t frameIndex_ = 0;
    bool capture_ = false;
    vk::Buffer captured_;
    uint32_t capturedPixels_ = 0;
};

}  // namespace idk::frame
