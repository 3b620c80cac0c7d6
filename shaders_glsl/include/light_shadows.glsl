// light_shadows.glsl: visibility of a directional light through its cascades and of a spot light through its
// single perspective map (GpuShadowMap records after the per-light table, shared/shadow_types.h). The first
// cascade whose map holds the whole filter footprint is used (cascades are nested by distance, so that is the
// finest one); beyond the last one the light is unshadowed. Normal offset and 3x3 bilinear PCF as the point cubes
// (include/shadows.glsl), with one change for perspective maps: they compare depth along the map's axis, not along
// the ray to the light, so off the axis a receiver facing the light still has a depth slope across the kernel of
// up to tan(A) texels per texel, A the angle between the normal and the axis; the offset grows with the larger of
// sin(T) and sin(A) (for a cascade the axis is the light direction, A = T). Ports the cascade lookup of
// IDKEngine's shadow shaders.
#ifndef IDK_LIGHT_SHADOWS_GLSL
#define IDK_LIGHT_SHADOWS_GLSL
#extension GL_EXT_buffer_reference : require
#include "bindless.glsl"
#include "shadow_types.h"

layout(set = 0, binding = kBindingSampledImages) uniform texture2DArray gTextures2DArray[];

layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer ShadowMapBuffer {
    GpuShadowMap data[];
};

// table: the address of the per-light table (s is its entry for this light); n, l as pointShadowVisibility.
float mapShadowVisibility(uint64_t table, GpuPointShadow s, vec3 position, vec3 n, vec3 l) {
    ShadowMapBuffer maps = ShadowMapBuffer(table + uint64_t(s.mapOffset));
    float cosT = clamp(dot(n, l), 0.0, 1.0);
    float sinT = sqrt(1.0 - cosT * cosT);
    for (uint c = 0; c < s.mapCount; ++c) {
        GpuShadowMap m = maps.data[c];
        vec4 clip0 = m.viewProjection * vec4(position, 1.0);
        if (clip0.w <= 0.0) continue;  // behind a spot light: outside its cone, unlit anyway
        float texel = m.texelScale * (m.perspective != 0u ? clip0.w : 1.0);
        // The map's depth axis: the clip.w row (perspective) or the clip.z row (orthographic) of viewProjection.
        mat4 vp = m.viewProjection;
        vec3 axis = normalize(m.perspective != 0u ? vec3(vp[0].w, vp[1].w, vp[2].w) : vec3(vp[0].z, vp[1].z, vp[2].z));
        float sinA = length(cross(n, axis));
        vec4 clip = vp * vec4(position + n * (texel * (1.0 + 3.0 * max(sinT, sinA))), 1.0);
        vec3 ndc = clip.xyz / clip.w;
        vec2 uv = ndc.xy * 0.5 + 0.5;
        float margin = kShadowMapMargin * m.invResolution;
        if (any(lessThan(uv, vec2(margin))) || any(greaterThan(uv, vec2(1.0 - margin)))) continue;
        if (ndc.z >= 1.0) return 1.0;  // beyond the far plane: nothing was rasterized there
        float lit = 0.0;
        for (int j = -1; j <= 1; ++j) {
            for (int i = -1; i <= 1; ++i) {
                vec2 st = uv + vec2(i, j) * m.invResolution;
                lit += texture(sampler2DArrayShadow(gTextures2DArray[nonuniformEXT(s.cube)],
                                                    gSamplers[s.samplerIndex]),
                               vec4(st, float(m.layer), ndc.z));
            }
        }
        return lit / 9.0;
    }
    return 1.0;
}

#endif
