// frame_recipe.cpp: the deferred PBR frame, in order. Every line is one feature; each feature reads what the
// lines above it put into the FrameContext and adds its own products. Features that are off (or that the scene
// does not need) add nothing and allocate nothing. Ports IDKEngine's RasterPipeline.Render frame order
// (reference 1.5, steps 6.6-6.13, 9).
#include "frame/frame_recipe.hpp"

namespace idk::frame {
namespace {

// Display output lights into a transient HDR image that the tonemap writes into the target; Hdr output lights
// straight into the target.
graph::TextureHandle hdrTarget(FrameContext& f) {
    // The upscaler lights a render-size image and writes the output itself (upscale_feature.cpp).
    if (f.settings.output != render::OutputKind::Display && !UpscaleFeature::enabled(f.settings)) return f.output;
    graph::TextureDesc desc;
    desc.format = VK_FORMAT_R16G16B16A16_SFLOAT;
    return f.graph.createTexture("hdr radiance", desc);
}

graph::TextureHandle finish(FrameContext& f) {
    graph::TextureHandle last = f.settings.output == render::OutputKind::Display
                                    ? passes::addTonemapPass(f.graph, f.ctx, f.shaders, f.hdr, f.output,
                                                             f.settings.exposure)
                                    : f.hdr;
    f.graph.markOutput(last);
    return last;
}

}  // namespace

// The point-shadow cubes are released by Renderer::setScene before the old scene they were built from.
void Features::setScene(vk::Context& ctx, const render::GpuScene& scene, uint32_t framesInFlight) {
    transparency.setScene(ctx, scene, framesInFlight);
    transmission.setScene(ctx, scene, framesInFlight);
    culling.setScene();
    vxgi.setScene(scene);
}

void Features::setSourceScene(vk::Context& ctx, const scene::Scene& source, const render::GpuScene& scene,
                              const render::RenderSettings& settings) {
    rtShadows.setScene(ctx, source, scene, settings);
}

graph::TextureHandle recordPbrFrame(FrameContext& f, render::GpuScene& scene, Features& x) {
    x.upscale.beginFrame(f);                                          // --upscale S < 1: render size until its resolve
    x.temporal.beginFrame(f);                                         // jitters f.viewProjection (--aa taa)
    x.environment.addPasses(f);                                       // f.environment
    x.inputs.addPasses(f, scene, x.environment.current(f.settings));  // f.frameConstants, f.scene, f.lights
    // Shadows before the G-buffer: the installed validation layer counts every draw that uses the bindless
    // sampled array (the G-buffer's) as reading the cubes, so their write must not follow such a draw.
    x.pointShadows.addPasses(f, scene);                               // f.pointShadows
    x.vxgi.addPasses(f, x.rtShadows.voxelShadowRays(f));              // f.voxelGrid (--gi vxgi)
    f.gbuffer = x.culling.addGBuffer(f, scene);                       // GPU culling; f.depthPyramid
    x.rtShadows.addPasses(f, scene);                                  // f.pointShadows (--shadows raytraced)
    x.temporal.addMotionVectors(f, scene);                            // f.motionVectors
    x.vrs.beginFrame(f);                                              // f.vrsRates: last frame's shading rates
    x.ssao.addPasses(f);                                              // f.ambientOcclusion
    x.vxgi.addConeTracing(f);                                         // f.indirectLight (--gi vxgi)
    x.ssr.addPasses(f);                                               // f.reflections (--ssr)
    const passes::LightingInputs lighting{f.pointShadows, f.scene.materials, f.vrsRates, f.ambientOcclusion,
                                          f.indirectLight, f.reflections};
    if (x.vrs.hardwareRung()) {
        f.hdr = x.vrs.addHardwareLighting(f, hdrTarget(f), lighting);  // VRS hardware rung: lighting + sky, fragment
    } else {
        f.hdr = passes::addDeferredLightingPass(f.graph, f.ctx, f.shaders, f.gbuffer, f.frameConstants, f.scene.lights,
                                                f.environment, hdrTarget(f), lighting);
        f.hdr = passes::addSkyPass(f.graph, f.ctx, f.shaders, f.gbuffer.depth, f.frameConstants, f.environment,
                                   f.hdr, f.vrsRates);
    }
    x.vrs.addReconstructPass(f);                                      // VRS: fills the pixels not shaded
    x.transmission.addPasses(f, scene);                               // refracts f.hdr behind transmissive surfaces
    x.upscale.keepOpaque(f, x.transparency.enabled());                // upscaler: the reactive term's reference
    x.transparency.addPasses(f, scene);                               // blends into f.hdr
    x.volumetrics.addPasses(f, scene);                                // fogs f.hdr (--volumetrics)
    x.vrs.addClassifyPasses(f);                                       // VRS: rates for the next frame
    x.ssr.keepLitImage(f);                                            // next frame's SSR hits (--ssr)
    x.temporal.addResolve(f);                                         // TAA: f.hdr
    x.upscale.addResolve(f);                                          // upscaler: f.hdr at output size
    x.bloom.addPasses(f);                                             // blends into f.hdr
    x.vxgi.addDebugView(f);                                           // replaces f.hdr (--gi-debug voxels)
    return finish(f);                                                 // tonemap (Display) into f.output
}

void recordCullingWarmup(FrameContext& f, render::GpuScene& scene, Features& x) {
    x.environment.addPasses(f);
    x.inputs.addPasses(f, scene, x.environment.current(f.settings));
    f.gbuffer = x.culling.addGBuffer(f, scene);
    f.graph.markOutput(f.gbuffer.depth);
}

void recordSurfaceIds(FrameContext& f, render::GpuScene& scene, Features& x, graph::TextureHandle ids) {
    x.environment.addPasses(f);
    x.inputs.addPasses(f, scene, x.environment.current(f.settings));
    f.gbuffer = passes::addGBufferPass(f.graph, f.ctx, f.shaders, f.scene, f.frameConstants, &f.log, nullptr, nullptr,
                                       ids);
    f.graph.markOutput(f.gbuffer.ids);
}

}  // namespace idk::frame
