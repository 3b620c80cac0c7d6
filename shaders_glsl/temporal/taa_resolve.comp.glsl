#version 460
// taa_resolve.comp.glsl: temporal anti-aliasing. Per pixel: the motion vector of the nearest surface in the 3x3
// neighbourhood (dilation; background pixels are reprojected from the camera matrices), last frame's resolved
// colour at the reprojected position with a 16-tap Catmull-Rom filter, rejection of disoccluded history (depth:
// the history's surface is not this pixel's static surface; velocity: the history's motion differs from this
// pixel's), variance clipping of the history to this frame's 3x3 neighbourhood in YCoCg (Salvi 2016), and an
// accumulation whose weight is kept per pixel in alpha (a running mean up to maxWeight samples, so a still image
// converges to the mean of the jittered frames; a frame where nothing moved keeps the whole history). Ports IDKEngine's TAAResolve/compute.glsl (reference 2.5) with
// YCoCg variance clipping and disocclusion tests that the original lacks (it clamps RGB to the min/max box).
// A real GPU would fetch the history with 9 bilinear taps through a sampler; the set's storage view is read here
// (see shared/deferred_types.h on why frame images are not sampled), so the 16 taps are explicit.
#extension GL_GOOGLE_include_directive : require
#include "scene_buffers.glsl"
#include "bindless.glsl"
#include "temporal_types.h"
#include "temporal_common.glsl"

layout(local_size_x = kTemporalGroupSize, local_size_y = kTemporalGroupSize) in;
layout(push_constant, scalar) uniform Push { TaaPush p; };

vec3 currentYCoCg(ivec2 q, ivec2 size) {
    return rgbToYCoCg(imageLoad(gImagesRgba16f[p.color], clamp(q, ivec2(0), size - 1)).rgb);
}

// Catmull-Rom through the history (in pixels; pixel centres at +0.5), clamped to the image.
vec4 sampleHistoryCatmullRom(vec2 position, ivec2 size) {
    vec2 f = position - 0.5;
    ivec2 base = ivec2(floor(f));
    vec2 t = f - vec2(base);
    vec4 wx = catmullRomWeights(t.x), wy = catmullRomWeights(t.y);
    vec4 sum = vec4(0.0);
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) {
            ivec2 q = clamp(base + ivec2(i - 1, j - 1), ivec2(0), size - 1);
            sum += wx[i] * wy[j] * imageLoad(gImagesRgba16f[p.history], q);
        }
    return sum;
}

void main() {
    GpuTemporalFrame t = TemporalBuffer(p.temporal).t;
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = ivec2(t.extent);
    if (any(greaterThanEqual(pixel, size))) return;

    // This frame's neighbourhood: YCoCg moments, and the nearest surface (its motion moves the edge).
    vec3 m1 = vec3(0.0), m2 = vec3(0.0);
    float nearest = 2.0;
    ivec2 nearestPixel = pixel;
    for (int y = -1; y <= 1; ++y)
        for (int x = -1; x <= 1; ++x) {
            ivec2 q = clamp(pixel + ivec2(x, y), ivec2(0), size - 1);
            vec3 c = currentYCoCg(q, size);
            m1 += c;
            m2 += c * c;
            float d = imageLoad(gImagesR32f[p.depth], q).r;
            if (d < nearest) {
                nearest = d;
                nearestPixel = q;
            }
        }
    vec4 current = imageLoad(gImagesRgba16f[p.color], pixel);
    float depth = imageLoad(gImagesR32f[p.depth], pixel).r;
    vec2 motion = pixelMotion(t, p.motion, p.depth, nearestPixel);
    imageStore(gImagesR32f[p.outDepth], pixel, vec4(depth));
    imageStore(gImagesR32ui[p.outMotion], pixel, uvec4(packHalf2x16(pixelMotion(t, p.motion, p.depth, pixel))));

    vec2 uv = (vec2(pixel) + 0.5) / vec2(size);
    vec2 previousUv = uv - motion;
    float weight = 0.0;
    vec3 history = vec3(0.0);
    if (p.historyValid != 0u && p.frameStatic != 0u) {
        // Nothing moved or changed since last frame (camera, poses, lights): every history texel still shows its
        // pixel's surface, so it is kept whole and a still converges to the mean of the jittered frames. Clipping
        // would keep it from converging: a thin feature that only some jitter phases hit is clipped away by the
        // phases that miss it (FSR2 "locks" such pixels; a static frame locks them all).
        vec4 h = imageLoad(gImagesRgba16f[p.history], pixel);
        history = h.rgb;
        weight = clamp(h.a, 0.0, p.maxWeight);
    } else if (p.historyValid != 0u && all(greaterThanEqual(previousUv, vec2(0.0))) &&
               all(lessThan(previousUv, vec2(1.0))) &&
               !disoccluded(t, p.depth, p.historyDepth, p.historyMotion, pixel, depth, motion, previousUv)) {
        vec4 h = sampleHistoryCatmullRom(previousUv * vec2(size), size);
        history = max(h.rgb, vec3(0.0));  // Catmull-Rom's negative lobes can undershoot
        weight = clamp(imageLoad(gImagesRgba16f[p.history], ivec2(previousUv * vec2(size))).a, 0.0, p.maxWeight);
        if (p.clampHistory != 0u) {
            vec3 mean = m1 / 9.0;
            vec3 sigma = sqrt(max(m2 / 9.0 - mean * mean, vec3(0.0)));
            history = yCoCgToRgb(clipToBox(mean, p.clipGamma * sigma, rgbToYCoCg(history)));
        }
    }
    // Running mean: the new sample counts once, the history as `weight` samples (capped, so motion stays responsive).
    vec3 resolved = (history * weight + current.rgb) / (weight + 1.0);
    imageStore(gImagesRgba16f[p.outColor], pixel, vec4(resolved, min(weight + 1.0, p.maxWeight)));
}
