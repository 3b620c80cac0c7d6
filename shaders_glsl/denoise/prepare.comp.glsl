#version 460
// prepare.comp.glsl: the denoiser's first step (shared/denoise_filter.h): demodulates the noisy radiance by the
// albedo, clamps fireflies to the neighbourhood's mean + fireflyClamp standard deviations, estimates the luminance
// variance of each pixel over a 7x7 neighbourhood weighted by normal and depth similarity (SVGF's spatial fallback
// when no temporal moments exist) or, when the tracer gives it, the pixel's own variance of the mean from its
// samples' second moment (SVGF's temporal moments: our accumulation over samples), and stores the depth gradient the a-trous iterations scale their depth
// tolerance with. Replaces IDKEngine's OIDN input step (reference 2.2).
#extension GL_GOOGLE_include_directive : require
#include "bindless.glsl"
#include "denoise_filter.h"

layout(local_size_x = kDenoiseGroupSize, local_size_y = kDenoiseGroupSize) in;
layout(push_constant, scalar) uniform Push { DenoisePush p; };

bool inside(ivec2 q) { return all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, ivec2(p.extent))); }
vec3 loadNormal(ivec2 q) { return denoiseLoadRgba(p.normal, (p.formats & kDenoiseNormal32f) != 0u, q).xyz; }
float loadDepth(ivec2 q) { return imageLoad(gImagesR32f[p.depth], q).r; }
vec3 albedoFactor(ivec2 q) {
    return denoiseAlbedoFactor(denoiseLoadRgba(p.albedo, (p.formats & kDenoiseAlbedo32f) != 0u, q).xyz);
}
vec3 illumination(ivec2 q) {
    return denoiseSanitize3(denoiseLoadRgba(p.color, (p.formats & kDenoiseColor32f) != 0u, q).xyz) / albedoFactor(q);
}

// The smaller one-sided depth difference along one axis, over valid neighbours (0 when there is none): the
// smaller side keeps a silhouette pixel's tolerance that of its own surface.
float axisGradient(ivec2 pixel, ivec2 axis, float z) {
    float g = -1.0;
    for (int s = -1; s <= 1; s += 2) {
        ivec2 q = pixel + s * axis;
        if (!inside(q)) continue;
        float zq = loadDepth(q);
        if (!denoiseValidGuide(loadNormal(q), zq)) continue;
        float d = abs(zq - z);
        g = g < 0.0 ? d : min(g, d);
    }
    return max(g, 0.0);
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (!inside(pixel)) return;
    vec3 n = loadNormal(pixel);
    float z = loadDepth(pixel);
    if (!denoiseValidGuide(n, z)) {  // sky: remodulate passes the radiance through; nobody reads these
        imageStore(gDenoiseImagesRgba32f[p.illumOut], pixel, vec4(0.0));
        imageStore(gImagesR32f[p.gradient], pixel, vec4(0.0));
        return;
    }
    float gradient = max(axisGradient(pixel, ivec2(1, 0), z), axisGradient(pixel, ivec2(0, 1), z));
    vec3 centre = illumination(pixel);
    vec3 albedo = albedoFactor(pixel);
    float lp = denoiseLuminance(centre);

    // Two passes over the neighbours (centre excluded): their weighted mean luminance, then the spread around it.
    float sumW = 0.0, sumL = 0.0, sumV = 0.0;
    for (int pass = 0; pass < 2; ++pass) {
        float mean = sumW > 0.0 ? sumL / sumW : 0.0;
        for (int dy = -kDenoiseVarianceRadius; dy <= kDenoiseVarianceRadius; ++dy) {
            for (int dx = -kDenoiseVarianceRadius; dx <= kDenoiseVarianceRadius; ++dx) {
                ivec2 q = pixel + ivec2(dx, dy);
                if ((dx == 0 && dy == 0) || !inside(q)) continue;
                vec3 nq = loadNormal(q);
                float zq = loadDepth(q);
                if (!denoiseValidGuide(nq, zq)) continue;
                float distance = sqrt(float(dx * dx + dy * dy));
                float w = denoiseNormalWeight(n, nq, p.sigmaNormal) * denoiseAlbedoWeight(albedo, albedoFactor(q)) *
                          denoiseDepthWeight(z, zq, denoiseDepthScale(gradient, distance, z, p.sigmaDepth));
                float l = denoiseLuminance(illumination(q));
                if (pass == 0) {
                    sumW += w;
                    sumL += w * l;
                } else {
                    sumV += w * (l - mean) * (l - mean);
                }
            }
        }
    }
    float mean = sumW > 0.0 ? sumL / sumW : 0.0;
    float limit = denoiseLuminanceLimit(mean, sumW > 0.0 ? sumV / sumW : 0.0, sumW, p.fireflyClamp);
    // The clamp only without the pixel's own variance (one sample): with it, a bright pixel is judged against its
    // own noise (a real highlight has little), and clamping it would be a bias the final shrink cannot see.
    float pixelVariance = p.variance != kDenoiseNoVariance ? imageLoad(gImagesR32f[p.variance], pixel).r : -1.0;
    if (pixelVariance < 0.0 && lp > limit) {
        centre *= limit / lp;
        lp = limit;
    }
    float variance = denoiseStartVariance(pixelVariance, albedo, denoiseCombinedVariance(sumW, sumV, mean, lp));
    imageStore(gDenoiseImagesRgba32f[p.illumOut], pixel, vec4(centre, variance));
    imageStore(gImagesR32f[p.gradient], pixel, vec4(gradient));
}
