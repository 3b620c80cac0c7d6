// ssr_feature.hpp: screen-space reflections (passes/ssr.cpp). addPasses marches each smooth pixel's mirror ray
// through a closest-depth Hi-Z pyramid of the G-buffer before deferred lighting, which applies the hits as its
// specular ambient term (FrameContext::reflections); keepLitImage copies the frame's lit image into graph history
// for the next frame's hits. Hits sample LAST frame's lit image, reprojected: the current one is what deferred
// lighting is about to write, so using it would need a second lighting pass (IDKEngine adds SSR after lighting
// instead, which cannot weight it by the BRDF in place of the environment term). A still render therefore runs
// two frames with SSR on (Renderer::renderStill). Nothing is created while --ssr is off.
#pragma once
#include <glm/glm.hpp>

#include "frame/frame_context.hpp"

namespace idk::frame {

class SsrFeature {
public:
    void addPasses(FrameContext& f);     // f.reflections
    void keepLitImage(FrameContext& f);  // f.hdr into the next frame's history

private:
    bool havePrevious_ = false;
    glm::mat4 previous_{1.0f};  // last frame's (jittered) view-projection: the matrix its lit image was seen with
    uint32_t previousWidth_ = 0, previousHeight_ = 0;
};

}  // namespace idk::frame
