// gbuffer_fragment.glsl: the G-buffer fragment shader's body (gbuffer/gbuffer.frag.glsl), shared with its
// surface-ID variant (gbuffer/gbuffer_ids.frag.glsl, GBUFFER_IDS defined) so that both keep exactly the same
// fragments: same material sampling, alpha MASK and single-sided facing discards.
#include "scene_buffers.glsl"
#include "bindless.glsl"
#include "octahedral.glsl"
#include "color.glsl"
#include "material_eval.glsl"
#include "gbuffer_anisotropy.glsl"
#include "gbuffer_layer_bits.glsl"

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
layout(location = 3) out vec4 outEmissive;  // RGBA16F: emitted radiance, alpha: layered material index + 1
layout(location = 4) out float outDepth;    // R32F: the fragment's depth (what the depth test kept)
// KHR_materials_specular / _clearcoat / _sheen texels of layered materials, for the lighting pass:
// x = unorm8 (specular A, clearcoat R, clearcoatRoughness G, sheenRoughness A), y / z = sRGB-encoded unorm8
// specularColor / sheenColor RGB. Their alphas and w carry the newer extensions' texels, by what the material uses
// (gbuffer_layer_bits.glsl says which; the lighting pass reads the same flags): y.a / z.a KHR_materials_iridescence's
// (factor R, thickness G), else diffuseTransmissionTexture A / diffuseTransmissionColorTexture R (sRGB); w the coat
// normal (clearcoatNormalTexture) in 2 x 12 bits, else KHR_materials_anisotropy's direction in its low 16 bits
// (gbuffer_anisotropy.glsl), else the diffuse-transmission colour's G, B in its high 16 bits; an anisotropic
// material's anisotropyTexture B in w's top byte. Discarded when the scene has neither such a texture nor an
// anisotropic material (no attachment).
layout(location = 5) out uvec4 outLayers;
// RG32UI: the texels the layers target has no bits for in a material combining extensions (gbuffer_layer_bits.glsl:
// diffuse transmission, anisotropy direction). Discarded unless the scene needs it (no attachment).
layout(location = 6) out uvec2 outLayerSpill;
#ifdef GBUFFER_IDS
layout(location = 7) out uvec2 outIds;      // RG32UI: the draw and its triangle (gl_PrimitiveID) of the kept fragment
#endif

