// screen_transmission_test.cpp: the rasterizer's screen-space KHR_materials_transmission (+ _volume, _dispersion)
// pass (passes/transmission.cpp, include/screen_transmission.glsl) against the GPU path tracer, which is exact for
// these cases (smooth glass in front of emitters):
//  * thin-walled: a smooth white transmissive quad (no volume) in front of two emissive panels under a constant
//    environment; the raster's pixels inside the quad match the path tracer's at 256 spp: mean relative error per
//    channel < 3% (measured 0.45%), 95th percentile < 8% (measured 0.8%); transmission 0 renders bit for bit as the material without the extension, and
//    `--transmission off` as the deferred opaque look within 1% of the peak (measured 0.15%: the G-buffer's 8-bit
//    albedo);
//  * volume: three slabs (closed front and back faces in the path tracer, thicknessFactor in the raster) with
//    Beer-Lambert attenuation in front of a white emitter: the mean tint per slab and channel is within 7% of the
//    path tracer's (measured +3.5..4.6%: the raster weights one interface by 1 - F, the path tracer two), and
//    thicker slabs are darker in both, channel by channel;
//  * dispersion: a tilted thick dispersive interface with a small emitter behind it (as pt_dispersion_test): the
//    channels' image centroids come out in the path tracer's order (red, green, blue), separated by the path
//    tracer's spread within 35%, each within 1.5 px of its centroid; with dispersion 0 they coincide (0.02 px);
//  * transmissive surfaces still cast shadows (coverage, as BLEND ones);
//  * only scenes with transmissive materials run the passes; `--transmission off` runs no opaque-colour chain;
//  * TransmissionTest renders under the validation layers (sync validation in CI) and its transmissive pixels are
//    closer to the path tracer's image than the opaque look was: RMSE below 0.8 x the opaque look's (measured 0.087
//    vs 0.187 at 96x96 against 48 spp).
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "conformance/quad_scene.hpp"
#include "gpu/pathtrace/pt_image_util.hpp"
#include "pathtrace/pt_scene.hpp"
#include "render/path_tracer.hpp"
#include "render/renderer.hpp"
#include "render/scene_textures.hpp"
#include "scene/camera.hpp"
#include "scene/gltf_loader.hpp"
#include "support/dispersion_prism.hpp"
#include "support/gpu_fixture.hpp"

