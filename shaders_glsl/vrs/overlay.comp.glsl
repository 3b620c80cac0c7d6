#version 460
// overlay.comp.glsl (--vrs-debug): tints each tile of the lit HDR image by the rate the classifier chose for the
// next frame: none for 1x1, then blue, green, yellow, red for 2x1 .. 4x4 (the original's debug view shows 4x4 in
// red too). Runs after the classifier has read the image.
#extension GL_GOOGLE_include_directive : require
#include "bindless.glsl"
#include "vrs_rates.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push { VrsOverlayPush p; };

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, imageSize(gImagesRgba16f[p.target])))) return;
    uint rate = vrsTileRate(VrsRatesRef(p.rates), uvec2(pixel));
    if (rate == 0u) return;
    const vec3 tint[4] = vec3[4](vec3(0.1, 0.3, 1.0), vec3(0.1, 1.0, 0.2), vec3(1.0, 0.9, 0.1), vec3(1.0, 0.1, 0.1));
    vec4 c = imageLoad(gImagesRgba16f[p.target], pixel);
    float l = max((c.r + c.g + c.b) / 3.0, 0.05);
    imageStore(gImagesRgba16f[p.target], pixel, vec4(mix(c.rgb, tint[rate - 1u] * l * 2.0, 0.5), c.a));
}
