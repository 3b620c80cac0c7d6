#version 460
// lighting_rate.frag.glsl: deferred lighting and the sky in one fullscreen fragment pass, for the hardware VRS
// rungs: the rasterizer runs one invocation per coarse fragment (the KHR rate attachment / NV shading-rate image
// built from the classifier's rates) and the colour attachment broadcasts its output to every pixel it covers.
// Each invocation shades the anchor (top-left pixel) of its tile's coarse cell, the pixel the software rung
// shades, with the same per-pixel code (include/deferred_lighting_pixel.glsl, include/sky_pixel.glsl); where a
// device clamps a rate to a smaller supported fragment, several fragments shade the same anchor. Counts its
// invocations with an atomic (helper invocations' atomics have no effect, so only real fragments count).
#extension GL_GOOGLE_include_directive : require
#define IDK_VRS_FRAGMENT_STAGE 1  // include/vrs_rates.glsl: leave out the compute-only helper
#include "scene_buffers.glsl"
#include "bindless.glsl"
#include "vrs_rates.glsl"
#include "vrs_hardware_types.h"
#include "deferred_lighting_pixel.glsl"
#include "sky_pixel.glsl"

layout(push_constant, scalar) uniform Push { VrsLightingRatePush q; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer InvocationCount { uint count; };
layout(location = 0) out vec4 outRadiance;

void main() {
    GpuFrame f = FrameBuffer(q.lighting.frame).frame;
    // gl_FragCoord is the centre of the (possibly coarse) fragment; its floor lies inside the fragment, whose area
    // is aligned to its size, so rounding down to the cell gives the cell's anchor.
    uvec2 inside = uvec2(gl_FragCoord.xy);
    uvec2 cell = vrsCellSize(vrsTileRate(VrsRatesRef(q.lighting.vrsRates), inside));
    ivec2 anchor = ivec2(inside / cell * cell);
    atomicAdd(InvocationCount(q.invocations).count, 1u);

    vec4 radiance;
    if (!deferredLightingPixel(q.lighting, f, anchor, radiance))
        radiance = vec4(skyPixelRadiance(f, anchor), 0.0);  // alpha 0: sky, as sky.comp
    outRadiance = radiance;
}