namespace idk::test {
namespace {

class ScreenTransmissionTest : public GpuTest {};

// Moves quad i of a makeQuadScene by `m` (applied after the quad's own basis and centre).
void place(scene::Scene& s, size_t i, const glm::mat4& m) {
    const glm::mat4 world = m * s.nodes[i].world;
    s.nodes[i].world = world;
    s.nodes[i].matrix = world;
    s.instances[i].world = world;
    for (float x : {-1.0f, 1.0f})
        for (float y : {-1.0f, 1.0f}) s.bounds.extend(glm::vec3(m * glm::vec4(x * 3.0f, y * 3.0f, 0.0f, 1.0f)));
}

struct Env {
    float radiance = 0.0f;  // constant environment (the raster's constant is 0.5 x intensity)
};

core::ImageRgba32f raster(vk::Context& ctx, vk::ShaderLibrary& shaders, const scene::Scene& scene,
                          const scene::CameraView& camera, uint32_t size, Env env,
                          render::TransmissionMode mode = render::TransmissionMode::Screen) {
    render::RenderSettings settings;
    settings.output = render::OutputKind::Hdr;
    settings.environment = std::filesystem::path();  // constant 0.5
    settings.environmentIntensity = env.radiance / 0.5f;
    settings.transmission = mode;
    render::Renderer renderer(ctx, shaders, settings);
    renderer.setScene(scene);
    render::SceneTextureStream textures(ctx, renderer, scene);
    textures.finishSynchronously();
    return renderer.renderOffscreen(camera, size, size).image;
}

core::ImageRgba32f pathTraced(vk::Context& ctx, vk::ShaderLibrary& shaders, const scene::Scene& scene,
                              const scene::CameraView& camera, uint32_t size, Env env, uint32_t spp,
                              uint32_t maxDepth = 6) {
    const pathtrace::PathTraceScene pts = pathtrace::buildPathTraceScene(scene, nullptr, 1.0f, glm::vec3(env.radiance));
    render::PathTracerOptions options;
    options.traversal = render::PtTraversal::Bvh;
    render::PathTracer tracer(ctx, shaders, scene, pts, options);
    render::PathTraceSettings s;
    s.spp = spp;
    s.seed = 11;
    s.maxDepth = maxDepth;
    return tracer.render(camera, size, size, s).image;
}

const float* pixel(const core::ImageRgba32f& img, uint32_t size, uint32_t x, uint32_t y) {
    return &img.pixels[(size_t(y) * size + x) * 4];
}

// Pixel (x, y)'s centre ray hits the plane z = zPlane at (wx, wy): for masks in world units.
glm::dvec2 onPlane(const scene::CameraView& camera, uint32_t size, uint32_t x, uint32_t y, double zPlane) {
    const glm::dmat4 inv =
        glm::inverse(glm::dmat4(scene::projectionMatrix(camera, 1.0f) * scene::viewMatrix(camera)));
    const double nx = (x + 0.5) / size * 2.0 - 1.0, ny = (y + 0.5) / size * 2.0 - 1.0;
    const glm::dvec4 a = inv * glm::dvec4(nx, ny, 0.0, 1.0), b = inv * glm::dvec4(nx, ny, 0.5, 1.0);
    const glm::dvec3 o = glm::dvec3(a) / a.w, d = glm::normalize(glm::dvec3(b) / b.w - o);
    const glm::dvec3 p = o + d * ((zPlane - o.z) / d.z);
    return {p.x, p.y};
}

// ------------------------------------------------------------------------------------------------ thin-walled quad
constexpr uint32_t kQuadSize = 64;
constexpr float kGlassHalf = 0.3f;

scene::Scene thinQuad(float transmission) {
    conformance::QuadSpec glass;
    glass.halfSize = kGlassHalf;
    glass.roughness = 0.0f;
    conformance::QuadSpec left, right;  // emissive panels behind, meeting at x = 0
    left.centre = glm::vec2(-1.0f, 0.0f);
    right.centre = glm::vec2(1.0f, 0.0f);
    left.halfSize = right.halfSize = 1.0f;
    left.baseColor = right.baseColor = glm::vec3(0.0f);
    left.emissive = glm::vec3(1.0f, 0.5f, 0.2f);
    right.emissive = glm::vec3(0.2f, 0.5f, 1.0f);
    scene::Scene s = conformance::makeQuadScene({glass, left, right});
    s.materials[0].transmission = transmission;
    const glm::mat4 back = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, -1.0f));
    place(s, 1, back);
    place(s, 2, back);
    return s;
}

scene::CameraView frontCamera(float z, float yfov) {
    scene::CameraView c;
    c.position = glm::vec3(0.0f, 0.0f, z);
    c.yfov = yfov;
    return c;
}

TEST_F(ScreenTransmissionTest, ThinWalledQuadMatchesThePathTracer) {
    const scene::CameraView camera = frontCamera(2.0f, 0.6f);
    const Env env{0.5f};
    const scene::Scene s = thinQuad(1.0f);
    const core::ImageRgba32f r = raster(ctx(), shaders(), s, camera, kQuadSize, env);
    const core::ImageRgba32f p = pathTraced(ctx(), shaders(), s, camera, kQuadSize, env, 256);
    const core::ImageRgba32f opaque = raster(ctx(), shaders(), thinQuad(0.0f), camera, kQuadSize, env);
    const double pixelWorld = 2.0 * 2.0 * std::tan(0.3) / kQuadSize;  // one pixel at z = 0
    std::vector<double> errors;
    double opaqueSum = 0.0;
    for (uint32_t y = 0; y < kQuadSize; ++y)
        for (uint32_t x = 0; x < kQuadSize; ++x) {
            const glm::dvec2 w = onPlane(camera, kQuadSize, x, y, 0.0);
            if (std::abs(w.x) > kGlassHalf - 2 * pixelWorld || std::abs(w.y) > kGlassHalf - 2 * pixelWorld) continue;
            if (std::abs(w.x) < 2 * pixelWorld) continue;  // the panels' seam
            for (int c = 0; c < 3; ++c) {
                const double want = pixel(p, kQuadSize, x, y)[c];
                errors.push_back(std::abs(pixel(r, kQuadSize, x, y)[c] - want) / want);
                opaqueSum += std::abs(pixel(opaque, kQuadSize, x, y)[c] - want) / want;
            }
        }
    ASSERT_GT(errors.size(), size_t(3 * 300));
    double mean = 0.0;
    for (double e : errors) mean += e;
    mean /= double(errors.size());
    std::sort(errors.begin(), errors.end());
    const double p95 = errors[errors.size() * 95 / 100];
    std::printf("thin-walled quad, %zu channel values: raster vs path tracer (256 spp) mean relative error %.4f, "
                "95th percentile %.4f; the opaque look's mean %.4f\n",
                errors.size(), mean, p95, opaqueSum / double(errors.size()));
    EXPECT_LT(mean, 0.03);
    EXPECT_LT(p95, 0.08);
    EXPECT_GT(opaqueSum / double(errors.size()), 10 * 0.03);  // the comparison tells transmission from none
}

