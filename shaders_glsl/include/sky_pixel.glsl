// sky_pixel.glsl: the environment radiance seen through one background pixel, shared by the compute sky pass
// (sky/sky.comp) and the hardware-VRS fragment pass (vrs/lighting_rate.frag).
#ifndef IDK_SKY_PIXEL_GLSL
#define IDK_SKY_PIXEL_GLSL
#include "scene_buffers.glsl"
#include "environment.glsl"

vec3 skyPixelRadiance(GpuFrame f, ivec2 pixel) {
    // The ray through the pixel centre from two depths (works for finite and infinite far planes).
    vec2 ndc = (vec2(pixel) + 0.5) / vec2(f.extent) * 2.0 - 1.0;
    vec4 a = f.inverseViewProjection * vec4(ndc, 0.0, 1.0);
    vec4 b = f.inverseViewProjection * vec4(ndc, 0.5, 1.0);
    vec3 dir = normalize(b.xyz / b.w - a.xyz / a.w);
    return environmentRadiance(f, dir, 0.0);
}

#endif
