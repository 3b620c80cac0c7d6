#version 460
// remodulate.comp.glsl: the denoiser's last step (shared/denoise_filter.h): filtered illumination times the albedo
// factor the prepare step divided by, shrunk toward the raw pixel where the change is larger than the pixel's noise
// (denoiseShrinkWeight; only with a variance input); sky / invalid guide pixels get their (sanitized) input
// radiance unchanged.
// Alpha is the input's. Replaces IDKEngine's OIDN output upload (reference 2.2).
#extension GL_GOOGLE_include_directive : require
#include "bindless.glsl"
#include "denoise_filter.h"

layout(local_size_x = kDenoiseGroupSize, local_size_y = kDenoiseGroupSize) in;
layout(push_constant, scalar) uniform Push { DenoisePush p; };

bool validAt(ivec2 q) {
    return denoiseValidGuide(denoiseLoadRgba(p.normal, (p.formats & kDenoiseNormal32f) != 0u, q).xyz,
                             imageLoad(gImagesR32f[p.depth], q).r);
}
vec3 albedoAt(ivec2 q) {
    return denoiseAlbedoFactor(denoiseLoadRgba(p.albedo, (p.formats & kDenoiseAlbedo32f) != 0u, q).xyz);
}
vec3 filteredAt(ivec2 q) { return imageLoad(gDenoiseImagesRgba32f[p.illumIn], q).xyz * albedoAt(q); }
float varianceAt(ivec2 q) { return p.variance != kDenoiseNoVariance ? imageLoad(gImagesR32f[p.variance], q).r : -1.0; }
// The noise variance of the filter's change at q (denoiseChangeVariance).
float changeVarianceAt(ivec2 q, float v) {
    return denoiseChangeVariance(v, imageLoad(gDenoiseImagesRgba32f[p.illumIn], q).w, albedoAt(q));
}

// Mean of denoiseShrinkExcess over the valid neighbours with a known variance (0 when there is none).
float meanExcess(ivec2 pixel) {
    float sum = 0.0, count = 0.0;
    for (int dy = -kDenoiseShrinkRadius; dy <= kDenoiseShrinkRadius; ++dy) {
        for (int dx = -kDenoiseShrinkRadius; dx <= kDenoiseShrinkRadius; ++dx) {
            ivec2 q = pixel + ivec2(dx, dy);
            if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(uvec2(q), p.extent)) || !validAt(q)) continue;
            float v = varianceAt(q);
            if (!(v >= 0.0)) continue;
            vec3 raw = denoiseSanitize3(denoiseLoadRgba(p.color, (p.formats & kDenoiseColor32f) != 0u, q).xyz);
            sum += denoiseShrinkExcess(changeVarianceAt(q, v), denoiseLuminance(raw), denoiseLuminance(filteredAt(q)));
            count += 1.0;
        }
    }
    return count > 0.0 ? sum / count : 0.0;
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(uvec2(pixel), p.extent))) return;
    vec4 color = denoiseLoadRgba(p.color, (p.formats & kDenoiseColor32f) != 0u, pixel);
    float alpha = denoiseIsFinite(color.w) ? color.w : 1.0;
    vec3 radiance = denoiseSanitize3(color.xyz);
    if (validAt(pixel)) {
        vec3 filtered = filteredAt(pixel);
        float v = varianceAt(pixel);
        float vd = changeVarianceAt(pixel, v);
        float own = denoiseShrinkExcess(vd, denoiseLuminance(radiance), denoiseLuminance(filtered));
        float w = v >= 0.0 ? denoiseShrinkWeight(vd, meanExcess(pixel), own) : 1.0;
        radiance += w * (filtered - radiance);
    }
    imageStore(gDenoiseImagesRgba32f[p.target], pixel, vec4(radiance, alpha));
}