TEST_F(ScreenTransmissionTest, TransmissionZeroIsTheOpaqueImageAndOffDrawsItOpaque) {
    const scene::CameraView camera = frontCamera(2.0f, 0.6f);
    const Env env{0.5f};
    scene::Scene plain = thinQuad(0.0f);
    plain.materials[0].roughness = 0.4f;
    plain.materials[0].baseColorFactor = glm::vec4(0.8f, 0.6f, 0.4f, 1.0f);
    scene::Scene decoys = plain;  // the other transmission/volume fields set, the factor 0
    decoys.materials[0].thickness = 0.7f;
    decoys.materials[0].ior = 1.8f;
    decoys.materials[0].attenuationDistance = 0.2f;
    decoys.materials[0].attenuationColor = glm::vec3(0.2f, 0.3f, 0.9f);
    decoys.materials[0].dispersion = 3.0f;
    const core::ImageRgba32f a = raster(ctx(), shaders(), plain, camera, kQuadSize, env);
    const core::ImageRgba32f b = raster(ctx(), shaders(), decoys, camera, kQuadSize, env);
    EXPECT_EQ(a.pixels, b.pixels);

    // --transmission off: the transmissive quad is forward-shaded opaque; the deferred pass's look within the
    // G-buffer's quantisation (8-bit sRGB albedo, octahedral normal) of the peak.
    scene::Scene glass = plain;
    glass.materials[0].transmission = 1.0f;
    const core::ImageRgba32f off = raster(ctx(), shaders(), glass, camera, kQuadSize, env, render::TransmissionMode::Off);
    double peak = 0.0, worst = 0.0;
    for (size_t i = 0; i < a.pixels.size(); ++i)
        if (i % 4 != 3) peak = std::max(peak, double(a.pixels[i]));
    for (size_t i = 0; i < a.pixels.size(); ++i)
        if (i % 4 != 3) worst = std::max(worst, std::abs(double(off.pixels[i]) - a.pixels[i]) / peak);
    std::printf("--transmission off vs the deferred opaque quad: worst %.2e of the peak\n", worst);
    EXPECT_LT(worst, 1e-2);
}

// The passes a frame ran whose names start with `prefix`.
size_t passesNamed(vk::Context& ctx, vk::ShaderLibrary& shaders, const scene::Scene& scene,
                   render::TransmissionMode mode, const std::string& prefix) {
    render::RenderSettings settings;
    settings.output = render::OutputKind::Hdr;
    settings.environment = std::filesystem::path();
    settings.transmission = mode;
    render::Renderer renderer(ctx, shaders, settings);
    renderer.setScene(scene);
    size_t n = 0;
    for (const std::string& pass : renderer.renderOffscreen(frontCamera(2.0f, 0.6f), 16, 16).passesRun)
        n += pass.rfind(prefix, 0) == 0;
    return n;
}

