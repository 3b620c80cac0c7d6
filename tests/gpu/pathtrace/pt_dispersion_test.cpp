// pt_dispersion_test.cpp: KHR_materials_dispersion in the path tracers (shared/pt_dispersion.h). The camera looks
// through a smooth dispersive glass interface tilted by 40 degrees (a thick material: the rays refract into the
// volume behind it) at a small white emitter inside: each channel sees the emitter where Snell's law at that
// channel's IOR puts it. The CPU reference's per-channel image centroids agree with a CPU Snell trace of the pixel
// centres (within 0.6 px) and come out separated in the order of the IORs (red bends least);
// the GPU gives the CPU's samples at the same seed (90% of the pixels within 1e-3, means within 1%); with dispersion 0
// the channels coincide (one IOR) and the GPU equals the CPU.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstdio>

#include "conformance/quad_scene.hpp"
#include "gpu/pathtrace/pt_image_util.hpp"
#include "pathtrace/cpu_path_tracer.hpp"
#include "pathtrace/pt_scene.hpp"
#include "support/gpu_fixture.hpp"
#include "support/dispersion_prism.hpp"
#include "support/same_pixels.hpp"

namespace idk::test {
namespace {

constexpr uint32_t kSize = 64;
constexpr float kDispersion = 4.0f;  // Abbe number 5: strong, so the channels land pixels apart

class PtDispersionTest : public GpuTest {};

double emitterX();

scene::Scene prismScene(float dispersion) {
    scene::Scene s = prismQuads(dispersion);
    s.materials[0].thickness = 1.0f;  // a volume: the camera's rays refract into it
    const glm::mat4 place = glm::translate(glm::mat4(1.0f), glm::vec3(float(emitterX()), 0.0f, kPrismEmitterZ));
    s.nodes[1].world = place;
    s.nodes[1].matrix = place;
    s.instances[1].world = place;
    return s;
}

scene::CameraView camera() {
    scene::CameraView c;
    c.position = glm::vec3(0.0f, 0.0f, kPrismCameraZ);
    c.yfov = kPrismFov;
    return c;
}

pathtrace::PtSettings settings() {
    pathtrace::PtSettings s;
    s.spp = 24;
    s.seed = 5;
    s.maxDepth = 3;
    s.rouletteDepth = 3;
    s.nee = true;
    return s;
}

// The emitter sits where the optical axis lands at the d line's IOR (the green channel's image centre).
double emitterX() { return prismLanding(glm::dvec3(0.0, 0.0, -1.0), kPrismIor).x; }

// Whether a pixel centre's ray, refracted at IOR n, meets the emitter.
bool snellHitsEmitter(uint32_t px, uint32_t py, double n) {
    const double t = std::tan(0.5 * kPrismFov);
    const glm::dvec3 d = glm::normalize(glm::dvec3((2.0 * (px + 0.5) / kSize - 1.0) * t,
                                                   (1.0 - 2.0 * (py + 0.5) / kSize) * t, -1.0));
    const glm::dvec3 q = prismLanding(d, n);
    return std::abs(q.x - emitterX()) < kPrismEmitterHalf && std::abs(q.y) < kPrismEmitterHalf;
}

double centroidX(const core::ImageRgba32f& img, int c) { return channelCentroidX(img, kSize, c); }

TEST_F(PtDispersionTest, ChannelsSeparateAsSnellSaysAndGpuEqualsCpu) {
    const scene::Scene sc = prismScene(kDispersion);
    const pathtrace::PathTraceScene pts = pathtrace::buildPathTraceScene(sc, nullptr, 1.0f, glm::vec3(0.0f));
    const core::ImageRgba32f cpu = pathtrace::renderReference(pts, camera(), kSize, kSize, settings());
    double rendered[3], oracle[3];
    for (int c = 0; c < 3; ++c) {
        const double lambda[3] = {656.3, 587.6, 486.1};  // the Fraunhofer C, d, F lines (nm)
        const double n =
            kPrismIor + (kPrismIor - 1.0) * kDispersion / 20.0 * (523655.0 / (lambda[c] * lambda[c]) - 1.5168);
        double sum = 0.0, count = 0.0;
        for (uint32_t y = 0; y < kSize; ++y)
            for (uint32_t x = 0; x < kSize; ++x)
                if (snellHitsEmitter(x, y, n)) {
                    sum += x + 0.5;
                    count += 1.0;
                }
        ASSERT_GT(count, 4.0) << "channel " << c << " misses the emitter";
        oracle[c] = sum / count;
        rendered[c] = centroidX(cpu, c);
        std::printf("channel %d (IOR %.4f): emitter image centroid x %.2f px, Snell trace %.2f px (%g pixels)\n", c,
                    n, rendered[c], oracle[c], count);
        EXPECT_NEAR(rendered[c], oracle[c], 0.6) << "channel " << c;
    }
    // Refraction turns the rays toward -x (toward the interface's inward normal). Red bends least, so a red ray
    // lands farther toward +x than a green one from the same pixel: to reach the emitter (on the green axis ray)
    // red must leave from pixels farther toward -x, blue from pixels toward +x. The channels are pixels apart.
    EXPECT_LT(oracle[0], oracle[1]);
    EXPECT_LT(oracle[1], oracle[2]);
    EXPECT_LT(rendered[0], rendered[1]);
    EXPECT_LT(rendered[1], rendered[2]);
    EXPECT_GT(rendered[2] - rendered[0], 2.0);

    expectGpuDrawsTheCpuSamples(ctx(), shaders(), sc, pts, camera(), kSize, settings(), cpu, "dispersive prism");

    // Dispersion 0: one IOR, every channel sees the emitter at the same place, GPU = CPU. (The tracers skip the
    // channel pick and the IOR change entirely then: no sample drawn, the same code path as before the extension.)
    const scene::Scene off = prismScene(0.0f);
    const pathtrace::PathTraceScene offPts = pathtrace::buildPathTraceScene(off, nullptr, 1.0f, glm::vec3(0.0f));
    render::PathTracerOptions options;
    options.traversal = render::PtTraversal::Bvh;
    render::PathTracer offTracer(ctx(), shaders(), off, offPts, options);
    const core::ImageRgba32f a = offTracer.render(camera(), kSize, kSize, settings()).image;
    const core::ImageRgba32f cpuOff = pathtrace::renderReference(offPts, camera(), kSize, kSize, settings());
    std::printf("dispersion 0: centroids R %.3f G %.3f B %.3f px\n", centroidX(cpuOff, 0), centroidX(cpuOff, 1),
                centroidX(cpuOff, 2));
    EXPECT_NEAR(centroidX(cpuOff, 0), centroidX(cpuOff, 2), 0.05);
    EXPECT_GT(samePixelFraction(a, cpuOff), 0.9);
}

}  // namespace
}  // namespace idk::test
