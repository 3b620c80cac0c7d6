// denoise_filter.h: the edge-aware a-trous denoiser's push block and its per-pixel math, ONE source compiled as
// C++ (namespace idk::gpu: the CPU oracle in tests/conformance/denoise uses it) and as GLSL (shaders_glsl/denoise).
// The filter is SVGF's spatial part (Schied et al. 2017, "Spatiotemporal Variance-Guided Filtering") without its
// temporal accumulation: the path tracer already accumulates. It replaces IDKEngine's OIDN round trip (reference
// 2.2), which is not packaged in Debian.
//   prepare:    illumination = radiance / albedo (demodulation); firefly rejection (the centre's luminance clamped
//               to its neighbours' mean + fireflyClamp standard deviations: biased darker, like every clamp, but a
//               lone 1000x sample otherwise survives every edge-stopping filter; only without a variance input);
//               luminance variance: the pixel's own variance of the mean when the tracer gives it (from 2 spp:
//               second moments, SVGF's temporal moments), else from a 7x7 bilateral neighbourhood (normal + depth
//               weights); per-pixel depth gradient;
//   a-trous:    5x5 B3-spline taps at step 2^i, weighted by normal, depth, albedo-ratio and variance-scaled
//               luminance similarity; variance filtered with the squared weights;
// The albedo-ratio weight (min/max of the two albedo luminances, squared) is ours: demodulation assumes radiance
// proportional to albedo, which emission and specular reflection on dark surfaces break (radiance 0.4 on albedo
// 0.001 demodulates to 400); the squared ratio is the inverse-variance weight of such an estimate, so a dark
// pixel's amplified illumination never reaches a bright neighbour, while similar albedos mix freely.
//   remodulate: illumination * albedo, then (with a variance input) shrunk toward the raw pixel by
//               denoiseShrinkWeight, so that where the filter's change exceeds the pixel's noise (bias: blurred
//               detail at high spp) the raw value wins; this is what keeps the output no worse than raw.
// Sky / invalid guide pixels (depth 0, inf or NaN, normal shorter than 0.5) pass through unfiltered and never feed
// their neighbours. Radiance is sanitized first (NaN/inf -> 0, clamped to [0, kDenoiseMaxRadiance]) so every
// intermediate value stays finite in float32.
#ifndef IDK_DENOISE_FILTER_H
#define IDK_DENOISE_FILTER_H
#include "interop.h"
#ifdef __cplusplus
#include <cmath>
#endif

IDK_GPU_BEGIN

// Formats of the three RGBA inputs: bit set = RGBA32F, clear = RGBA16F (DenoisePush::formats).
IDK_CONST(uint, kDenoiseColor32f, 1u);
IDK_CONST(uint, kDenoiseAlbedo32f, 2u);
IDK_CONST(uint, kDenoiseNormal32f, 4u);

IDK_CONST(uint, kDenoiseGroupSize, 8u);        // 8x8 invocations per workgroup
IDK_CONST(int, kDenoiseVarianceRadius, 3);     // 7x7 neighbourhood of the spatial variance estimate
IDK_CONST(float, kDenoiseAlbedoFloor, 1e-3f);  // demodulation divides by max(albedo, floor)
IDK_CONST(float, kDenoiseMaxRadiance, 1e12f);  // keeps (radiance / floor)^2 far from float overflow
IDK_CONST(float, kDenoiseLuminanceEpsilon, 1e-10f);
IDK_CONST(float, kDenoiseDepthRelative, 1e-3f);  // depth tolerance floor, relative to the centre depth

// One push block for the three shaders (bindless storage-image indices).
struct DenoisePush {
    uint color;     // RGBA16F/32F noisy linear radiance (input)
    uint albedo;    // RGBA16F/32F first-hit albedo
    uint normal;    // RGBA16F/32F first-hit world normal (xyz)
    uint depth;     // R32F first-hit view distance
    uint gradient;  // R32F per-pixel depth gradient (written by prepare, read by a-trous)
    uint illumIn;   // RGBA32F illumination (rgb) + luminance variance (a)
    uint illumOut;  // RGBA32F
    uint target;    // RGBA32F denoised radiance (remodulate)
    uint formats;   // kDenoise*32f bits
    uint step;      // a-trous tap spacing in pixels (1, 2, 4, ...)
    uvec2 extent;
    float sigmaLuminance;
    float sigmaNormal;
    float sigmaDepth;
    float fireflyClamp;  // standard deviations above the neighbours' mean luminance (<= 0: no clamp)
    uint variance;  // R32F variance of the mean luminance per pixel (< 0: unknown), kDenoiseNoVariance: none
};
IDK_GPU_SIZE(DenoisePush, 68);
IDK_CONST(uint, kDenoiseNoVariance, 0xFFFFFFFFu);