TEST_F(ScreenTransmissionTest, OnlyScenesWithTransmissiveMaterialsRunThePasses) {
    // No transmissive material: no transmission pass and no chain (and no sorted-draw buffer: setScene skips it).
    EXPECT_EQ(passesNamed(ctx(), shaders(), thinQuad(0.0f), render::TransmissionMode::Screen, "transmission"), 0u);
    // --transmission off: the forward pass alone, no opaque-colour chain.
    EXPECT_EQ(passesNamed(ctx(), shaders(), thinQuad(1.0f), render::TransmissionMode::Off, "transmission_chain"), 0u);
    EXPECT_EQ(passesNamed(ctx(), shaders(), thinQuad(1.0f), render::TransmissionMode::Off, "transmission"), 1u);
    EXPECT_EQ(passesNamed(ctx(), shaders(), thinQuad(1.0f), render::TransmissionMode::Screen, "transmission"), 6u);
    // Screen: the chain of a 16 x 16 frame (16, 8, 4, 2, 1: five levels) and the forward pass.
    EXPECT_EQ(passesNamed(ctx(), shaders(), thinQuad(1.0f), render::TransmissionMode::Screen, "transmission_chain"),
              5u);
}

// A transmissive quad leaves the G-buffer but still casts a shadow (as BLEND draws do: by coverage), as it did
// when it was drawn opaque: a white floor at z = -1 lit by a point light at z = 1 through a glass quad at z = 0.
TEST_F(ScreenTransmissionTest, TransmissiveSurfacesStillCastShadows) {
    conformance::QuadSpec glass;
    glass.halfSize = kGlassHalf;
    glass.roughness = 0.0f;
    conformance::QuadSpec floor;
    floor.halfSize = 2.0f;
    scene::Scene s = conformance::makeQuadScene({glass, floor});
    place(s, 1, glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, -1.0f)));
    scene::Light light;
    light.type = scene::LightType::Point;
    light.position = glm::vec3(0.0f, 0.0f, 1.0f);
    light.intensity = 2.0f;
    s.lights.push_back(light);
    const scene::CameraView camera = frontCamera(2.0f, 0.9f);
    // The floor seen beside the glass (|x| > 0.45 at z = -1) and inside its shadow (|x| < 0.6), and outside it.
    auto floorAt = [&](const core::ImageRgba32f& img, double wx) {
        uint32_t best = 0;
        double bestDistance = 1e9;
        for (uint32_t x = 0; x < kQuadSize; ++x) {
            const double d = std::abs(onPlane(camera, kQuadSize, x, kQuadSize / 2, -1.0).x - wx);
            if (d < bestDistance) bestDistance = d, best = x;
        }
        return double(pixel(img, kQuadSize, best, kQuadSize / 2)[1]);
    };
    for (float transmission : {0.0f, 1.0f}) {
        s.materials[0].transmission = transmission;
        const core::ImageRgba32f img = raster(ctx(), shaders(), s, camera, kQuadSize, Env{});
        const double shadowed = floorAt(img, 0.53), lit = floorAt(img, 0.8);
        std::printf("glass transmission %.0f: floor in its shadow %.4f, beside it %.4f\n", transmission, shadowed, lit);
        EXPECT_GT(lit, 0.0);
        EXPECT_LT(shadowed, 0.1 * lit) << "transmission " << transmission;
    }
}

// ------------------------------------------------------------------------------------------------ volume slabs
constexpr uint32_t kSlabSize = 96;
constexpr float kSlabHalf = 0.25f;
constexpr float kSlabX[3] = {-0.65f, 0.0f, 0.65f};
constexpr float kSlabDepth[3] = {0.1f, 0.25f, 0.5f};

scene::Scene slabs() {
    std::vector<conformance::QuadSpec> quads;
    for (int i = 0; i < 3; ++i) {
        conformance::QuadSpec front;
        front.centre = glm::vec2(kSlabX[i], 0.0f);
        front.halfSize = kSlabHalf;
        front.roughness = 0.0f;
        conformance::QuadSpec back = front;
        back.basis = glm::mat3(glm::rotate(glm::mat4(1.0f), 3.14159265f, glm::vec3(0.0f, 1.0f, 0.0f)));
        quads.push_back(front);
        quads.push_back(back);
    }
    conformance::QuadSpec emitter;
    emitter.halfSize = 3.0f;
    emitter.baseColor = glm::vec3(0.0f);
    emitter.emissive = glm::vec3(1.0f);
    quads.push_back(emitter);
    scene::Scene s = conformance::makeQuadScene(quads);
    for (int i = 0; i < 3; ++i) {
        place(s, 2 * i + 1, glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, -kSlabDepth[i])));
        for (int f = 0; f < 2; ++f) {
            scene::Material& m = s.materials[2 * i + f];
            m.transmission = 1.0f;
            m.thickness = kSlabDepth[i];
            m.attenuationDistance = 0.3f;
            m.attenuationColor = glm::vec3(0.8f, 0.5f, 0.3f);
        }
    }
    place(s, 6, glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, -1.5f)));
    return s;
}

