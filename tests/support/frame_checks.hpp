// frame_checks.hpp: property checks on whole HDR frames of the deferred renderer: finiteness, the coverage mask
// (HDR alpha: 1 geometry, 0 sky) against the scene's projected bounds, and radiance statistics.
#pragma once
#include <glm/glm.hpp>

#include "core/image_file.hpp"
#include "scene/scene.hpp"

namespace idk::test {

struct FrameStats {
    size_t nonFinite = 0;               // NaN/Inf channels
    size_t negative = 0;                // channels below 0
    size_t geometry = 0;                // pixels with alpha 1
    size_t outsideBounds = 0;           // geometry pixels outside the projected bounds rectangle (grown by 1 pixel)
    size_t boundsPixels = 0;            // pixels inside the projected bounds rectangle
    double maxGeometryRadiance = 0.0;   // largest channel over geometry pixels
    double meanGeometryRadiance = 0.0;  // mean of RGB over geometry pixels
    double fill() const { return boundsPixels ? double(geometry) / double(boundsPixels) : 0.0; }
};

// viewProjection maps world to Vulkan clip space (as the renderer's GpuFrame). Bounds corners behind the camera
// make the rectangle the whole image.
FrameStats analyzeFrame(const core::ImageRgba32f& hdr, const scene::Aabb& bounds, const glm::mat4& viewProjection);

}  // namespace idk::test
