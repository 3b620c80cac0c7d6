// bloom_feature.cpp: adds the bloom passes when --bloom is on.
#include "frame/bloom_feature.hpp"

#include "passes/bloom.hpp"

namespace idk::frame {

void BloomFeature::addPasses(FrameContext& f) {
    const BloomSettings& s = f.settings.bloom;
    if (!s.enabled || s.strength <= 0.0f) return;
    f.hdr = passes::addBloomPasses(f.graph, f.ctx, f.shaders, f.hdr, f.width, f.height, {s.strength, s.karis});
}

}  // namespace idk::frame
