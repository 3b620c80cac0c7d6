// shadow_caster.glsl: what every shadow-map pass shares (point cubes, cascades, spot maps): the caster's vertex
// pulling (world position plus the inputs of the alpha test, as in gbuffer.vert) and the alpha-MASK and BLEND
// coverage tests of the fragment stage. Ports the vertex pulling and alpha test of IDKEngine's Shadows/PointShadow shaders.
#ifndef IDK_SHADOW_CASTER_GLSL
#define IDK_SHADOW_CASTER_GLSL
#include "scene_buffers.glsl"
#include "bindless.glsl"
#include "pt_sampler.h"

#ifdef IDK_SHADOW_CASTER_VERTEX
layout(location = 0) out vec2 outUv;
layout(location = 1) out vec2 outUv1;
layout(location = 2) out float outAlpha;  // COLOR_0 alpha
layout(location = 3) flat out uint outDraw;

// World position of this vertex; writes the fragment stage's inputs.
vec3 shadowCasterVertex(uint64_t vertices, uint64_t instances, uint64_t colors, uint64_t uv1) {
#ifdef IDK_SHADOW_CASTER_CULLED  // compacted commands (GPU culling): firstInstance names the instance
    uint draw = uint(gl_InstanceIndex);
#else
    uint draw = gl_DrawID;
#endif
    GpuInstance instance = InstanceBuffer(instances).data[draw];
    GpuVertex v = VertexBuffer(vertices).data[gl_VertexIndex];
    outUv = v.uv0;
    outUv1 = uv1 != 0 ? Vec2Buffer(uv1).data[gl_VertexIndex] : vec2(0.0);
    outAlpha = colors != 0 ? Vec4Buffer(colors).data[gl_VertexIndex].a : 1.0;
    outDraw = draw;
    return (instance.model * vec4(v.position, 1.0)).xyz;
}
#else
layout(location = 0) in vec2 inUv;
layout(location = 1) in vec2 inUv1;
layout(location = 2) in float inAlpha;
layout(location = 3) flat in uint inDraw;

// Whether a fragment casts no shadow: alpha MASK below its material's cutoff, or BLEND by coverage, a stochastic
// alpha test: the texel is kept with probability alpha (a hash of texel and draw against it), so the shadow
// filter's taps average to the visibility 1 - alpha behind one layer and, with independent coins per draw, to
// the product of (1 - alpha) behind several: the expectation of the ray-traced rung's BLEND rule
// (pathtrace/wf_trace.h). Chosen over coverage-weighted maps because it needs no extra opacity target and keeps
// one depth-only map per light; the cost is noise of the filter's footprint (21 cube taps, 2x2 PCF per map tap).
bool shadowCasterCutAway(uint64_t instances, uint64_t meshes, uint64_t materials) {
    GpuInstance instance = InstanceBuffer(instances).data[inDraw];
    GpuMaterial m = MaterialBuffer(materials).data[MeshBuffer(meshes).data[instance.mesh].material];
    if (m.alphaMode != kAlphaMask && m.alphaMode != kAlphaBlend) return false;
    GpuTextureSlot slot = m.slots[kSlotBaseColor];
    vec3 h = vec3(slot.texCoord == 1u ? inUv1 : inUv, 1.0);
    vec2 st = vec2(dot(slot.row0, h), dot(slot.row1, h));
    float alpha = m.baseColorFactor.a * inAlpha * IDK_SAMPLE_2D(slot.texture, slot.samplerIndex, st).a;
    if (m.alphaMode == kAlphaMask) return alpha < m.alphaCutoff;
    uvec2 texel = uvec2(gl_FragCoord.xy);
    float coin = ptUnitFloat(ptHash(texel.x ^ ptHash(texel.y ^ ptHash(inDraw * 0x9E3779B9u))));
    return coin >= clamp(alpha, 0.0, 1.0);
}
#endif

#endif
