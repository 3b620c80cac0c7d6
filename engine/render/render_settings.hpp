// render_settings.hpp: what a rasterized frame is asked to do. Each feature owns a settings struct (declared in
// its own header under engine/frame/) that is a member here; frame/settings_table.cpp lists the options a user may
// set (CLI flags, viewer panels and the --stats --json record are all generated from that one table).
#pragma once
#include <cstdint>
#include <filesystem>
#include <optional>

#include "frame/vrs_settings.hpp"
#include "frame/bloom_settings.hpp"
#include "frame/ssao_settings.hpp"
#include "frame/ssr_settings.hpp"
#include "frame/temporal_settings.hpp"
#include "frame/vxgi_settings.hpp"
#include "render/point_shadow_maps.hpp"
#include "frame/culling_settings.hpp"
#include "render/light_shadow_maps.hpp"
#include "render/atmosphere.hpp"
#include "frame/volumetric_settings.hpp"

namespace idk::render {

enum class Shading : uint8_t { Pbr, Lambert };
// Transparency: Sorted = BLEND draws back to front, "over" (the exact reference); Weighted = weighted blended OIT;
// Layers = the 10 nearest fragments per pixel, composited in order (passes/oit_layers.cpp).
enum class OitMode : uint8_t { Sorted, Weighted, Layers };
// KHR_materials_transmission in the rasterizer: Screen = the opaque frame refracted behind transmissive surfaces
// (frame/transmission_feature.hpp); Off = the surfaces drawn opaque (their reflected lobes only).
enum class TransmissionMode : uint8_t { Screen, Off };
enum class OutputKind : uint8_t {
    Display,  // AgX-tonemapped, sRGB-encoded 8-bit (what a PNG stores)
    Hdr,      // linear radiance before tonemapping (what an EXR stores); no tonemap pass
};

struct RenderSettings {
    Shading shading = Shading::Pbr;        // fixed once a scene is set
    OutputKind output = OutputKind::Display;  // ignored by Lambert (always linear HDR)
    float exposure = 1.0f;                 // linear scale before the tonemap curve
    float environmentIntensity = 1.0f;     // scales the sky and the ambient light (0: black, no ambient)
    // Equirectangular HDR environment: nullopt = defaultEnvironmentPath(); an empty path = constant grey 0.5.
    // A file that cannot be read falls back to the constant with a warning.
    std::optional<std::filesystem::path> environment;
    PointShadowSettings pointShadows;  // which lights cast cube shadows, and the cube resolution
    frame::VrsSettings vrs;            // variable-rate shading of lighting and sky (off by default)
    frame::CullingSettings culling;    // GPU culling of the draws (frame/culling_feature.hpp)
    frame::TemporalSettings temporal;  // --aa, --temporal-frames (frame/temporal_feature.hpp)
    frame::BloomSettings bloom;        // --bloom, --bloom-strength (frame/bloom_feature.hpp)
    frame::SsaoSettings ssao;          // --ssao, --ssao-radius, --ssao-samples (frame/ssao_feature.hpp)
    frame::VxgiSettings vxgi;          // voxel global illumination (--gi, --voxels)
    LightShadowSettings lightShadows;  // directional cascades and spot maps
    AtmosphereSettings atmosphere;     // `--sky atmosphere`: the baked single-scattering sky as the environment
    frame::VolumetricSettings volumetrics;  // `--volumetrics`: in-scattering in a homogeneous medium
    OitMode oit = OitMode::Sorted;     // `--oit sorted|weighted|layers`
    TransmissionMode transmission = TransmissionMode::Screen;  // `--transmission screen|off`
    frame::SsrSettings ssr;            // --ssr, --ssr-steps, --ssr-thickness (frame/ssr_feature.hpp)
};

}  // namespace idk::render
