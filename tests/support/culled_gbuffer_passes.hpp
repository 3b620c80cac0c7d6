// culled_gbuffer_passes.hpp: the passes the default G-buffer runs (--culling hiz, frame/culling_feature.hpp): the
// early phase (last frame's visible draws), the Hi-Z pyramid of its depth, the late phase over it, the counters'
// copy. The final depth pyramid is pruned by the graph when no later pass reads it. Pass-list tests splice this
// where the single "gbuffer" pass of --culling off used to be.
#pragma once
#include <string>
#include <vector>

namespace idk::test {

inline std::vector<std::string> withCulledGBuffer(std::vector<std::string> before, std::vector<std::string> after) {
    for (const char* p : {"cull_reset_early", "cull_early", "gbuffer", "depth_pyramid_early", "cull_reset_late",
                          "cull_late", "gbuffer_late", "cull_stats"})
        before.push_back(p);
    before.insert(before.end(), after.begin(), after.end());
    return before;
}

}  // namespace idk::test
