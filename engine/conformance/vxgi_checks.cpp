// vxgi_checks.cpp: the VXGI voxelization passes (passes/vxgi_voxelize.cpp through the Renderer's VXGI feature)
// against the CPU voxelizer (voxel_oracle.hpp) on a 64^3 grid over a scene of quads: an open box of six walls (gaps
// at the edges so no two walls share a voxel), an emissive ceiling, a tilted double-sided quad inside, a stack of
// three parallel quads in one voxel layer (0.30 facing down, 0.305 and 0.31 facing up: the front-most rule of
// shared/vxgi_depth_key.h hides the middle one behind the top one, while the bottom one, of the other facing, stays:
// two fragments per voxel, whose mean and max differ), and a floor and a wall meeting in a row of corner voxels
// (two facings, both kept). One unshadowed point light. With --gi-raster centre, the oracle's thin voxelization
// (which applies the same front-most rule):
//  * "vxgi/voxelize" on each rung of "vxgi-atomics": occupancy agrees with the oracle on >= 99.5% of the voxels
//    either marks (the oracle's tie-free design makes it 100% here); each occupied voxel's rgb is the oracle's MEAN
//    of its front-most fragments (native: float atomic add + count; gl-interop: fragment records added by GL float atomics,
//    merged by Vulkan) or MAX (fallback: r32ui + max) within 0.2% (+1e-5); on one-fragment voxels the six
//    directional level-0 voxels are the oracle's radiance seen by its quad's facing (one-sided ceiling: dark from
//    above) within the same tolerance; empty voxels are all-zero in the grid and the directional volumes.
//  * "vxgi/rungs agree": both rungs give the same grid and directional level 0 (within 1e-3 relative) on the
//    voxels holding one fragment.
//  * "vxgi/ray-traced shadows": with --shadows raytraced, the scene plus a blocker over the floor against the oracle
//    with hard shadows (the voxelization's shadow rays through the BVH), as "vxgi/voxelize" on the chosen rung.
//  * "vxgi/thin wall" on each rung of "conservative-raster" (native VK_EXT_conservative_rasterization, fallback
//    geometry-shader dilation): a wall one voxel thin whose edges stop inside voxels: every voxel column along its
//    normal that the wall touches holds a wall voxel (no holes), and no column it does not touch does; centre
//    raster must miss some edge columns (or the check could not fail).
// Moved from tests/conformance/vxgi/voxelize_test.cpp.
#include <glm/gtc/packing.hpp>

#include <cmath>
#include <cstring>

#include "conformance/conformance.hpp"
#include "conformance/voxel_oracle.hpp"
#include "graph/barrier_planner.hpp"
#include "render/renderer.hpp"
#include "shared/vxgi_cone.h"
#include "vk/transfer.hpp"

