// frame_checks.cpp: property checks on HDR frames of the deferred renderer (finiteness, coverage against the
// projected bounds, radiance statistics); see frame_checks.hpp. Test support, no IDKEngine counterpart.
#include "support/frame_checks.hpp"

#include <algorithm>
#include <cmath>

namespace idk::test {

FrameStats analyzeFrame(const core::ImageRgba32f& hdr, const scene::Aabb& bounds, const glm::mat4& viewProjection) {
    FrameStats s;
    const double w = hdr.width, h = hdr.height;
    double minX = w, minY = h, maxX = 0, maxY = 0;
    bool behind = false;
    for (int c = 0; c < 8; ++c) {
        glm::vec3 corner((c & 1) ? bounds.max.x : bounds.min.x, (c & 2) ? bounds.max.y : bounds.min.y,
                         (c & 4) ? bounds.max.z : bounds.min.z);
        glm::vec4 clip = viewProjection * glm::vec4(corner, 1.0f);
        if (clip.w <= 0.0f) {
            behind = true;
            continue;
        }
        double x = (clip.x / clip.w * 0.5 + 0.5) * w, y = (clip.y / clip.w * 0.5 + 0.5) * h;
        minX = std::min(minX, x);
        maxX = std::max(maxX, x);
        minY = std::min(minY, y);
        maxY = std::max(maxY, y);
    }
    if (behind) minX = minY = 0, maxX = w, maxY = h;
    double sum = 0.0;
    for (uint32_t py = 0; py < hdr.height; ++py) {
        for (uint32_t px = 0; px < hdr.width; ++px) {
            const float* p = &hdr.pixels[(size_t(py) * hdr.width + px) * 4];
            double cx = px + 0.5, cy = py + 0.5;
            bool inBounds = cx >= minX && cx <= maxX && cy >= minY && cy <= maxY;
            bool inGrown = cx >= minX - 1 && cx <= maxX + 1 && cy >= minY - 1 && cy <= maxY + 1;
            s.boundsPixels += inBounds;
            for (int c = 0; c < 4; ++c) {
                s.nonFinite += !std::isfinite(p[c]);
                s.negative += p[c] < 0.0f;
            }
            if (p[3] != 1.0f) continue;
            ++s.geometry;
            s.outsideBounds += !inGrown;
            s.maxGeometryRadiance = std::max({s.maxGeometryRadiance, double(p[0]), double(p[1]), double(p[2])});
            sum += (double(p[0]) + p[1] + p[2]) / 3.0;
        }
    }
    s.meanGeometryRadiance = s.geometry ? sum / double(s.geometry) : 0.0;
    return s;
}

}  // namespace idk::test
