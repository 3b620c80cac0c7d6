// settings_table.cpp: the table of the rasterized frame's options (see settings_table.hpp) and the functions that
// turn it into CLI parsing, help text and JSON. One row per option; a feature's rows sit together.
#include "frame/settings_table.hpp"

#include <array>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>

namespace idk::frame {
namespace {

using render::RenderSettings;
using AntiAliasing = frame::AntiAliasing;

constexpr std::array<uint32_t, 5> kShadowCubeSizes = {128, 256, 512, 1024, 2048};

double cubeSizeIndex(uint32_t size) {
    for (size_t i = 0; i < kShadowCubeSizes.size(); ++i)
        if (kShadowCubeSizes[i] == size) return double(i);
    return 2.0;
}

double voxelSizeIndex(uint32_t size) {
    for (size_t i = 0; i < kVoxelGridSizes.size(); ++i)
        if (kVoxelGridSizes[i] == size) return double(i);
    return 1.0;
}

std::vector<SettingOption> buildTable() {
    std::vector<SettingOption> t;
    // Tonemap and environment.
    t.push_back({"--exposure", "Tonemap", "exposure", "linear exposure before tonemapping", OptionKind::Number,
                 0.0, 64.0, {}, [](const RenderSettings& s) { return double(s.exposure); },
                 [](RenderSettings& s, double v) { s.exposure = float(v); }, true});
    t.push_back({"--env-intensity", "Environment", "environment intensity",
                 "scale of the sky and ambient light (0 = black sky, no ambient)", OptionKind::Number, 0.0, 16.0, {},
                 [](const RenderSettings& s) { return double(s.environmentIntensity); },
                 [](RenderSettings& s, double v) { s.environmentIntensity = float(v); }});
    // Point-light cube shadows.
    t.push_back({"--shadow-lights", "Shadows", "shadow-casting lights",
                 "lights that cast shadows (point/wide spot: cube; directional: cascades; spot: map), the first N in light "
                 "order (0 = none)",
                 OptionKind::Integer, 0.0, 16.0, {},
                 [](const RenderSettings& s) { return double(s.pointShadows.maxLights); },
                 [](RenderSettings& s, double v) { s.pointShadows.maxLights = uint32_t(v); }});
    t.push_back({"--shadow-size", "Shadows", "shadow cube size", "cube shadow face size in texels",
                 OptionKind::Choice, 0.0, 0.0, {"128", "256", "512", "1024", "2048"},
                 [](const RenderSettings& s) { return cubeSizeIndex(s.pointShadows.resolution); },
                 [](RenderSettings& s, double v) { s.pointShadows.resolution = kShadowCubeSizes[size_t(v)]; }});
    // Variable-rate shading (frame/vrs_feature.hpp).
    t.push_back({"--vrs", "Variable-rate shading", "variable-rate shading",
                 "lighting and sky at per-tile rates classified from the previous frame", OptionKind::Choice, 0.0,
                 0.0, {"off", "on"}, [](const RenderSettings& s) { return s.vrs.enabled ? 1.0 : 0.0; },
                 [](RenderSettings& s, double v) { s.vrs.enabled = v != 0.0; }});
    t.push_back({"--vrs-debug", "Variable-rate shading", "rate overlay",
                 "tint each tile by its shading rate (none 1x1, blue 2x1, green 2x2, yellow 4x2, red 4x4)",
                 OptionKind::Toggle, 0.0, 1.0, {}, [](const RenderSettings& s) { return s.vrs.debug ? 1.0 : 0.0; },
                 [](RenderSettings& s, double v) { s.vrs.debug = v != 0.0; }});
    t.push_back({"--vrs-rate", "Variable-rate shading", "fixed rate",
                 "every tile at one rate instead of the classifier's (comparisons, benchmarks)", OptionKind::Choice,
                 0.0, 0.0, {"auto", "1x1", "2x1", "2x2", "4x2", "4x4"},
                 [](const RenderSettings& s) { return double(s.vrs.fixedRate + 1); },
                 [](RenderSettings& s, double v) { s.vrs.fixedRate = int(v) - 1; }});
    // GPU culling (frame/culling_feature.hpp).
    t.push_back({"--culling", "Culling", "culling", "GPU culling of the draws (off: draw every instance)",
                 OptionKind::Choice, 0.0, 0.0, {"off", "frustum", "hiz"},
                 [](const RenderSettings& s) { return double(s.culling.mode); },
                 [](RenderSettings& s, double v) { s.culling.mode = frame::CullingMode(v); }});
    t.push_back({"--geometry", "Culling", "geometry path",
                 "how the culled G-buffer draws: mesh (task + mesh shaders cull meshlets, needs VK_EXT_mesh_shader), "
                 "mdi (vkCmdDrawIndexedIndirectCount of whole instances) or auto (the mesh-shading ladder's rung)",
                 OptionKind::Choice, 0.0, 0.0, {"auto", "mesh", "mdi"},
                 [](const RenderSettings& s) { return double(s.culling.geometry); },
                 [](RenderSettings& s, double v) { s.culling.geometry = frame::GeometryPath(v); }});
    t.push_back({"--cull-freeze", "Culling", "freeze culling camera",
                 "keep culling with the camera of the frame this was turned on (occlusion pauses)", OptionKind::Toggle,
                 0.0, 1.0, {}, [](const RenderSettings& s) { return s.culling.freeze ? 1.0 : 0.0; },
                 [](RenderSettings& s, double v) { s.culling.freeze = v != 0.0; }});
    // Temporal anti-aliasing (frame/temporal_feature.hpp).
    t.push_back({"--aa", "Temporal", "anti-aliasing",
                 "anti-aliasing: none, taa (jittered frames + history; with --upscale S < 1 the temporal upscaler), "
                 "or upscale (the upscaler at any S, 1 included)",
                 OptionKind::Choice, 0.0, 0.0, {"none", "taa", "upscale"},
                 [](const RenderSettings& s) { return double(s.temporal.aa); },
                 [](RenderSettings& s, double v) { s.temporal.aa = AntiAliasing(int(v)); }});
    t.push_back({"--temporal-frames", "Temporal", "temporal frames",
                 "jitter phases; a still with --aa taa renders this many frames to converge", OptionKind::Integer,
                 1.0, 64.0, {}, [](const RenderSettings& s) { return double(s.temporal.frames); },
                 [](RenderSettings& s, double v) { s.temporal.frames = uint32_t(v); }});
    t.push_back({"--upscale", "Temporal", "upscale scale",
                 "render scale S of the temporal upscaler (--aa taa with S < 1, or --aa upscale): render at S x "
                 "output size, reconstruct at output size (1 = no upscaling; needs --aa taa or upscale)",
                 OptionKind::Number, 0.5, 1.0, {}, [](const RenderSettings& s) { return double(s.temporal.upscale); },
                 [](RenderSettings& s, double v) { s.temporal.upscale = float(v); }});
    // Bloom (frame/bloom_feature.hpp).
    t.push_back({"--bloom", "Bloom", "bloom", "energy-conserving bloom (13-tap downsample, tent upsample)",
                 OptionKind::Toggle, 0.0, 1.0, {}, [](const RenderSettings& s) { return s.bloom.enabled ? 1.0 : 0.0; },
                 [](RenderSettings& s, double v) { s.bloom.enabled = v != 0.0; }});
    t.push_back({"--bloom-strength", "Bloom", "bloom strength", "blend toward the blurred image", OptionKind::Number,
                 0.0, 1.0, {}, [](const RenderSettings& s) { return double(s.bloom.strength); },
                 [](RenderSettings& s, double v) { s.bloom.strength = float(v); }});
    // Screen-space ambient occlusion (frame/ssao_feature.hpp).
    t.push_back({"--ssao", "SSAO", "ambient occlusion", "screen-space ambient occlusion of the ambient light",
                 OptionKind::Toggle, 0.0, 1.0, {}, [](const RenderSettings& s) { return s.ssao.enabled ? 1.0 : 0.0; },
                 [](RenderSettings& s, double v) { s.ssao.enabled = v != 0.0; }});
    t.push_back({"--ssao-radius", "SSAO", "radius", "world-space reach of the occlusion rays", OptionKind::Number,
                 0.001, 100.0, {}, [](const RenderSettings& s) { return double(s.ssao.radius); },
                 [](RenderSettings& s, double v) { s.ssao.radius = float(v); }, true});
    t.push_back({"--ssao-samples", "SSAO", "samples", "occlusion rays per pixel per frame", OptionKind::Integer, 1.0,
                 64.0, {}, [](const RenderSettings& s) { return double(s.ssao.samples); },
                 [](RenderSettings& s, double v) { s.ssao.samples = uint32_t(v); }});
    // Voxel global illumination (frame/vxgi_feature.hpp).
    t.push_back({"--gi", "Global illumination", "global illumination",
                 "indirect light: none (environment ambient only) or vxgi (voxel cone tracing)", OptionKind::Choice,
                 0.0, 0.0, {"none", "vxgi"}, [](const RenderSettings& s) { return double(s.vxgi.mode); },
                 [](RenderSettings& s, double v) { s.vxgi.mode = frame::GiMode(v); }});
    t.push_back({"--voxels", "Global illumination", "voxel grid size", "VXGI grid voxels per side",
                 OptionKind::Choice, 0.0, 0.0, {"64", "128", "256", "384", "512"},
                 [](const RenderSettings& s) { return voxelSizeIndex(s.vxgi.voxels); },
                 [](RenderSettings& s, double v) { s.vxgi.voxels = kVoxelGridSizes[size_t(v)]; }});
    t.push_back({"--gi-slabs", "Global illumination", "voxelization slabs",
                 "VXGI voxelization in z-slabs (accumulators of 1/S of the grid, passes repeated per slab): auto "
                 "(the fewest that fit the memory budget) or 1, 2, 4, 8",
                 OptionKind::Choice, 0.0, 0.0, {"auto", "1", "2", "4", "8"},
                 [](const RenderSettings& s) {
                     return s.vxgi.slabs == 0 ? 0.0 : double(std::countr_zero(s.vxgi.slabs) + 1);
                 },
                 [](RenderSettings& s, double v) { s.vxgi.slabs = v < 1.0 ? 0u : 1u << (uint32_t(v) - 1u); }});
    t.push_back({"--gi-cones", "Global illumination", "ring cones",
                 "VXGI diffuse cones around the normal's cone (cosine-weighted set of 1 + N)", OptionKind::Integer,
                 3.0, 16.0, {}, [](const RenderSettings& s) { return double(s.vxgi.ringCones); },
                 [](RenderSettings& s, double v) { s.vxgi.ringCones = uint32_t(v); }});
    t.push_back({"--gi-footprint", "Global illumination", "footprint cones",
                 "VXGI: each diffuse cone traced as 1, 4 or 7 narrower cones across its footprint", OptionKind::Choice,
                 0.0, 0.0, {"1", "4", "7"},
                 [](const RenderSettings& s) {
                     return s.vxgi.footprintCones >= 7 ? 2.0 : (s.vxgi.footprintCones >= 4 ? 1.0 : 0.0);
                 },
                 [](RenderSettings& s, double v) { s.vxgi.footprintCones = v >= 2.0 ? 7u : (v >= 1.0 ? 4u : 1u); }});
    t.push_back({"--gi-step", "Global illumination", "cone step", "VXGI cone march step in sampled cells",
                 OptionKind::Number, 0.1, 1.0, {}, [](const RenderSettings& s) { return double(s.vxgi.stepFactor); },
                 [](RenderSettings& s, double v) { s.vxgi.stepFactor = float(v); }});
    t.push_back({"--gi-resolution", "Global illumination", "cone resolution",
                 "VXGI cone tracing per pixel (full) or per 2x2 block with an edge-aware upsample (half)",
                 OptionKind::Choice, 0.0, 0.0, {"full", "half"},
                 [](const RenderSettings& s) { return double(s.vxgi.resolution); },
                 [](RenderSettings& s, double v) { s.vxgi.resolution = frame::GiResolution(v); }});
    t.push_back({"--gi-raster", "Global illumination", "voxel raster",
                 "VXGI voxelization: conservative (thin walls never leak) or centre (pixel centres only)",
                 OptionKind::Choice, 0.0, 0.0, {"conservative", "centre"},
                 [](const RenderSettings& s) { return double(s.vxgi.raster); },
                 [](RenderSettings& s, double v) { s.vxgi.raster = frame::VoxelRaster(v); }});
    t.push_back({"--gi-grid", "Global illumination", "voxel grid",
                 "VXGI grid placement: fit (the scene's bounds) or camera (same size, follows the camera in steps of "
                 "1/8 of the grid)",
                 OptionKind::Choice, 0.0, 0.0, {"fit", "camera"},
                 [](const RenderSettings& s) { return double(s.vxgi.grid); },
                 [](RenderSettings& s, double v) { s.vxgi.grid = frame::VoxelGridPlacement(v); }});
    t.push_back({"--gi-voxel-draws", "Global illumination", "voxel draws",
                 "VXGI voxelization: three draws (one per axis) or single (a geometry shader picks each triangle's axis)",
                 OptionKind::Choice, 0.0, 0.0, {"three", "single"},
                 [](const RenderSettings& s) { return double(s.vxgi.draws); },
                 [](RenderSettings& s, double v) { s.vxgi.draws = frame::VoxelDraws(v); }});
    t.push_back({"--gi-debug", "Global illumination", "voxel debug view",
                 "show the voxels instead of the lit image: off or voxels (first cell with coverage > 0.5 along "
                 "each camera ray; needs --gi vxgi)",
                 OptionKind::Choice, 0.0, 0.0, {"off", "voxels"},
                 [](const RenderSettings& s) { return double(s.vxgi.debug); },
                 [](RenderSettings& s, double v) { s.vxgi.debug = frame::GiDebug(v); }});
    t.push_back({"--gi-debug-level", "Global illumination", "debug level",
                 "voxel debug view's level: 0 the grid, L >= 1 the directional volumes' level L (at most log2 voxels)",
                 OptionKind::Integer, 0.0, 9.0, {}, [](const RenderSettings& s) { return double(s.vxgi.debugLevel); },
                 [](RenderSettings& s, double v) { s.vxgi.debugLevel = uint32_t(v); }});
    // Directional cascades and spot maps (frame/point_shadow_feature.cpp, render/light_shadow_maps.hpp).
    t.push_back({"--shadow-cascades", "Shadows", "cascades", "cascaded shadow maps per directional light",
                 OptionKind::Integer, 1.0, 4.0, {},
                 [](const RenderSettings& s) { return double(s.lightShadows.cascades); },
                 [](RenderSettings& s, double v) { s.lightShadows.cascades = uint32_t(v); }});
    t.push_back({"--shadow-map-size", "Shadows", "cascade/spot map size", "directional cascade and spot map size",
                 OptionKind::Choice, 0.0, 0.0, {"128", "256", "512", "1024", "2048"},
                 [](const RenderSettings& s) { return cubeSizeIndex(s.lightShadows.resolution); },
                 [](RenderSettings& s, double v) { s.lightShadows.resolution = kShadowCubeSizes[size_t(v)]; }});
    t.push_back({"--shadow-distance", "Shadows", "cascade distance",
                 "view distance the cascades cover (0 = to the far end of the scene)", OptionKind::Number, 0.0, 1e4,
                 {}, [](const RenderSettings& s) { return double(s.lightShadows.distance); },
                 [](RenderSettings& s, double v) { s.lightShadows.distance = float(v); }});
    t.push_back({"--shadows", "Shadows", "shadow mode",
                 "maps: cubes, cascades, spot maps; raytraced: one shadow ray per pixel and light (set before loading)",
                 OptionKind::Choice, 0.0, 0.0, {"maps", "raytraced"},
                 [](const RenderSettings& s) { return s.lightShadows.rayTraced ? 1.0 : 0.0; },
                 [](RenderSettings& s, double v) { s.lightShadows.rayTraced = v > 0.5; }});
    // Atmospheric-scattering sky (render/atmosphere.hpp), baked when the sun settings change.
    t.push_back({"--sky", "Environment", "sky", "hdr: the environment file; atmosphere: Rayleigh + Mie sky of the sun",
                 OptionKind::Choice, 0.0, 0.0, {"hdr", "atmosphere"},
                 [](const RenderSettings& s) { return s.atmosphere.enabled ? 1.0 : 0.0; },
                 [](RenderSettings& s, double v) { s.atmosphere.enabled = v > 0.5; }});
    t.push_back({"--sun-elevation", "Environment", "sun elevation", "atmosphere: sun degrees above the horizon",
                 OptionKind::Number, -10.0, 90.0, {},
                 [](const RenderSettings& s) { return double(s.atmosphere.sunElevation); },
                 [](RenderSettings& s, double v) { s.atmosphere.sunElevation = float(v); }});
    t.push_back({"--sun-azimuth", "Environment", "sun azimuth", "atmosphere: degrees from -Z towards +X",
                 OptionKind::Number, -360.0, 360.0, {},
                 [](const RenderSettings& s) { return double(s.atmosphere.sunAzimuth); },
                 [](RenderSettings& s, double v) { s.atmosphere.sunAzimuth = float(v); }});
    // Volumetric lighting (frame/volumetrics_feature.hpp).
    t.push_back({"--volumetrics", "Volumetrics", "volumetric lighting",
                 "in-scattering of every light (with its shadows) in a homogeneous medium", OptionKind::Toggle, 0.0,
                 1.0, {}, [](const RenderSettings& s) { return s.volumetrics.enabled ? 1.0 : 0.0; },
                 [](RenderSettings& s, double v) { s.volumetrics.enabled = v != 0.0; }});
    t.push_back({"--fog-density", "Volumetrics", "density", "scattering coefficient per metre", OptionKind::Number,
                 0.0, 10.0, {}, [](const RenderSettings& s) { return double(s.volumetrics.density); },
                 [](RenderSettings& s, double v) { s.volumetrics.density = float(v); }});
    t.push_back({"--fog-anisotropy", "Volumetrics", "anisotropy", "Henyey-Greenstein g (> 0: forward scattering)",
                 OptionKind::Number, -0.95, 0.95, {},
                 [](const RenderSettings& s) { return double(s.volumetrics.anisotropy); },
                 [](RenderSettings& s, double v) { s.volumetrics.anisotropy = float(v); }});
    t.push_back({"--volumetrics-scale", "Volumetrics", "resolution divisor", "march at 1/2 or 1/4 resolution",
                 OptionKind::Choice, 0.0, 0.0, {"2", "4"},
                 [](const RenderSettings& s) { return s.volumetrics.scale == 4 ? 1.0 : 0.0; },
                 [](RenderSettings& s, double v) { s.volumetrics.scale = v > 0.5 ? 4u : 2u; }});
    // Order-independent transparency (passes/oit_weighted.cpp); sorted is the exact reference.
    t.push_back({"--oit", "Transparency", "transparency",
                 "sorted: back-to-front over (exact); weighted: weighted blended OIT; layers: 10 nearest per pixel",
                 OptionKind::Choice, 0.0, 0.0, {"sorted", "weighted", "layers"},
                 [](const RenderSettings& s) { return double(static_cast<uint8_t>(s.oit)); },
                 [](RenderSettings& s, double v) { s.oit = static_cast<render::OitMode>(std::lround(v)); }});
    // KHR_materials_transmission (frame/transmission_feature.hpp): screen-space refraction of the opaque frame.
    t.push_back({"--transmission", "Transparency", "transmission",
                 "screen: transmissive materials show the opaque frame refracted behind them; off: drawn opaque",
                 OptionKind::Choice, 0.0, 0.0, {"screen", "off"},
                 [](const RenderSettings& s) { return double(static_cast<uint8_t>(s.transmission)); },
                 [](RenderSettings& s, double v) {
                     s.transmission = static_cast<render::TransmissionMode>(std::lround(v));
                 }});
    // Soft ray-traced shadows (rt_shadows/mask_body.h): sphere lights sampled stochastically.
    t.push_back({"--light-radius", "Shadows", "light radius",
                 "raytraced: point and spot lights as spheres of this radius in metres (0: hard shadows)",
                 OptionKind::Number, 0.0, 100.0, {}, [](const RenderSettings& s) { return double(s.lightShadows.lightRadius); },
                 [](RenderSettings& s, double v) { s.lightShadows.lightRadius = float(v); }});
    t.push_back({"--soft-shadow-rays", "Shadows", "soft shadow rays", "raytraced with a light radius: rays per pixel and light",
                 OptionKind::Integer, 1.0, 256.0, {},
                 [](const RenderSettings& s) { return double(s.lightShadows.softShadowRays); },
                 [](RenderSettings& s, double v) { s.lightShadows.softShadowRays = uint32_t(v); }});
    // Screen-space reflections (frame/ssr_feature.hpp).
    t.push_back({"--ssr", "SSR", "screen-space reflections",
                 "Hi-Z screen-space reflections as the specular ambient of smooth surfaces", OptionKind::Toggle, 0.0,
                 1.0, {}, [](const RenderSettings& s) { return s.ssr.enabled ? 1.0 : 0.0; },
                 [](RenderSettings& s, double v) { s.ssr.enabled = v != 0.0; }});
    t.push_back({"--ssr-steps", "SSR", "max steps", "Hi-Z march iterations per reflection ray", OptionKind::Integer,
                 1.0, 1024.0, {}, [](const RenderSettings& s) { return double(s.ssr.maxSteps); },
                 [](RenderSettings& s, double v) { s.ssr.maxSteps = uint32_t(v); }});
    t.push_back({"--ssr-thickness", "SSR", "thickness", "world units a surface extends behind its depth",
                 OptionKind::Number, 0.001, 100.0, {}, [](const RenderSettings& s) { return double(s.ssr.thickness); },
                 [](RenderSettings& s, double v) { s.ssr.thickness = float(v); }, true});
    return t;
}

std::string key(const SettingOption& o) { return std::string(o.flag).substr(2); }

std::string choiceList(const SettingOption& o) {
    std::string list;
    for (const char* c : o.choices) list += (list.empty() ? "" : "|") + std::string(c);
    return list;
}

std::string formatNumber(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", v);
    return text;
}

}  // namespace

const std::vector<SettingOption>& settingOptions() {
    static const std::vector<SettingOption> table = buildTable();
    return table;
}

core::CliSpec withSettingOptions(core::CliSpec spec) {
    for (const SettingOption& o : settingOptions())
        (o.kind == OptionKind::Toggle ? spec.flags : spec.options).insert(o.flag);
    return spec;
}

void applySettingOptions(const core::CliArgs& args, render::RenderSettings& settings) {
    for (const SettingOption& o : settingOptions()) {
        if (o.kind == OptionKind::Toggle) {
            if (args.has(o.flag)) o.set(settings, 1.0);
            continue;
        }
        const std::optional<std::string> text = args.get(o.flag);
        if (!text) continue;
        if (o.kind == OptionKind::Choice) {
            size_t i = 0;
            while (i < o.choices.size() && *text != o.choices[i]) ++i;
            if (i == o.choices.size())
                throw core::CliError(std::string(o.flag) + " '" + *text + "': use " + choiceList(o));
            o.set(settings, double(i));
            continue;
        }
        const double v = core::parseNumber(o.flag, *text);
        const bool whole = o.kind == OptionKind::Number || v == std::floor(v);
        if (!(v >= o.min && v <= o.max) || !whole)
            throw core::CliError(std::string(o.flag) + " '" + *text + "': give " +
                                 (o.kind == OptionKind::Integer ? "a whole number" : "a number") + " in [" +
                                 formatNumber(o.min) + ", " + formatNumber(o.max) + "]");
        o.set(settings, v);
    }
    // The upscaler reconstructs from jittered frames and their history: with --aa none there is none, and a
    // render scale that silently did nothing would mislead.
    if (const std::optional<std::string> scale = args.get("--upscale"); scale && settings.temporal.aa == AntiAliasing::None)
        throw core::CliError("--upscale '" + *scale + "': the temporal upscaler needs --aa taa (or --aa upscale); "
                             "with --aa none nothing is upscaled");
    // The debug view shows the voxel grid, which only --gi vxgi builds.
    if (const std::optional<std::string> debug = args.get("--gi-debug");
        debug && settings.vxgi.debug != frame::GiDebug::Off && settings.vxgi.mode != frame::GiMode::Vxgi)
        throw core::CliError("--gi-debug '" + *debug + "': the voxel debug view needs --gi vxgi (there is no voxel "
                             "grid with --gi none)");
    if (const std::optional<std::string> level = args.get("--gi-debug-level")) {
        uint32_t maxLevel = 0;
        while ((settings.vxgi.voxels >> (maxLevel + 1)) > 0) ++maxLevel;
        if (settings.vxgi.debugLevel > maxLevel)
            throw core::CliError("--gi-debug-level '" + *level + "': " + std::to_string(settings.vxgi.voxels) +
                                 "^3 voxels have levels 0 to " + std::to_string(maxLevel));
    }
}

std::string optionValueText(const SettingOption& o, const render::RenderSettings& settings) {
    const double v = o.get(settings);
    switch (o.kind) {
    case OptionKind::Choice: return o.choices.at(size_t(v));
    case OptionKind::Toggle: return v != 0.0 ? "on" : "off";
    default: return formatNumber(v);
    }
}

std::string settingOptionsHelp() {
    const render::RenderSettings defaults;
    std::string help;
    for (const SettingOption& o : settingOptions()) {
        std::string usage = std::string("  ") + o.flag;
        if (o.kind == OptionKind::Choice) usage += " " + choiceList(o);
        else if (o.kind != OptionKind::Toggle) usage += o.kind == OptionKind::Integer ? " N" : " X";
        usage.resize(std::max<size_t>(usage.size() + 1, 19), ' ');
        help += usage + o.help;
        if (o.kind != OptionKind::Toggle) {
            if (o.kind != OptionKind::Choice)
                help += " (" + formatNumber(o.min) + " to " + formatNumber(o.max) + ";";
            else
                help += " (";
            help += " default " + optionValueText(o, defaults) + ")";
        }
        help += "\n";
    }
    return help;
}

nlohmann::json settingsJson(const render::RenderSettings& settings) {
    nlohmann::json j = nlohmann::json::object();
    for (const SettingOption& o : settingOptions()) {
        const double v = o.get(settings);
        switch (o.kind) {
        case OptionKind::Choice: j[key(o)] = o.choices.at(size_t(v)); break;
        case OptionKind::Toggle: j[key(o)] = v != 0.0; break;
        case OptionKind::Integer: j[key(o)] = int64_t(v); break;
        case OptionKind::Number: j[key(o)] = v; break;
        }
    }
    return j;
}

}  // namespace idk::frame
