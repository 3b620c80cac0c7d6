// ssao_oracle.hpp: the exact reference of SSAO (frame/ssao_feature.hpp): ambient visibility computed on the CPU with
// rays through our BVH from the surface points of the same G-buffer (SsaoFeature's captured depth and normals):
// per pixel, `rays` cosine-distributed rays of the SSAO radius; visibility = the fraction that escape. Compared
// with SSAO's visibility over the geometry pixels. Used by tests/gpu/temporal/ssao_test.cpp and the benchmark.
#pragma once
#include <cstdint>
#include <vector>

#include "scene/camera.hpp"
#include "scene/scene.hpp"

namespace idk::frame {

struct AoComparison {
    size_t pixels = 0;                       // geometry pixels compared
    double meanSsao = 0.0, meanTraced = 0.0;  // mean visibility of each
    double mae = 0.0;                        // mean |SSAO - traced|
    double maeConstant = 0.0;                // the best constant guess's (the traced mean)
    double correlation = 0.0;                // Pearson correlation of SSAO and traced visibility
};

// `planes`: SsaoFeature::captured() of a width x height frame of `scene` seen from `camera`.
AoComparison compareWithTracedAo(const scene::Scene& scene, const scene::CameraView& camera, uint32_t width,
                                 uint32_t height, const std::vector<uint32_t>& planes, float radius, int rays,
                                 uint32_t seed);

}  // namespace idk::frame