vec4 sampleSlot(GpuTextureSlot slot) { return sampleMaterialSlot(slot, inUv, inUv1); }

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
    float specularT = 1.0, coatT = 1.0, coatRoughnessT = 1.0, sheenRoughnessT = 1.0;
    vec3 specularColorT = vec3(1.0), sheenColorT = vec3(1.0);
    if ((m.flags & kMaterialLayers) != 0u)  // uniform per draw: derivatives stay defined
        sampleLayerTexels(m, inUv, inUv1, specularT, specularColorT, coatT, coatRoughnessT, sheenColorT,
                          sheenRoughnessT);
    float diffTransT = 1.0;
    vec3 diffTransColorT = vec3(1.0);
    if ((m.flags & kMaterialDiffuseTransmission) != 0u)  // uniform per draw
        sampleDiffuseTransmissionTexels(m, inUv, inUv1, diffTransT, diffTransColorT);
    vec4 coatNormalT = vec4(0.5, 0.5, 1.0, 1.0);  // clearcoatNormalTexture (flat without one)
    if ((m.flags & kMaterialClearcoatNormal) != 0u) coatNormalT = sampleSlot(m.slots[kSlotClearcoatNormal]);
    vec3 anisotropyT = vec3(1.0, 0.5, 1.0);  // anisotropyTexture: RG direction (the tangent without one), B strength
    if ((m.flags & kMaterialAnisotropyTexture) != 0u) anisotropyT = sampleSlot(m.slots[kSlotAnisotropy]).rgb;
    vec2 iridescenceT = vec2(1.0);  // KHR_materials_iridescence: R of its texture, G of its thickness texture
    if ((m.flags & kMaterialIridescence) != 0u)
        iridescenceT = vec2(sampleSlot(m.slots[kSlotIridescence]).r, sampleSlot(m.slots[kSlotIridescenceThickness]).g);

    vec3 n = normalize(inNormal);
    vec3 t, b;
    bool haveFrame = materialTangentFrame(n, inTangent, inWorldPosition, inUv, t, b);
    vec2 xy = nt.xy * 2.0 - 1.0;                          // remap first, then reconstruct z from it
    vec3 tn = vec3(xy * m.normalScale, sqrt(max(1.0 - dot(xy, xy), 0.0)));
    vec2 cxy = coatNormalT.xy * 2.0 - 1.0;                // the coat's own normal map, from the same frame
    vec3 ctn = vec3(cxy * m.clearcoatNormalScale, sqrt(max(1.0 - dot(cxy, cxy), 0.0)));
    vec3 nc = haveFrame ? normalize(t * ctn.x + b * ctn.y + n * ctn.z) : n;
    if (haveFrame) n = normalize(t * tn.x + b * tn.y + n * tn.z);

    // Single-sided materials reject back faces here rather than with the pipeline's cull mode, so that one
    // indirect draw covers single- and double-sided materials (and mirrored instances flip the test).
    bool front = gl_FrontFacing != ((instance.flags & kInstanceMirrored) != 0u);
    bool doubleSided = (m.flags & kMaterialDoubleSided) != 0u;
    if ((!front && !doubleSided) || (m.alphaMode == kAlphaMask && baseColor.a < m.alphaCutoff)) discard;
    if (!front) {
        n = -n;
        nc = -nc;
    }

    outAlbedo = vec4(srgbEncode(baseColor.rgb), m.alphaMode == kAlphaOpaque ? 1.0 : baseColor.a);
    outNormal = packSnorm2x16(octEncode(n));
    uint anisotropyWord = 0u;  // the direction the forward pass builds (withAnisotropyFrame), else none
    if ((m.flags & kMaterialAnisotropy) != 0u && haveFrame)
        anisotropyWord = encodeAnisotropyDirection(anisotropyDirection(m.anisotropyRotation, t, b, anisotropyT.rg),
                                                   octDecode(unpackSnorm2x16(outNormal)));
    outMaterial = vec4(clamp(m.metallicFactor * mr.b, 0.0, 1.0), clamp(m.roughnessFactor * mr.g, 0.0, 1.0),
                       1.0 + m.occlusionStrength * (ao - 1.0), (m.flags & kMaterialUnlit) != 0u ? 0.0 : 1.0);
    // Emissive alpha: 1 + the material index when the material uses a BSDF extension (the lighting pass reads its
    // factors from the material buffer), else 0. RGBA16F holds integers exactly up to 2048; a material past that
    // is shaded without its extensions (a real renderer with more would add an R16UI target).
    bool layered = (m.flags & (kMaterialLayers | kMaterialAnisotropy | kMaterialDiffuseTransmission |
                               kMaterialIridescence)) != 0u &&
                   materialIndex < 2047u;
    outEmissive = vec4(emissive, layered ? float(materialIndex + 1u) : 0.0);
    vec3 diffTransColorEnc = srgbEncode(clamp(diffTransColorT, 0.0, 1.0));
    vec2 alphas = packLayerAlphas(m.flags, iridescenceT, diffTransT, diffTransColorEnc);
    uint w = packLayerWord(m.flags, octEncode(nc), anisotropyWord, anisotropyT.b, diffTransColorEnc);
    outLayers = uvec4(packUnorm4x8(vec4(specularT, coatT, coatRoughnessT, sheenRoughnessT)),
                      packUnorm4x8(vec4(srgbEncode(clamp(specularColorT, 0.0, 1.0)), alphas.x)),
                      packUnorm4x8(vec4(srgbEncode(clamp(sheenColorT, 0.0, 1.0)), alphas.y)), w);
    outLayerSpill = packLayerSpill(m.flags, diffTransT, diffTransColorEnc, anisotropyWord);
    outDepth = gl_FragCoord.z;
#ifdef GBUFFER_IDS
    outIds = uvec2(inDraw, uint(gl_PrimitiveID));
#endif
}
