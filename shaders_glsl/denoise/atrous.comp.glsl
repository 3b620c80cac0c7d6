#version 460
// atrous.comp.glsl: one edge-aware a-trous wavelet iteration of the denoiser (shared/denoise_filter.h): 5x5
// B3-spline taps spaced p.step pixels apart, each weighted by normal, depth, albedo-ratio and luminance similarity
// (shared/denoise_filter.h), where the
// luminance tolerance is sigmaLuminance times the centre's standard deviation (3x3-blurred variance); the variance
// channel is filtered with the squared weights. SVGF's a-trous step; replaces IDKEngine's OIDN filter (reference 2.2).
#extension GL_GOOGLE_include_directive : require
#include "bindless.glsl"
#include "denoise_filter.h"

layout(local_size_x = kDenoiseGroupSize, local_size_y = kDenoiseGroupSize) in;
layout(push_constant, scalar) uniform Push { DenoisePush p; };

bool inside(ivec2 q) { return all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, ivec2(p.extent))); }
vec3 loadNormal(ivec2 q) { return denoiseLoadRgba(p.normal, (p.formats & kDenoiseNormal32f) != 0u, q).xyz; }
float loadDepth(ivec2 q) { return imageLoad(gImagesR32f[p.depth], q).r; }
vec4 loadIllum(ivec2 q) { return imageLoad(gDenoiseImagesRgba32f[p.illumIn], q); }
vec3 albedoFactor(ivec2 q) {
    return denoiseAlbedoFactor(denoiseLoadRgba(p.albedo, (p.formats & kDenoiseAlbedo32f) != 0u, q).xyz);
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (!inside(pixel)) return;
    vec3 n = loadNormal(pixel);
    float z = loadDepth(pixel);
    vec4 centre = loadIllum(pixel);
    if (!denoiseValidGuide(n, z)) {
        imageStore(gDenoiseImagesRgba32f[p.illumOut], pixel, centre);
        return;
    }
    // 3x3 Gaussian of the variance over valid neighbours: one noisy variance sample is too unsteady a tolerance.
    float sumK = 0.0, sumV = 0.0;
    for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
            ivec2 q = pixel + ivec2(dx, dy);
            if (!inside(q) || !denoiseValidGuide(loadNormal(q), loadDepth(q))) continue;
            float k = (dx == 0 ? 0.5 : 0.25) * (dy == 0 ? 0.5 : 0.25);
            sumK += k;
            sumV += k * loadIllum(q).w;
        }
    }
    float lumScale = denoiseLuminanceScale(sumV / sumK, p.sigmaLuminance);
    float gradient = imageLoad(gImagesR32f[p.gradient], pixel).r;
    float lp = denoiseLuminance(centre.xyz);
    vec3 albedo = albedoFactor(pixel);

    vec3 sum = vec3(0.0);
    float sumW = 0.0, sumVar = 0.0;
    for (int dy = -2; dy <= 2; ++dy) {
        for (int dx = -2; dx <= 2; ++dx) {
            ivec2 q = pixel + ivec2(dx, dy) * int(p.step);
            if (!inside(q)) continue;
            vec3 nq = loadNormal(q);
            float zq = loadDepth(q);
            if (!denoiseValidGuide(nq, zq)) continue;
            vec4 iq = loadIllum(q);
            float distance = float(p.step) * sqrt(float(dx * dx + dy * dy));
            float w = denoiseKernel(dx) * denoiseKernel(dy) * denoiseNormalWeight(n, nq, p.sigmaNormal) *
                      denoiseAlbedoWeight(albedo, albedoFactor(q)) *
                      denoiseDepthWeight(z, zq, denoiseDepthScale(gradient, distance, z, p.sigmaDepth)) *
                      denoiseLuminanceWeight(lp, denoiseLuminance(iq.xyz), lumScale);
            sum += w * iq.xyz;
            sumVar += w * w * iq.w;
            sumW += w;
        }
    }
    // sumW >= 9/64: the centre tap's weight (all similarity factors are 1 for it).
    imageStore(gDenoiseImagesRgba32f[p.illumOut], pixel, vec4(sum / sumW, sumVar / (sumW * sumW)));
}
