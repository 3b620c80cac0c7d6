// shadow_oracle.hpp: the shadow tests' frames and CPU visibility oracle (tests/gpu/shadows/*): scenes of placed
// quads rendered to 128x128 HDR frames with a constant environment, and per floor pixel the visibility
// s = (full - ambient) / (unshadowed - ambient) (RGB sums) from three frames (with shadows; the light at
// intensity 0; shadows off) compared with a CPU ray from the floor point to the light (support/placed_quads.hpp
// castRay, exact for quads). Pixels within a band of the CPU shadow boundary are excluded; its width is a stated
// number of shadow texels at the point (the filter footprint and normal offset blur the edge).
#pragma once
#include <glm/glm.hpp>

#include <functional>
#include <string>
#include <vector>

#include "core/image_file.hpp"
#include "render/render_settings.hpp"
#include "scene/camera.hpp"
#include "scene/scene.hpp"
#include "support/placed_quads.hpp"
#include "vk/context.hpp"
#include "vk/shader_library.hpp"

namespace idk::test {

constexpr uint32_t kShadowFrameSize = 128;

struct ShadowFrames {
    core::ImageRgba32f full, ambient, unshadowed;
};

// Renders the three frames (light 0 is the one tested); `settings` sets the shadow options (maxLights is set per
// frame). Writes <build>/shadow_oracle_test/<name>_{full,unshadowed,ambient}.exr.
ShadowFrames renderShadowFrames(vk::Context& ctx, vk::ShaderLibrary& shaders, scene::Scene scene,
                                const scene::CameraView& camera, const std::string& name,
                                const render::RenderSettings& settings);
// Settings of the shadow tests: HDR output, constant environment at 0.3, cubes and maps at `resolution`.
render::RenderSettings shadowTestSettings(uint32_t resolution);

scene::CameraView shadowTestCamera(glm::vec3 eye, glm::vec3 target);
double rgbSum(const core::ImageRgba32f& img, size_t pixel);

// Primary CPU hits through every pixel centre (the same ray construction as the deferred lighting).
struct PrimaryHits {
    std::vector<int> quad;  // -1: none
    std::vector<glm::dvec3> point;
};
PrimaryHits primaryHits(const std::vector<PlacedQuad>& quads, const scene::CameraView& camera);
bool interiorPixel(const PrimaryHits& h, uint32_t px, uint32_t py);  // the 3x3 neighbourhood hits the same quad

// The light as the oracle sees it: the point a shadow ray from p aims at (a point light's position, or far away
// against a directional light's direction) and the world size of one shadow texel at p.
struct OracleLight {
    std::function<glm::dvec3(const glm::dvec3&)> target;
    std::function<double(const glm::dvec3&)> texel;
};
bool occludedFrom(const std::vector<PlacedQuad>& quads, const glm::dvec3& p, const glm::dvec3& target);
// The visible fraction of a sphere light (centre c, radius r) from p past `occluders`: n x n stratified directions
// uniform in the sphere's cone seen from p (the soft-shadow oracle: SoftShadowTest and the benchmark's soft rows).
double sphereVisibility(const std::vector<PlacedQuad>& occluders, const glm::dvec3& p, const glm::dvec3& c, double r,
                        int n);

struct FloorCounts {
    uint32_t dark = 0, lit = 0, band = 0, unlit = 0, failures = 0;
    std::string first;
};
// Classifies the floor pixels (quad 0 of `visible`) by the CPU ray towards the light through `occluders`: s <= 0.02
// where occluded, s >= 0.98 where not, skipping pixels within bandTexels texels (divided by the cosine of
// incidence, at least 1/4) of the CPU shadow boundary and, where skipUnlit, pixels the light does not reach even
// unshadowed (outside a spot cone); otherwise an unlit floor pixel fails.
FloorCounts checkShadowFloor(const ShadowFrames& f, const std::vector<PlacedQuad>& visible,
                             const std::vector<PlacedQuad>& occluders, const scene::CameraView& camera,
                             const OracleLight& light, double bandTexels, bool skipUnlit = false);

PlacedQuad floorQuad(float halfSize);

struct AcneCounts {
    uint32_t tested = 0, failures = 0;
    double worst = 1.0;  // lowest visibility seen
    std::string first;   // the first failing pixel
};
// Self-shadowing on the corner scene (floor y = 0, walls x = -2 and z = -2), where nothing casts a shadow: every
// interior pixel the light reaches, farther than band(p) from the corner's other surfaces, must keep s >= 0.99.
AcneCounts checkNoAcne(const ShadowFrames& f, const PrimaryHits& hits,
                       const std::function<double(const glm::dvec3&)>& band);

}  // namespace idk::test
