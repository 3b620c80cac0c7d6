// storage_bilinear.glsl: clamped texel fetches and a bilinear fetch through the bindless RGBA16F storage views, for
// passes that read the frame's images (which are not sampled: see shared/deferred_types.h): bloom and the screen-space
// transmission chain. nonuniformEXT because the transmission's image index varies per fragment; where the index is
// uniform (bloom's push constants) compilers see that and emit a plain load. A real GPU would sample through a linear
// sampler: one filtered fetch in place of 4 loads.
#ifndef IDK_STORAGE_BILINEAR_GLSL
#define IDK_STORAGE_BILINEAR_GLSL

vec3 storageTexel(uint image, ivec2 q, uvec2 size) {
    return imageLoad(gImagesRgba16f[nonuniformEXT(image)], clamp(q, ivec2(0), ivec2(size) - 1)).rgb;
}

// Bilinear at `position` in pixel units (pixel centres at +0.5), clamped to the edge.
vec3 storageBilinear(uint image, vec2 position, uvec2 size) {
    vec2 f = position - 0.5;
    ivec2 base = ivec2(floor(f));
    vec2 t = f - vec2(base);
    return mix(mix(storageTexel(image, base, size), storageTexel(image, base + ivec2(1, 0), size), t.x),
               mix(storageTexel(image, base + ivec2(0, 1), size), storageTexel(image, base + ivec2(1, 1), size), t.x),
               t.y);
}

#endif
