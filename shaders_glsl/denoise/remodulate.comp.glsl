#version 460
// remodulate.comp.glsl: the denoiser's last step (shared/denoise_filter.h): filtered illumination times the albedo
// factor the prepare step divided by; sky / invalid guide pixels get their (sanitized) input radiance unchanged.
// Alpha is the input's. Replaces IDKEngine's OIDN output upload (reference 2.2).
#extension GL_GOOGLE_include_directive : require
#include "bindless.glsl"
#include "denoise_filter.h"

layout(local_size_x = kDenoiseGroupSize, local_size_y = kDenoiseGroupSize) in;
layout(push_constant, scalar) uniform Push { DenoisePush p; };

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(uvec2(pixel), p.extent))) return;
    vec4 color = denoiseLoadRgba(p.color, (p.formats & kDenoiseColor32f) != 0u, pixel);
    vec3 n = denoiseLoadRgba(p.normal, (p.formats & kDenoiseNormal32f) != 0u, pixel).xyz;
    float z = imageLoad(gImagesR32f[p.depth], pixel).r;
    float alpha = denoiseIsFinite(color.w) ? color.w : 1.0;
    vec3 radiance = denoiseSanitize3(color.xyz);
    if (denoiseValidGuide(n, z)) {
        vec3 albedo = denoiseLoadRgba(p.albedo, (p.formats & kDenoiseAlbedo32f) != 0u, pixel).xyz;
        radiance = imageLoad(gDenoiseImagesRgba32f[p.illumIn], pixel).xyz * denoiseAlbedoFactor(albedo);
    }
    imageStore(gDenoiseImagesRgba32f[p.target], pixel, vec4(radiance, alpha));
}