#ifdef __cplusplus
#define IDK_DN_FN inline
#define IDK_DN_EXP std::exp
#define IDK_DN_POW std::pow
#define IDK_DN_SQRT std::sqrt
#define IDK_DN_ABS std::fabs
#define IDK_DN_MIN std::fmin
#define IDK_DN_MAX std::fmax
IDK_DN_FN bool denoiseIsFinite(float x) { return std::isfinite(x); }
#else
#define IDK_DN_FN
#define IDK_DN_EXP exp
#define IDK_DN_POW pow
#define IDK_DN_SQRT sqrt
#define IDK_DN_ABS abs
#define IDK_DN_MIN min
#define IDK_DN_MAX max
// By the bits: a compiler may assume no NaN/inf and fold isnan/isinf away.
bool denoiseIsFinite(float x) { return (floatBitsToUint(x) & 0x7f800000u) != 0x7f800000u; }
#endif

IDK_DN_FN float denoiseLuminance(vec3 c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

IDK_DN_FN float denoiseSanitize(float x) {
    return denoiseIsFinite(x) ? IDK_DN_MIN(IDK_DN_MAX(x, 0.0f), kDenoiseMaxRadiance) : 0.0f;
}
IDK_DN_FN vec3 denoiseSanitize3(vec3 c) { return vec3(denoiseSanitize(c.x), denoiseSanitize(c.y), denoiseSanitize(c.z)); }

// Per channel max(albedo, floor); a non-finite albedo counts as 1 (no demodulation).
IDK_DN_FN float denoiseAlbedoChannel(float a) { return denoiseIsFinite(a) ? IDK_DN_MAX(a, kDenoiseAlbedoFloor) : 1.0f; }
IDK_DN_FN vec3 denoiseAlbedoFactor(vec3 a) {
    return vec3(denoiseAlbedoChannel(a.x), denoiseAlbedoChannel(a.y), denoiseAlbedoChannel(a.z));
}

// A pixel the filter works on: a finite positive view distance and a normal of length >= 0.5.
IDK_DN_FN bool denoiseValidGuide(vec3 n, float depth) {
    float n2 = n.x * n.x + n.y * n.y + n.z * n.z;
    return denoiseIsFinite(depth) && depth > 0.0f && denoiseIsFinite(n2) && n2 >= 0.25f;
}

// B3-spline taps (1/16, 1/4, 3/8, 1/4, 1/16) by |offset|.
IDK_DN_FN float denoiseKernel(int d) { return d == 0 ? 0.375f : (d == 1 || d == -1 ? 0.25f : 0.0625f); }

IDK_DN_FN float denoiseAlbedoWeight(vec3 albedoFactorP, vec3 albedoFactorQ) {
    float ap = denoiseLuminance(albedoFactorP), aq = denoiseLuminance(albedoFactorQ);
    float r = IDK_DN_MIN(ap, aq) / IDK_DN_MAX(ap, aq);
    return r * r;
}

IDK_DN_FN float denoiseNormalWeight(vec3 np, vec3 nq, float sigmaNormal) {
    float lp = IDK_DN_SQRT(np.x * np.x + np.y * np.y + np.z * np.z);
    float lq = IDK_DN_SQRT(nq.x * nq.x + nq.y * nq.y + nq.z * nq.z);
    float c = (np.x * nq.x + np.y * nq.y + np.z * nq.z) / (lp * lq);
    return IDK_DN_POW(IDK_DN_MIN(IDK_DN_MAX(c, 0.0f), 1.0f), sigmaNormal);
}

// The depth difference a tap `distance` pixels away may have on the centre's own surface: the centre's depth
// gradient times the distance (scaled by sigmaDepth), never below a small fraction of the centre depth.
IDK_DN_FN float denoiseDepthScale(float gradient, float distance, float depth, float sigmaDepth) {
    return sigmaDepth * gradient * distance + kDenoiseDepthRelative * depth + 1e-30f;
}
IDK_DN_FN float denoiseDepthWeight(float zp, float zq, float scale) { return IDK_DN_EXP(-IDK_DN_ABS(zp - zq) / scale); }

// Luminance similarity scaled by the (filtered) standard deviation of the centre: noise-sized differences pass.
IDK_DN_FN float denoiseLuminanceScale(float variance, float sigmaLuminance) {
    return sigmaLuminance * IDK_DN_SQRT(IDK_DN_MAX(variance, 0.0f)) + kDenoiseLuminanceEpsilon;
}
IDK_DN_FN float denoiseLuminanceWeight(float lp, float lq, float scale) { return IDK_DN_EXP(-IDK_DN_ABS(lp - lq) / scale); }

// Firefly rejection: the largest luminance the centre may keep, given its neighbours' weighted mean and variance
// (centre excluded); a very large value when off (k <= 0) or without neighbours (sumW == 0).
IDK_DN_FN float denoiseLuminanceLimit(float mean, float variance, float sumW, float k) {
    return (k > 0.0f && sumW > 0.0f) ? mean + k * IDK_DN_SQRT(IDK_DN_MAX(variance, 0.0f)) : 3.0e38f;
}

// The illumination variance prepare starts from: the pixel's own variance of the mean (radiance luminance variance
// over the squared albedo luminance) when known (>= 0), else the neighbourhood's spatial estimate.
IDK_DN_FN float denoiseStartVariance(float pixelVariance, vec3 albedoFactor, float spatialVariance) {
    float a = denoiseLuminance(albedoFactor);
    return pixelVariance >= 0.0f ? pixelVariance / (a * a) : spatialVariance;
}

// "Never worse than raw": weight of the filtered value in the output, per pixel. The raw mean has luminance variance
// v; the filter keeps a share rho of it (the a-trous variance channel propagates sum(w^2) v, which for a weighted
// mean that includes the centre is also about the centre's own weight), so the change d = filtered - raw has noise
// variance vd = (1 - rho) v and E[d^2] = bias^2 + vd. The squared bias is estimated as the mean of d^2 - vd over
// the pixel's 5x5 neighbourhood (kDenoiseShrinkRadius: smooth bias), or, when larger, the pixel's own d^2 - vd
// (a feature of a pixel or two, such as a point light's hot spot or an emissive texture's detail, whose bias the
// 5x5 mean would dilute; noisy, so it also costs some denoising where there is only noise), clamped at 0; and
// raw + w (filtered - raw) with w = vd / (vd + bias^2) is the mix of least expected squared error
// (E[(raw - truth) d] = -vd). Unknown v (< 0, one sample): the filter alone (w = 1).
IDK_CONST(int, kDenoiseShrinkRadius, 2);
IDK_DN_FN float denoiseChangeVariance(float v, float filteredIllumVariance, vec3 albedoFactor) {
    float a = denoiseLuminance(albedoFactor);
    float rho = v > 0.0f ? IDK_DN_MIN(IDK_DN_MAX(filteredIllumVariance * a * a / v, 0.0f), 1.0f) : 1.0f;
    return v * (1.0f - rho);
}
IDK_DN_FN float denoiseShrinkExcess(float v, float rawLuminance, float filteredLuminance) {
    float d = filteredLuminance - rawLuminance;
    return d * d - v;
}
IDK_DN_FN float denoiseShrinkWeight(float v, float meanExcess, float ownExcess) {
    if (!(v >= 0.0f)) return 1.0f;
    float bias2 = IDK_DN_MAX(IDK_DN_MAX(meanExcess, ownExcess), 0.0f);
    return v + bias2 > 0.0f ? v / (v + bias2) : 1.0f;
}

// Weighted variance of the neighbours (weights sum sumW, mean m, sum of w (l - m)^2 = sumV) together with the centre
// (weight 1, luminance lp), without the cancellation of E[l^2] - E[l]^2.
IDK_DN_FN float denoiseCombinedVariance(float sumW, float sumV, float m, float lp) {
    float all = (sumW * m + lp) / (sumW + 1.0f);
    return (sumV + sumW * (m - all) * (m - all) + (lp - all) * (lp - all)) / (sumW + 1.0f);
}

#undef IDK_DN_FN
#undef IDK_DN_EXP
#undef IDK_DN_POW
#undef IDK_DN_SQRT
#undef IDK_DN_ABS
#undef IDK_DN_MIN
#undef IDK_DN_MAX

IDK_GPU_END

// GLSL only: reading the inputs by their format (bindless.glsl declares no rgba32f alias, so it is declared here).
#ifndef __cplusplus
layout(set = 0, binding = kBindingStorageImages, rgba32f) uniform image2D gDenoiseImagesRgba32f[];

vec4 denoiseLoadRgba(uint index, bool is32f, ivec2 pixel) {
    if (is32f) return imageLoad(gDenoiseImagesRgba32f[index], pixel);
    return imageLoad(gImagesRgba16f[index], pixel);
}
#endif

#endif