// Mean RGB over the pixels whose ray meets slab i's front face at least 2 pixels inside its edges.
glm::dvec3 slabMean(const core::ImageRgba32f& img, const scene::CameraView& camera, int i) {
    const double pixelWorld = 2.0 * 4.0 * std::tan(0.5 * camera.yfov) / kSlabSize;
    glm::dvec3 sum(0.0);
    double n = 0.0;
    for (uint32_t y = 0; y < kSlabSize; ++y)
        for (uint32_t x = 0; x < kSlabSize; ++x) {
            const glm::dvec2 w = onPlane(camera, kSlabSize, x, y, 0.0);
            // Inside the front face, and the straight ray still inside the back face (the sides are open).
            const glm::dvec2 wb = onPlane(camera, kSlabSize, x, y, -kSlabDepth[i]);
            const double inset = kSlabHalf - 2 * pixelWorld;
            if (std::abs(w.x - kSlabX[i]) > inset || std::abs(w.y) > inset) continue;
            if (std::abs(wb.x - kSlabX[i]) > inset || std::abs(wb.y) > inset) continue;
            const float* p = pixel(img, kSlabSize, x, y);
            sum += glm::dvec3(p[0], p[1], p[2]);
            n += 1.0;
        }
    EXPECT_GT(n, 100.0) << "slab " << i;
    return sum / std::max(n, 1.0);
}

TEST_F(ScreenTransmissionTest, VolumeSlabsTintLikeThePathTracerAndThickerIsDarker) {
    const scene::CameraView camera = frontCamera(4.0f, 0.45f);
    const scene::Scene s = slabs();
    const core::ImageRgba32f r = raster(ctx(), shaders(), s, camera, kSlabSize, Env{});
    const core::ImageRgba32f p = pathTraced(ctx(), shaders(), s, camera, kSlabSize, Env{}, 64);
    glm::dvec3 rm[3], pm[3];
    for (int i = 0; i < 3; ++i) {
        rm[i] = slabMean(r, camera, i);
        pm[i] = slabMean(p, camera, i);
        std::printf("slab %d (thickness %.2f): raster tint (%.4f %.4f %.4f), path tracer (%.4f %.4f %.4f)\n", i,
                    kSlabDepth[i], rm[i].x, rm[i].y, rm[i].z, pm[i].x, pm[i].y, pm[i].z);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(rm[i][c] / pm[i][c], 1.0, 0.07) << "slab " << i << " channel " << c;
    }
    for (int i = 0; i + 1 < 3; ++i)
        for (int c = 0; c < 3; ++c) {
            EXPECT_GT(rm[i][c], rm[i + 1][c]) << "raster, slabs " << i << ", " << i + 1 << " channel " << c;
            EXPECT_GT(pm[i][c], pm[i + 1][c]) << "path tracer, slabs " << i << ", " << i + 1 << " channel " << c;
        }
}

// ------------------------------------------------------------------------------------------------ dispersion
constexpr uint32_t kPrismSize = 64;

scene::Scene prism(float dispersion) {
    scene::Scene s = prismQuads(dispersion);
    const glm::dvec3 r = prismRefracted(glm::dvec3(0.0, 0.0, -1.0), kPrismIor);  // the axis ray, from the origin
    s.materials[0].thickness = float(kPrismEmitterZ / r.z);  // the raster leaves the volume on the emitter's plane
    place(s, 1, glm::translate(glm::mat4(1.0f), glm::vec3(float(r.x * (kPrismEmitterZ / r.z)), 0.0f, kPrismEmitterZ)));
    return s;
}

double centroidX(const core::ImageRgba32f& img, int c) { return channelCentroidX(img, kPrismSize, c); }

