// bloom_feature.hpp: the "CoD" bloom (passes/bloom.cpp) blended into the lit HDR image before tonemapping, after
// TAA (as in IDKEngine, where it runs at presentation resolution on the TAA/FSR2 output). Transient images only;
// nothing is created while --bloom is off.
#pragma once
#include "frame/frame_context.hpp"

namespace idk::frame {

class BloomFeature {
public:
    void addPasses(FrameContext& f);  // blends into f.hdr
};

}  // namespace idk::frame
