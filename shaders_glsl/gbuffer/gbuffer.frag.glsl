#version 460
// gbuffer.frag.glsl: samples the material (bindless textures with KHR_texture_transform), applies alpha MASK,
// single-/double-sided facing and normal mapping in a proper tangent frame with handedness (vertex tangents,
// or a screen-space cotangent frame when the vertex has none), and writes the G-buffer.
// Ports IDKEngine's GBuffer/fragment.glsl, fixing its normal-map bugs (reference section 5).
#extension GL_GOOGLE_include_directive : require
#include "scene_buffers.glsl"
#include "bindless.glsl"
#include "octahedral.glsl"
#include "color.glsl"

layout(push_constant, scalar) uniform Push { GBufferPush p; };

layout(location = 0) in vec3 inWorldPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec4 inTangent;
layout(location = 3) in vec2 inUv;
layout(location = 4) flat in uint inDraw;
layout(location = 5) in vec4 inColor;
layout(location = 6) in vec2 inUv1;

layout(location = 0) out vec4 outAlbedo;    // RGBA8: sRGB-encoded base colour, alpha
layout(location = 1) out uint outNormal;    // R32UI: octahedral world normal (facing the viewer's side)
layout(location = 2) out vec4 outMaterial;  // RGBA8: metallic, roughness, occlusion, lit (0: unlit)
layout(location = 3) out vec4 outEmissive;  // RGBA16F: emitted radiance
layout(location = 4) out float outDepth;    // R32F: the fragment's depth (what the depth test kept)

vec4 sampleSlot(GpuTextureSlot slot) {
    vec3 h = vec3(slot.texCoord == 1u ? inUv1 : inUv, 1.0);
    vec2 st = vec2(dot(slot.row0, h), dot(slot.row1, h));
    uint t = slot.texture, s = slot.samplerIndex;
    return texture(sampler2D(gTextures2D[nonuniformEXT(t)], gSamplers[nonuniformEXT(s)]), st);
}

// Tangent (T) and glTF bitangent (B) at this fragment for the unit normal n.
bool tangentFrame(vec3 n, out vec3 t, out vec3 b) {
    if (inTangent.w != 0.0) {  // vertex tangents: B = cross(N, T) * w (glTF 2.0, 3.7.2.1)
        t = inTangent.xyz - n * dot(n, inTangent.xyz);
        float len2 = dot(t, t);
        if (len2 < 1e-20) return false;
        t *= inversesqrt(len2);
        b = cross(n, t) * (inTangent.w < 0.0 ? -1.0 : 1.0);
        return true;
    }
    // Cotangent frame from screen-space derivatives (Schuler 2013, "Normal Mapping Without Precomputed
    // Tangents"), with the determinant's sign kept so mirrored UVs get the mirrored frame: T = grad u,
    // B = -grad v (glTF's v runs down the image, its bitangent up).
    vec3 dp1 = dFdx(inWorldPosition), dp2 = dFdy(inWorldPosition);
    vec2 duv1 = dFdx(inUv), duv2 = dFdy(inUv);
    vec3 dp2perp = cross(dp2, n), dp1perp = cross(n, dp1);
    float det = dot(dp1, dp2perp);
    t = dp2perp * duv1.x + dp1perp * duv2.x;
    b = dp2perp * duv1.y + dp1perp * duv2.y;
    float len2 = max(dot(t, t), dot(b, b));
    if (len2 < 1e-30 || det == 0.0) return false;
    float s = inversesqrt(len2) * sign(det);
    t *= s;
    b *= -s;
    return true;
}

void main() {
    GpuInstance instance = InstanceBuffer(p.instances).data[inDraw];
    uint materialIndex = MeshBuffer(p.meshes).data[instance.mesh].material;
    GpuMaterial m = MaterialBuffer(p.materials).data[nonuniformEXT(materialIndex)];

    // Every sample happens before any discard so implicit derivatives stay defined for the whole quad.
    vec4 baseColor = m.baseColorFactor * sampleSlot(m.slots[kSlotBaseColor]) * inColor;
    vec4 mr = sampleSlot(m.slots[kSlotMetallicRoughness]);
    vec4 nt = sampleSlot(m.slots[kSlotNormal]);
    float ao = sampleSlot(m.slots[kSlotOcclusion]).r;
    vec3 emissive = m.emissiveFactor * sampleSlot(m.slots[kSlotEmissive]).rgb;

    vec3 n = normalize(inNormal);
    vec3 t, b;
    bool haveFrame = tangentFrame(n, t, b);
    vec2 xy = nt.xy * 2.0 - 1.0;                          // remap first, then reconstruct z from it
    vec3 tn = vec3(xy * m.normalScale, sqrt(max(1.0 - dot(xy, xy), 0.0)));
    if (haveFrame) n = normalize(t * tn.x + b * tn.y + n * tn.z);

    // Single-sided materials reject back faces here rather than with the pipeline's cull mode, so that one
    // indirect draw covers single- and double-sided materials (and mirrored instances flip the test).
    bool front = gl_FrontFacing != ((instance.flags & kInstanceMirrored) != 0u);
    bool doubleSided = (m.flags & kMaterialDoubleSided) != 0u;
    if ((!front && !doubleSided) || (m.alphaMode == kAlphaMask && baseColor.a < m.alphaCutoff)) discard;
    if (!front) n = -n;

    outAlbedo = vec4(srgbEncode(baseColor.rgb), m.alphaMode == kAlphaOpaque ? 1.0 : baseColor.a);
    outNormal = packSnorm2x16(octEncode(n));
    outMaterial = vec4(clamp(m.metallicFactor * mr.b, 0.0, 1.0), clamp(m.roughnessFactor * mr.g, 0.0, 1.0),
                       1.0 + m.occlusionStrength * (ao - 1.0), (m.flags & kMaterialUnlit) != 0u ? 0.0 : 1.0);
    outEmissive = vec4(emissive, 1.0);
    outDepth = gl_FragCoord.z;
}