TEST_F(ScreenTransmissionTest, DispersionSeparatesTheChannelsAsThePathTracer) {
    const scene::CameraView camera = frontCamera(kPrismCameraZ, kPrismFov);
    const scene::Scene s = prism(4.0f);
    const core::ImageRgba32f r = raster(ctx(), shaders(), s, camera, kPrismSize, Env{});
    const core::ImageRgba32f p = pathTraced(ctx(), shaders(), s, camera, kPrismSize, Env{}, 24, 3);
    double rc[3], pc[3];
    for (int c = 0; c < 3; ++c) {
        rc[c] = centroidX(r, c);
        pc[c] = centroidX(p, c);
    }
    std::printf("dispersive interface: emitter centroid x (px) raster R %.2f G %.2f B %.2f; path tracer R %.2f G %.2f "
                "B %.2f\n",
                rc[0], rc[1], rc[2], pc[0], pc[1], pc[2]);
    ASSERT_GT(pc[2] - pc[0], 2.0);  // the oracle separates them (pt_dispersion_test checks it against Snell)
    EXPECT_LT(rc[0], rc[1]);        // the same order: red bends least
    EXPECT_LT(rc[1], rc[2]);
    EXPECT_NEAR(rc[2] - rc[0], pc[2] - pc[0], 0.35 * (pc[2] - pc[0]));  // measured 3.79 vs 3.33 px
    // Each channel within 1.5 px of the path tracer's (measured 0.6, 0.6, 1.1): the raster leaves the volume after
    // the same thickness along every pixel's refracted ray, so off the axis its exit points miss the emitter's plane.
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(rc[c], pc[c], 1.5) << "channel " << c;

    const core::ImageRgba32f r0 = raster(ctx(), shaders(), prism(0.0f), camera, kPrismSize, Env{});
    std::printf("dispersion 0: raster centroids R %.3f G %.3f B %.3f px\n", centroidX(r0, 0), centroidX(r0, 1),
                centroidX(r0, 2));
    EXPECT_NEAR(centroidX(r0, 0), centroidX(r0, 1), 0.02);
    EXPECT_NEAR(centroidX(r0, 2), centroidX(r0, 1), 0.02);
}

// ------------------------------------------------------------------------------------------------ TransmissionTest
TEST_F(ScreenTransmissionTest, TransmissionTestIsCloserToThePathTracerThanTheOpaqueLook) {
    const scene::Scene s =
        scene::loadGltf(std::string(IDK_SHARED_DIR) + "/scenes/TransmissionTest/glTF-Binary/TransmissionTest.glb");
    const scene::CameraView camera = scene::defaultCamera(s);
    constexpr uint32_t kSize = 96;
    const Env env{0.5f};
    const core::ImageRgba32f screen = raster(ctx(), shaders(), s, camera, kSize, env);
    const core::ImageRgba32f off = raster(ctx(), shaders(), s, camera, kSize, env, render::TransmissionMode::Off);
    const core::ImageRgba32f p = pathTraced(ctx(), shaders(), s, camera, kSize, env, 48, 6);
    // The transmissive pixels: where the two raster modes differ (the refracted background is all that changes).
    double screenSum = 0.0, offSum = 0.0;
    size_t n = 0;
    for (size_t q = 0; q < screen.pixels.size() / 4; ++q) {
        double diff = 0.0;
        for (int c = 0; c < 3; ++c) diff += std::abs(screen.pixels[4 * q + c] - off.pixels[4 * q + c]);
        if (diff < 0.03) continue;
        ++n;
        for (int c = 0; c < 3; ++c) {
            screenSum += std::pow(screen.pixels[4 * q + c] - p.pixels[4 * q + c], 2.0);
            offSum += std::pow(off.pixels[4 * q + c] - p.pixels[4 * q + c], 2.0);
        }
    }
    const double screenRmse = std::sqrt(screenSum / double(3 * std::max<size_t>(n, 1)));
    const double offRmse = std::sqrt(offSum / double(3 * std::max<size_t>(n, 1)));
    std::printf("TransmissionTest %ux%u, %zu transmissive pixels: RMSE against the path tracer (48 spp) screen-space "
                "%.4f, opaque look %.4f\n",
                kSize, kSize, n, screenRmse, offRmse);
    EXPECT_GT(n, size_t(kSize) * kSize / 20);
    EXPECT_EQ(nonFiniteCount(screen), 0u);
    EXPECT_LT(screenRmse, 0.8 * offRmse);
}

}  // namespace
}  // namespace idk::test
