#version 460
// upscale_resolve.comp.glsl: the temporal upscaler's reconstruction (FSR2-class; our own, FSR2 is not packaged).
// Per OUTPUT pixel: the 3x3 jittered render samples around it, each weighted by a Gaussian of its distance to the
// output pixel centre in output pixels. Their normalised mean is this frame's colour; their summed weight (capped at
// 1) is this frame's sample weight, so a frame whose samples land near the pixel counts fully and one whose
// samples land between pixels counts little (FSR2's "sample proximity" accumulation). History: last frame's
// reconstruction at the position reprojected with the nearest surface's motion (Catmull-Rom), variance-clipped in
// YCoCg to the render samples' neighbourhood; thin features (a sample brighter or darker than all four of its
// neighbours: a ridge the next jitter phase may miss) get a widened box ("lock"); the reactive term (how much
// transparency changed this pixel: the lit image before and after the blended surfaces, as FSR2's reactive-mask
// generation does) lowers the history weight. A static frame keeps the whole history (as TAA does).
// A real GPU would read the render samples and history through bilinear samplers and cache the 3x3 in shared
// memory; lavapipe runs one invocation at a time, so the taps are explicit storage loads.
#extension GL_GOOGLE_include_directive : require
#include "scene_buffers.glsl"
#include "bindless.glsl"
#include "temporal_types.h"
#include "upscale_types.h"
#include "temporal_common.glsl"

layout(local_size_x = kTemporalGroupSize, local_size_y = kTemporalGroupSize) in;
layout(push_constant, scalar) uniform Push { UpscalePush p; };

float luma(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }

// Catmull-Rom through the history (output pixels; pixel centres at +0.5), clamped to the image.
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

// How much transparency changed render pixel q (0: opaque only .. 1), on tonemapped values (FSR2 compares the
// opaque-only and the composited image the same way).
float reactive(ivec2 q) {
    if (p.opaque == 0xFFFFFFFFu) return 0.0;
    vec3 a = imageLoad(gImagesRgba16f[p.color], q).rgb, b = imageLoad(gImagesRgba16f[p.opaque], q).rgb;
    vec3 d = abs(a / (1.0 + a) - b / (1.0 + b));
    return clamp(4.0 * max(d.r, max(d.g, d.b)), 0.0, 1.0);
}

void main() {
    GpuTemporalFrame t = TemporalBuffer(p.temporal).t;
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 outSize = ivec2(p.outputExtent);
    if (any(greaterThanEqual(pixel, outSize))) return;
    ivec2 renderSize = ivec2(t.extent);
    vec2 toOutput = vec2(outSize) / vec2(renderSize);  // output pixels per render pixel

    // Render pixel q's sample lies at q + 0.5 + jitter (render pixels); c is the output pixel centre there.
    vec2 uv = (vec2(pixel) + 0.5) / vec2(outSize);
    vec2 c = uv * vec2(renderSize) - t.jitterPixels;
    ivec2 base = ivec2(floor(c));
    vec3 m1 = vec3(0.0), m2 = vec3(0.0), sum = vec3(0.0);
    float weightSum = 0.0, nearest = 2.0, lumas[9];
    ivec2 nearestPixel = clamp(base, ivec2(0), renderSize - 1);
    float inv2s2 = 0.5 / (p.sigma * p.sigma);
    for (int y = -1; y <= 1; ++y)
        for (int x = -1; x <= 1; ++x) {
            ivec2 q = base + ivec2(x, y);
            ivec2 qc = clamp(q, ivec2(0), renderSize - 1);
            vec3 s = max(imageLoad(gImagesRgba16f[p.color], qc).rgb, vec3(0.0));
            vec3 y3 = rgbToYCoCg(s);
            m1 += y3;
            m2 += y3 * y3;
            lumas[(y + 1) * 3 + x + 1] = luma(s);
            vec2 d = (vec2(q) + 0.5 - c) * toOutput;
            float w = exp(-dot(d, d) * inv2s2);
            sum += w * s;
            weightSum += w;
            float z = imageLoad(gImagesR32f[p.depth], qc).r;
            if (z < nearest) {
                nearest = z;
                nearestPixel = qc;
            }
        }
    vec3 current = sum / max(weightSum, 1e-6);
    float sampleWeight = min(weightSum, 1.0);

    vec2 motion = pixelMotion(t, p.motion, p.depth, nearestPixel);
    vec2 previousUv = uv - motion;
    float weight = 0.0;
    vec3 history = vec3(0.0);
    if (p.historyValid != 0u && p.frameStatic != 0u) {
        vec4 h = imageLoad(gImagesRgba16f[p.history], pixel);
        history = h.rgb;
        weight = clamp(h.a, 0.0, p.maxWeight);
    } else if (p.historyValid != 0u && all(greaterThanEqual(previousUv, vec2(0.0))) &&
               all(lessThan(previousUv, vec2(1.0)))) {
        vec4 h = sampleHistoryCatmullRom(previousUv * vec2(outSize), outSize);
        history = max(h.rgb, vec3(0.0));  // Catmull-Rom's negative lobes can undershoot
        weight = clamp(imageLoad(gImagesRgba16f[p.history], ivec2(previousUv * vec2(outSize))).a, 0.0, p.maxWeight);
        // Lock: the centre sample is a ridge (all four neighbours on the same side of it): a thin feature that
        // this frame's 3x3 box would clip away when the next phase misses it.
        float l = lumas[4];
        float lo = min(min(lumas[1], lumas[3]), min(lumas[5], lumas[7]));
        float hi = max(max(lumas[1], lumas[3]), max(lumas[5], lumas[7]));
        bool thin = (l > hi * 1.25 + 1e-3) || (l * 1.25 + 1e-3 < lo);
        vec3 mean = m1 / 9.0;
        vec3 sigma = sqrt(max(m2 / 9.0 - mean * mean, vec3(0.0)));
        float gamma = thin ? 2.0 * p.clipGamma : p.clipGamma;
        history = yCoCgToRgb(clipToBox(mean, gamma * sigma, rgbToYCoCg(history)));
    }
    weight *= 1.0 - reactive(clamp(base, ivec2(0), renderSize - 1));
    float total = weight + sampleWeight;
    vec3 resolved = total > 0.0 ? (history * weight + current * sampleWeight) / total : current;
    imageStore(gImagesRgba16f[p.outColor], pixel, vec4(resolved, min(total, p.maxWeight)));
}
