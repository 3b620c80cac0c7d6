// ssr_feature.cpp: adds the SSR passes when --ssr is on (see ssr_feature.hpp).
#include "frame/ssr_feature.hpp"

#include "passes/ssr.hpp"

namespace idk::frame {

void SsrFeature::addPasses(FrameContext& f) {
    if (!f.settings.ssr.enabled) {
        havePrevious_ = false;  // switching SSR back on starts without history
        return;
    }
    passes::SsrInputs in;
    in.gbuffer = f.gbuffer;
    in.frame = f.frameConstants;
    in.pyramid = passes::addSsrPyramidPass(f.graph, f.ctx, f.shaders, f.gbuffer.depth, {f.width, f.height});
    in.previousViewProjection = previous_;
    in.havePrevious = havePrevious_ && previousWidth_ == f.width && previousHeight_ == f.height;
    in.maxSteps = f.settings.ssr.maxSteps;
    in.thickness = f.settings.ssr.thickness;
    f.reflections = passes::addSsrTracePass(f.graph, f.ctx, f.shaders, in);
}

void SsrFeature::keepLitImage(FrameContext& f) {
    if (!f.settings.ssr.enabled) return;
    passes::addSsrKeepPass(f.graph, f.ctx, f.shaders, f.hdr);
    previous_ = f.viewProjection;
    previousWidth_ = f.width;
    previousHeight_ = f.height;
    havePrevious_ = true;
}

}  // namespace idk::frame
