// shadow_checks.cpp: "shadows/point faces rungs agree": the two rungs of the ladder "point-shadow cube faces"
// render the same cube. Native (shaderOutputLayer): one instanced draw per light, gl_Layer from the vertex shader;
// fallback: six draws, one per face. Both render the embedded Cornell box at 64x64 with a 128^2 cube; every texel
// of every face of the light's D32 cube must be bit-identical (both rungs run the same vertex arithmetic,
// include/point_shadow_vertex.glsl), and so must the lit frames; each rung records 1 vs 6 indirect calls per light,
// and the box (open at the front) fills most of the cube (or the comparison would be empty).
// Moved from tests/gpu/shadows/shadow_ladder_test.cpp.
#include <cstring>

#include "app/default_scene.hpp"
#include "conformance/conformance.hpp"
#include "conformance/cube_readback.hpp"
#include "render/renderer.hpp"

namespace idk::conformance {
namespace {

constexpr uint32_t kFrame = 64, kCube = 128;

struct RungResult {
    std::vector<float> cube;
    core::ImageRgba32f frame;
    uint32_t shadowCalls = 0;
};

RungResult renderCornell(Verdict& v, vk::Context& ctx, vk::ShaderLibrary& shaders, vk::Rung rung) {
    const std::string what = vk::rungName(rung);
    const scene::Scene scene = app::loadDefaultScene();
    render::RenderSettings settings;
    settings.output = render::OutputKind::Hdr;
    settings.pointShadows.resolution = kCube;
    settings.culling.mode = frame::CullingMode::Off;  // culled cubes are drawn face by face on both rungs
    render::Renderer renderer(ctx, shaders, settings);
    renderer.setScene(scene);
    RungResult r;
    render::FrameResult frame = renderer.renderOffscreen(scene::defaultCamera(scene), kFrame, kFrame);
    r.frame = std::move(frame.image);
    for (const auto& e : frame.indirectDraws)
        if (e.pass == "point_shadows") r.shadowCalls = e.calls;
    const render::PointShadowMaps* maps = renderer.pointShadowMaps();
    if (!v.expect(maps != nullptr, what + ": the frame made no point-shadow maps")) return r;
    v.expectEq(maps->casters().size(), size_t(1), what + ": cubes (the Cornell box has one point light)");
    v.expect(maps->layered() == (rung == vk::Rung::Native), what + ": the maps' layering does not follow the rung");
    r.cube = readCube(ctx, maps->cube(0));
    return r;
}

void pointFacesAgree(CheckEnv& env, Verdict& v) {
    bool native = false;
    for (const vk::RungOption& o : env.ctx.ladder("point-shadow-faces").options) native |= o.rung == vk::Rung::Native && o.available;
    if (!native) {
        v.skip("device lacks shaderOutputLayer: only the six-draw rung runs");
        return;
    }
    RungResult results[2];
    const vk::Rung rungs[2] = {vk::Rung::Native, vk::Rung::Fallback};
    for (int r = 0; r < 2; ++r)
        onRung(env, v, "point-shadow-faces", rungs[r], [&](vk::Context& ctx, vk::ShaderLibrary& shaders) {
            results[r] = renderCornell(v, ctx, shaders, rungs[r]);
        });
    const RungResult &layered = results[0], &six = results[1];
    v.expectEq(layered.shadowCalls, 1u, "native: indirect draws per light");
    v.expectEq(six.shadowCalls, 6u, "fallback: indirect draws per light");
    if (!v.expectEq(layered.cube.size(), size_t(kCube) * kCube * 6, "native: cube texels") ||
        !v.expectEq(six.cube.size(), layered.cube.size(), "fallback: cube texels"))
        return;
    size_t differing = 0, covered = 0, outOfRange = 0;
    for (size_t i = 0; i < layered.cube.size(); ++i) {
        differing += std::memcmp(&layered.cube[i], &six.cube[i], sizeof(float)) != 0;
        v.recordError(std::abs(double(layered.cube[i]) - six.cube[i]));
        covered += layered.cube[i] < 1.0f;
        outOfRange += !(layered.cube[i] >= 0.0f && layered.cube[i] <= 1.0f);
    }
    v.expectEq(differing, size_t(0), "cube texels that differ between the rungs");
    v.expectEq(outOfRange, size_t(0), "cube depths outside [0, 1]");
    v.expect(covered > layered.cube.size() * 3 / 4, "the box should fill most of the cube (" + std::to_string(covered) + ")");
    v.expect(layered.frame.pixels.size() == six.frame.pixels.size() &&
                 std::memcmp(layered.frame.pixels.data(), six.frame.pixels.data(),
                             layered.frame.pixels.size() * sizeof(float)) == 0,
             "the lit frames differ");
}

}  // namespace

std::vector<Check> shadowChecks() {
    return {{"shadows/point faces rungs agree", "", "bit-identical cubes and frames", pointFacesAgree}};
}

}  // namespace idk::conformance