namespace idk::conformance {
namespace {

constexpr uint32_t kVoxels = 64;
constexpr double kRelTolerance = 2e-3, kAbsTolerance = 1e-5;

struct VoxelScene {
    std::vector<PlacedQuad> quads;
    std::vector<glm::vec3> emissive;
    OracleLight light{{0.2, 0.6, 0.1}, {3.0, 3.0, 3.0}};
};

VoxelScene makeVoxelScene() {
    VoxelScene t;
    // The walls lie on the scene bounds [-1, 1]^3 (voxel centres, fitVoxelGrid's half-voxel margin); their
    // edges stop short of the corners at coordinates that are no voxel centre.
    t.quads.push_back(placedQuad({0.0f, -1.0f, 0.0f}, {0, 1, 0}, {0.83f, 0.81f}, {0.8f, 0.8f, 0.8f}));     // floor
    t.quads.push_back(placedQuad({0.05f, 1.0f, -0.02f}, {0, -1, 0}, {0.71f, 0.77f}, {0.9f, 0.9f, 0.9f}));  // ceiling
    t.quads.push_back(placedQuad({-1.0f, 0.02f, 0.03f}, {1, 0, 0}, {0.74f, 0.69f}, {0.8f, 0.1f, 0.1f}));   // left
    t.quads.push_back(placedQuad({1.0f, -0.03f, 0.01f}, {-1, 0, 0}, {0.67f, 0.73f}, {0.1f, 0.8f, 0.1f}));  // right
    t.quads.push_back(placedQuad({0.01f, 0.02f, -1.0f}, {0, 0, 1}, {0.79f, 0.72f}, {0.7f, 0.7f, 0.6f}));   // back
    t.quads.push_back(placedQuad({-0.02f, 0.04f, 1.0f}, {0, 0, -1}, {0.76f, 0.7f}, {0.5f, 0.6f, 0.7f}));   // front
    t.quads.push_back(placedQuad({0.1f, -0.2f, 0.15f}, {0.3f, 0.8f, 0.45f}, {0.4f, 0.3f}, {0.2f, 0.7f, 0.3f}, true));
    // The stack, all in the voxel layer y in [0.2857, 0.3175): the bottom faces down, the middle is hidden by the top.
    t.quads.push_back(placedQuad({-0.3f, 0.30f, -0.2f}, {0, -1, 0}, {0.23f, 0.21f}, {0.9f, 0.2f, 0.2f}));
    t.quads.push_back(placedQuad({-0.3f, 0.31f, -0.2f}, {0, 1, 0}, {0.23f, 0.21f}, {0.1f, 0.3f, 0.9f}));
    t.quads.push_back(placedQuad({-0.3f, 0.305f, -0.2f}, {0, 1, 0}, {0.23f, 0.21f}, {0.2f, 0.9f, 0.4f}));
    // The corner: a floor (x in [0.36, 0.66], y = -0.5) and a wall facing -x at its far edge, sharing the voxels
    // (52, 16, 37..45) (the wall at x = 0.66 lies in voxel 52, the floor's last column's centre x = 0.651 too).
    t.quads.push_back(placedQuad({0.51f, -0.5f, 0.3f}, {0, 1, 0}, {0.15f, 0.15f}, {0.6f, 0.5f, 0.3f}));
    t.quads.push_back(placedQuad({0.66f, -0.35f, 0.3f}, {-1, 0, 0}, {0.15f, 0.15f}, {0.3f, 0.4f, 0.8f}));
    t.emissive.assign(t.quads.size(), glm::vec3(0.0f));
    t.emissive[1] = {1.5f, 1.2f, 0.9f};  // the ceiling glows
    return t;
}

scene::Scene toScene(const VoxelScene& t) {
    scene::Scene s = makePlacedQuadScene(t.quads);
    for (size_t i = 0; i < t.quads.size(); ++i) {
        s.materials[i].metallic = 0.0f;
        s.materials[i].emissive = t.emissive[i];
    }
    s.lights.push_back(pointLight(glm::vec3(t.light.position), float(t.light.intensity.x)));
    return s;
}

struct Grid {
    std::vector<glm::vec4> voxels;  // empty when the frame made no grid
    std::array<std::vector<glm::vec4>, 6> directions;  // level 0 of the directional volumes (+x -x +y -y +z -z)
    VkFormat directionFormat = VK_FORMAT_R16G16B16A16_SFLOAT;  // their colour images' ("vxgi-volume-format")
    passes::VoxelGridBox box;
};

// One 16x16 HDR frame with VXGI on (its voxelization runs the context's chosen rungs), no shadows (the oracle has
// none); the grid read back.
Grid voxelize(vk::Context& ctx, vk::ShaderLibrary& shaders, const VoxelScene& t, frame::VoxelRaster raster,
              bool rayTracedShadows = false) {
    render::RenderSettings settings;
    settings.output = render::OutputKind::Hdr;
    settings.pointShadows.maxLights = rayTracedShadows ? 4 : 0;
    settings.lightShadows.rayTraced = rayTracedShadows;
    settings.vxgi.mode = frame::GiMode::Vxgi;
    settings.vxgi.voxels = kVoxels;
    settings.vxgi.raster = raster;
    render::Renderer renderer(ctx, shaders, settings);
    renderer.setScene(toScene(t));
    scene::CameraView camera;
    camera.position = {0.0f, 0.0f, 0.9f};
    renderer.renderOffscreen(camera, 16, 16);
    Grid g;
    if (const vk::Image* grid = renderer.vxgi().grid()) {
        g.voxels = readVoxelGrid(ctx, *grid);
        // The directional volumes end where the cone tracer sampled them (the feature's final use).
        const VkImageLayout sampled = graph::stateAfterAccess(graph::Access::SampledRead, graph::ResourceKind::Image,
                                                              VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT)
                                          .layout;
        for (uint32_t d = 0; d < 6; ++d) g.directions[d] = readDirectionGrid(ctx, renderer.vxgi().directions()[d], sampled);
        g.directionFormat = renderer.vxgi().directions()[0].colour.image.format;
    }
    g.box = renderer.vxgi().box();
    return g;
}

// A GPU grid against the oracle: `useMax` picks the oracle's max (r32ui rung) or mean (float-add rung).
void expectMatchesOracle(Verdict& v, const Grid& g, const VoxelScene& t, bool useMax, bool shadowed = false) {
    const std::vector<OracleVoxel> oracle = voxelizeOnCpu(t.quads, t.emissive, {t.light}, g.box, shadowed);
    if (!v.expectEq(g.voxels.size(), oracle.size(), "voxel count")) return;
    size_t either = 0, agree = 0, compared = 0, multi = 0, ambiguous = 0, nonZeroEmpty = 0, partial = 0,
           directional = 0, hidden = 0, corners = 0;
    for (size_t i = 0; i < oracle.size(); ++i) {
        const OracleVoxel& o = oracle[i];
        const glm::vec4& c = g.voxels[i];
        if (o.ambiguous) {
            ++ambiguous;
            continue;
        }
        const bool gpu = c.a > 0.0f, cpu = o.count > 0;
        if (!gpu && !cpu) {
            nonZeroEmpty += c != glm::vec4(0.0f);
            for (const std::vector<glm::vec4>& d : g.directions) nonZeroEmpty += d[i] != glm::vec4(0.0f);
            continue;
        }
        ++either;
        if (gpu != cpu) continue;
        ++agree;
        partial += c.a != 1.0f;
        multi += o.count > 1;
        hidden += o.hidden > 0;
        // Kept fragments of two axes' facings (the floor and the wall in a corner voxel).
        corners += ((o.classes & 3u) != 0) + ((o.classes & 12u) != 0) + ((o.classes & 48u) != 0) >= 2;
        const glm::dvec3 want = useMax ? o.max : o.sum / double(o.count);
        for (int k = 0; k < 3; ++k) {
            const double err = std::abs(double(c[k]) - want[k]);
            v.recordError(err / (std::abs(want[k]) + kAbsTolerance / kRelTolerance));
            v.expect(err <= kRelTolerance * want[k] + kAbsTolerance,
                     "voxel " + std::to_string(i) + " channel " + std::to_string(k) + ": gpu " + std::to_string(c[k]) +
                         ", oracle " + std::to_string(want[k]));
        }
        ++compared;
        if (o.count != 1) continue;
        // One fragment: each directional level-0 voxel is the oracle's radiance seen along its direction by the
        // quad's facing (vxgiVoxelTowards, shared with the cone tracer's C++ side).
        ++directional;
        for (uint32_t k = 0; k < 6; ++k) {
            const glm::vec4 expected = gpu::vxgiVoxelTowards(glm::vec4(glm::vec3(want), 1.0f), glm::vec4(o.facing), k);
            const glm::vec4& got = g.directions[k][i];
            const glm::vec4 step = directionStep(g.directionFormat, expected);  // the store's rounding on top
            for (int ch = 0; ch < 4; ++ch) {
                const double err = std::abs(double(got[ch]) - expected[ch]);
                v.recordError(err / (std::abs(expected[ch]) + kAbsTolerance / kRelTolerance));
                v.expect(err <= kRelTolerance * std::abs(expected[ch]) + kAbsTolerance + step[ch],
                         "voxel " + std::to_string(i) + " direction " + std::to_string(k) + " channel " +
                             std::to_string(ch) + ": gpu " + std::to_string(got[ch]) + ", oracle " +
                             std::to_string(expected[ch]));
            }
        }
    }
    v.expect(directional > 10000, "too few one-fragment voxels for the directional check (" +
                                      std::to_string(directional) + ")");
    const double agreement = either ? double(agree) / double(either) : 0.0;
    v.expect(agreement >= 0.995, "occupancy agrees on " + std::to_string(100.0 * agreement) + "% of the voxels (>= 99.5%)");
    v.expectEq(nonZeroEmpty, size_t(0), "empty voxels that are not zero");
    v.expectEq(partial, size_t(0), "occupied voxels whose coverage is not 1");
    v.expect(compared > 10000, "the scene should cover many voxels (" + std::to_string(compared) + ")");
    v.expect(multi > 50, "the stack should put two fragments in some voxels (" + std::to_string(multi) + ")");
    v.expect(hidden > 50, "the stack's middle quad should be hidden in many voxels (" + std::to_string(hidden) + ")");
    v.expect(corners >= 8, "the corner should keep a floor and a wall in >= 8 voxels (" + std::to_string(corners) + ")");
    v.expect(ambiguous < either / 100, "the scene is meant to avoid ties (" + std::to_string(ambiguous) + ")");
}

void voxelizeOnRung(CheckEnv& env, Verdict& v) {
    const VoxelScene t = makeVoxelScene();
    onRung(env, v, "vxgi-atomics", *env.rung, [&](vk::Context& ctx, vk::ShaderLibrary& shaders) {
        expectMatchesOracle(v, voxelize(ctx, shaders, t, frame::VoxelRaster::Centre), t, env.rung == vk::Rung::Fallback);
    });
}

void rungsAgree(CheckEnv& env, Verdict& v) {
    bool native = false;
    for (const vk::RungOption& o : env.ctx.ladder("vxgi-atomics").options) native |= o.rung == vk::Rung::Native && o.available;
    if (!native) {
        v.skip("device lacks float image atomics: only the fallback rung runs");
        return;
    }
    const VoxelScene t = makeVoxelScene();
    Grid grids[2];
    const vk::Rung rungs[2] = {vk::Rung::Native, vk::Rung::Fallback};
    for (int r = 0; r < 2; ++r)
        onRung(env, v, "vxgi-atomics", rungs[r], [&](vk::Context& ctx, vk::ShaderLibrary& shaders) {
            grids[r] = voxelize(ctx, shaders, t, frame::VoxelRaster::Centre);
        });
    if (!v.expect(grids[0].voxels.size() == grids[1].voxels.size() && !grids[0].voxels.empty(), "the grids differ in size"))
        return;
    const std::vector<OracleVoxel> oracle = voxelizeOnCpu(t.quads, t.emissive, {t.light}, grids[0].box);
    size_t single = 0;
    for (size_t i = 0; i < oracle.size(); ++i) {
        if (oracle[i].count != 1 || oracle[i].ambiguous) continue;
        ++single;
        for (uint32_t k = 0; k < 7; ++k) {  // the grid, then the six directional level-0 volumes
            const glm::vec4& a = k == 0 ? grids[0].voxels[i] : grids[0].directions[k - 1][i];
            const glm::vec4& b = k == 0 ? grids[1].voxels[i] : grids[1].directions[k - 1][i];
            // The two fragment shaders are compiled apart: allow one fp16 rounding step (the grid), one storage
            // step of the directions' format (vxgi-volume-format).
            const glm::vec4 step = k == 0 ? glm::vec4(0.0f) : directionStep(grids[0].directionFormat, b);
            for (int c = 0; c < 4; ++c) {
                v.recordError(std::abs(a[c] - b[c]) / std::max(std::abs(b[c]), 1e-6f));
                v.expect(std::abs(a[c] - b[c]) <= 1e-3f * std::abs(b[c]) + 1e-6f + step[c],
                         "voxel " + std::to_string(i) + (k == 0 ? " grid" : " direction " + std::to_string(k - 1)) +
                             " channel " + std::to_string(c) + ": native " + std::to_string(a[c]) + ", fallback " +
                             std::to_string(b[c]));
            }
        }
    }
    v.expect(single > 1000, "too few one-fragment voxels to compare (" + std::to_string(single) + ")");
}

// --shadows raytraced: the voxels' light is shadowed by rays through the BVH (there is no shadow table when the
// voxelization runs). The voxel scene with a blocker between the light and the floor against the oracle with hard
// shadows; the oracle's unshadowed grid must differ in many voxels, or the check could not fail.
void rayTracedShadows(CheckEnv& env, Verdict& v) {
    VoxelScene t = makeVoxelScene();
    t.quads.push_back(placedQuad({0.2f, 0.05f, 0.1f}, {0, 1, 0}, {0.27f, 0.23f}, {0.5f, 0.5f, 0.5f}, true));
    t.emissive.push_back(glm::vec3(0.0f));
    const Grid g = voxelize(env.ctx, env.shaders, t, frame::VoxelRaster::Centre, true);
    if (!v.expect(!g.voxels.empty(), "no grid")) return;
    expectMatchesOracle(v, g, t, env.ctx.ladder("vxgi-atomics").chosen == vk::Rung::Fallback, true);
    const std::vector<OracleVoxel> lit = voxelizeOnCpu(t.quads, t.emissive, {t.light}, g.box, false);
    const std::vector<OracleVoxel> shadowed = voxelizeOnCpu(t.quads, t.emissive, {t.light}, g.box, true);
    size_t darker = 0;
    for (size_t i = 0; i < lit.size(); ++i)
        darker += lit[i].count > 0 && !shadowed[i].ambiguous && shadowed[i].count == lit[i].count &&
                  glm::length(shadowed[i].sum) < 0.5 * glm::length(lit[i].sum);
    v.expect(darker > 500, "the blocker should shadow many voxels (" + std::to_string(darker) + ")");
}

// Over the voxel columns along x (inner ones, away from the box's walls): those the wall's rectangle touches at all,
// those of them holding a wall voxel (the wall's x layer or a neighbour), and untouched ones holding one.
struct Columns {
    size_t touched = 0, covered = 0, outside = 0;
};

Columns wallColumns(const Grid& g, const PlacedQuad& wall) {
    Columns c;
    const scene::Aabb wallBounds = makePlacedQuadScene({wall}).bounds;  // the quad's extent in y and z
    const glm::dvec3 vmin(wallBounds.min), vmax(wallBounds.max);
    const int layer = int(std::floor((double(wall.centre.x) - g.box.gridMin.x) / g.box.voxelSize));
    for (int z = 1; z + 1 < int(kVoxels); ++z)
        for (int y = 1; y + 1 < int(kVoxels); ++y) {
            const double y0 = g.box.gridMin.y + y * double(g.box.voxelSize), y1 = y0 + g.box.voxelSize;
            const double z0 = g.box.gridMin.z + z * double(g.box.voxelSize), z1 = z0 + g.box.voxelSize;
            const bool touches = y1 > vmin.y && y0 < vmax.y && z1 > vmin.z && z0 < vmax.z;
            bool holds = false;
            for (int x = layer - 1; x <= layer + 1; ++x)
                holds = holds || g.voxels[(size_t(z) * kVoxels + y) * kVoxels + x].a > 0.0f;
            c.touched += touches;
            c.covered += touches && holds;
            c.outside += !touches && holds;
        }
    return c;
}

void thinWall(CheckEnv& env, Verdict& v) {
    VoxelScene t = makeVoxelScene();
    t.quads.resize(6);  // the open box's walls only, and a wall (normal +x) one voxel thin inside
    t.quads.push_back(placedQuad({0.013f, -0.012f, 0.021f}, {1, 0, 0}, {0.803f, 0.689f}, {0.8f, 0.8f, 0.8f}, true));
    t.emissive.assign(t.quads.size(), glm::vec3(0.0f));
    onRung(env, v, "conservative-raster", *env.rung, [&](vk::Context& ctx, vk::ShaderLibrary& shaders) {
        for (frame::VoxelRaster raster : {frame::VoxelRaster::Centre, frame::VoxelRaster::Conservative}) {
            const std::string what = raster == frame::VoxelRaster::Centre ? "centre raster" : "conservative raster";
            const Grid g = voxelize(ctx, shaders, t, raster);
            if (!v.expectEq(g.voxels.size(), size_t(kVoxels) * kVoxels * kVoxels, what + ": voxel count")) return;
            const Columns c = wallColumns(g, t.quads.back());
            v.expectEq(c.outside, size_t(0), what + ": untouched columns holding a wall voxel");
            if (raster == frame::VoxelRaster::Conservative)
                v.expectEq(c.covered, c.touched, what + ": touched columns holding a wall voxel (no holes)");
            else
                v.expect(c.covered < c.touched, what + ": covers all " + std::to_string(c.touched) +
                                                    " touched columns: the wall must have edge columns it misses");
        }
    });
}

}  // namespace

std::vector<Check> vxgiChecks() {
    return {
        {"vxgi/voxelize", "vxgi-atomics",
         "occupancy >= 99.5%; rgb and directional level 0 within 0.2% (+1e-5) of the oracle's mean or max",
         voxelizeOnRung},
        {"vxgi/rungs agree", "", "one-fragment voxels within 1e-3 relative", rungsAgree},
        {"vxgi/thin wall", "conservative-raster", "no holes, nothing outside the wall's columns", thinWall},
        {"vxgi/ray-traced shadows", "", "as vxgi/voxelize against the oracle with hard shadows", rayTracedShadows},
    };
}

}  // namespace idk::conformance
