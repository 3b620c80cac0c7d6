// bloom_common.glsl: clamped texel fetches and a bilinear fetch through the RGBA16F storage view (the frame's
// images are not sampled: see shared/deferred_types.h). A real GPU would use a linear sampler, and the 13-tap
// filter would be 13 bilinear fetches instead of 13 x 4 loads.
#ifndef IDK_BLOOM_COMMON_GLSL
#define IDK_BLOOM_COMMON_GLSL

vec3 texel(uint image, ivec2 q, uvec2 size) {
    return imageLoad(gImagesRgba16f[image], clamp(q, ivec2(0), ivec2(size) - 1)).rgb;
}

// Bilinear at `position` in pixel units (pixel centres at +0.5), clamped to the edge.
vec3 bilinear(uint image, vec2 position, uvec2 size) {
    vec2 f = position - 0.5;
    ivec2 base = ivec2(floor(f));
    vec2 t = f - vec2(base);
    return mix(mix(texel(image, base, size), texel(image, base + ivec2(1, 0), size), t.x),
               mix(texel(image, base + ivec2(0, 1), size), texel(image, base + ivec2(1, 1), size), t.x), t.y);
}

#endif
