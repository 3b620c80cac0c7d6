// frame_recipe.hpp: the deferred PBR frame as one ordered list of features (frame_recipe.cpp), and the features'
// persistent state. To add a feature: a settings struct and a class in its own files under engine/frame/, a member
// here, one line in recordPbrFrame at its place in the frame, its options in settings_table.cpp.
#pragma once
#include "frame/culling_feature.hpp"
#include "frame/bloom_feature.hpp"
#include "frame/environment_feature.hpp"
#include "frame/frame_context.hpp"
#include "frame/frame_inputs.hpp"
#include "frame/point_shadow_feature.hpp"
#include "frame/rt_shadow_feature.hpp"
#include "frame/ssao_feature.hpp"
#include "frame/temporal_feature.hpp"
#include "frame/upscale_feature.hpp"
#include "frame/volumetrics_feature.hpp"
#include "frame/transparency_feature.hpp"
#include "frame/transmission_feature.hpp"
#include "frame/vrs_feature.hpp"
#include "frame/vxgi_feature.hpp"
#include "frame/ssr_feature.hpp"
#include "render/gpu_scene.hpp"

namespace idk::frame {

struct Features {
    explicit Features(vk::Context& ctx)
        : inputs(ctx), environment(ctx), vrs(ctx), culling(ctx), temporal(ctx), ssao(ctx), vxgi(ctx) {}
    void setScene(vk::Context& ctx, const render::GpuScene& scene, uint32_t framesInFlight);
    // What needs the source scene (ray-traced shadows build its BVH); after setScene above.
    void setSourceScene(vk::Context& ctx, const scene::Scene& source, const render::GpuScene& scene,
                        const render::RenderSettings& settings);

    FrameInputs inputs;
    EnvironmentFeature environment;
    PointShadowFeature pointShadows;
    TransparencyFeature transparency;
    TransmissionFeature transmission;
    VrsFeature vrs;
    CullingFeature culling;
    TemporalFeature temporal;
    BloomFeature bloom;
    SsaoFeature ssao;
    VxgiFeature vxgi;
    RtShadowFeature rtShadows;
    VolumetricsFeature volumetrics;
    UpscaleFeature upscale;
    SsrFeature ssr;
};

// Declares the whole PBR frame into f.graph, ending in f.output (imported by the caller): the tonemapped image
// for Display output, else the linear HDR image itself. Returns the output's last version, marked as the
// graph's output.
graph::TextureHandle recordPbrFrame(FrameContext& f, render::GpuScene& scene, Features& features);

// The first steps of the frame up to the culled G-buffer, its depth marked as the graph's output: a still image's
// warm-up frames for --culling hiz, which leave the visibility bits that the real frame's early phase draws
// (without them a single frame's early phase draws nothing and occlusion culls nothing).
void recordCullingWarmup(FrameContext& f, render::GpuScene& scene, Features& features);

// The first steps of the frame and an unculled G-buffer that also writes the surface-ID buffer into `ids` (RG32UI:
// draw, triangle; marked as the graph's output): which draws and triangles contribute a pixel, the ground truth
// of culling's benchmarks.
void recordSurfaceIds(FrameContext& f, render::GpuScene& scene, Features& features, graph::TextureHandle ids);

}  // namespace idk::frame
