// forward_body.h (GLSL include): body of transparency/forward.frag and oit/weighted.frag: forward shading of BLEND materials over the lit opaque image: the material as the G-buffer
// samples it, the same lights, point shadows and environment ambient as deferred lighting (surface_lighting.glsl),
// output (radiance, alpha) for "over" blending. Depth-tested against the G-buffer's depth copy without writing.
// With --gi vxgi, the sorted rung's fragments inside the voxel grid trace the cone set themselves (include/cone_trace.glsl, the
// parameters from the VXGI feature's buffer, TransparencyPush::vxgiCones) in place of the SH ambient, as deferred
// lighting does with the G-buffer pass's traced images (vxgi_ambient.glsl).
// With IDK_FORWARD_TRANSMISSION (transmission/forward.frag), the screen-space transmission pass: transmissive
// materials, their radiance from include/screen_transmission.glsl, written opaque (alpha 1).
// Ports IDKEngine's RecordTransparent/fragment.glsl, sorted back to front instead of its k-buffer (reference 2.14).
#extension GL_GOOGLE_include_directive : require
#include "scene_buffers.glsl"
#include "bindless.glsl"
#include "material_eval.glsl"
#include "surface_lighting.glsl"
#ifdef IDK_FORWARD_VXGI
// Only the sorted rung (transparency/forward.frag) traces cones: a draw whose shader uses the bindless 3D array
// counts for the synchronization validation layer as reading the voxel grid, which the OIT rungs' graphs order
// against its writes with a reported write-after-write; they keep the SH ambient.
#include "cone_trace.glsl"
#include "vxgi_ambient.glsl"

IDK_BINDLESS_BUFFER_READONLY(gVxgiCones, VxgiConeParams);
#endif

#if defined(IDK_OIT_LAYER_DEPTHS) || defined(IDK_OIT_LAYERS)
// The fixed-layer rung (oit/layers_depth.frag, oit/layers_shade.frag): its arrays follow the forward push block.
#include "oit_layers.glsl"
layout(push_constant, scalar) uniform Push { TransparencyPush p; OitLayerBuffers oitLayers; };
#elif defined(IDK_FORWARD_TRANSMISSION)
// The transmission pass: its opaque-colour chain follows the forward push block.
#include "screen_transmission.glsl"
layout(push_constant, scalar) uniform Push { TransparencyPush p; TransmissionPush tp; };
#else
layout(push_constant, scalar) uniform Push { TransparencyPush p; };
#endif

layout(location = 0) in vec3 inWorldPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec4 inTangent;
layout(location = 3) in vec2 inUv;
layout(location = 4) flat in uint inInstance;
layout(location = 5) in vec4 inColor;
layout(location = 6) in vec2 inUv1;

#ifdef IDK_OIT_WEIGHTED
// Weighted blended OIT (oit/weighted.frag): both additive. 0: (radiance a, a) times the depth weight;
// 1: -ln(1 - a) in r (the product of (1 - a) over the fragments, summed as logarithms).
layout(location = 0) out vec4 outAccum;
layout(location = 1) out vec4 outRevealage;
void writeTransparent(vec4 c) {
    float a = clamp(c.a, 0.0, 0.999);
    // McGuire & Bavoil 2013, eq. 9 weight on the fragment's depth (0 near .. 1 far).
    float z = gl_FragCoord.z;
    float w = clamp(a * max(1e-2, 3e3 * (1.0 - z) * (1.0 - z) * (1.0 - z)), 1e-2, 3e3);
    outAccum = vec4(c.rgb * a, a) * w;
    outRevealage = vec4(-log(1.0 - a), 0.0, 0.0, 0.0);
}
#elif defined(IDK_OIT_LAYERS)
// Fixed-layer OIT (oit/layers_shade.frag): no attachment; (radiance, alpha) into the slot of this depth.
void writeTransparent(vec4 c) {
    int slot = oitClaimSlot(oitLayers, ivec2(gl_FragCoord.xy), gl_FragCoord.z);
    if (slot >= 0) oitStoreColor(oitLayers, ivec2(gl_FragCoord.xy), slot, c);
}
#elif defined(IDK_OIT_LAYER_DEPTHS)
void writeTransparent(vec4) {}  // unused: the depth pass returns before shading
#else
layout(location = 0) out vec4 outColor;  // linear radiance, alpha = coverage ("over": SRC_ALPHA, 1 - SRC_ALPHA)
void writeTransparent(vec4 c) { outColor = c; }
#endif

void main() {
    GpuInstance instance = InstanceBuffer(p.instances).data[inInstance];
    GpuMaterial m = MaterialBuffer(p.materials).data[nonuniformEXT(MeshBuffer(p.meshes).data[instance.mesh].material)];

    // Every sample happens before any discard so implicit derivatives stay defined for the whole quad; so does the
    // triangle's plane (the cones' receiver plane), from the world position's screen derivatives.
#ifdef IDK_FORWARD_VXGI
    vec3 geometric = cross(dFdx(inWorldPosition), dFdy(inWorldPosition));
#endif
    vec4 baseColor = m.baseColorFactor * sampleMaterialSlot(m.slots[kSlotBaseColor], inUv, inUv1) * inColor;
    vec4 mr = sampleMaterialSlot(m.slots[kSlotMetallicRoughness], inUv, inUv1);
    vec4 nt = sampleMaterialSlot(m.slots[kSlotNormal], inUv, inUv1);
    float ao = sampleMaterialSlot(m.slots[kSlotOcclusion], inUv, inUv1).r;
    vec3 emissive = m.emissiveFactor * sampleMaterialSlot(m.slots[kSlotEmissive], inUv, inUv1).rgb;
    LayerTexels layerTexels = noLayerTexels();  // KHR_materials_specular / _clearcoat / _sheen textures
    if ((m.flags & kMaterialLayers) != 0u)      // uniform per draw: derivatives stay defined
        sampleLayerTexels(m, inUv, inUv1, layerTexels.specular, layerTexels.specularColor, layerTexels.clearcoat,
                          layerTexels.clearcoatRoughness, layerTexels.sheenColor, layerTexels.sheenRoughness);
    if ((m.flags & kMaterialDiffuseTransmission) != 0u)  // KHR_materials_diffuse_transmission textures
        sampleDiffuseTransmissionTexels(m, inUv, inUv1, layerTexels.diffuseTransmission,
                                        layerTexels.diffuseTransmissionColor);
    vec4 coatNormalTexel = vec4(0.5, 0.5, 1.0, 1.0);  // clearcoatNormalTexture (flat without one)
    if ((m.flags & kMaterialClearcoatNormal) != 0u)
        coatNormalTexel = sampleMaterialSlot(m.slots[kSlotClearcoatNormal], inUv, inUv1);
    vec3 anisotropyTexel = vec3(1.0, 0.5, 1.0);  // anisotropyTexture: RG direction, B strength
    if ((m.flags & kMaterialAnisotropyTexture) != 0u)
        anisotropyTexel = sampleMaterialSlot(m.slots[kSlotAnisotropy], inUv, inUv1).rgb;
    vec2 iridescenceTexels = vec2(1.0);  // KHR_materials_iridescence: R of its texture, G of its thickness texture
    if ((m.flags & kMaterialIridescence) != 0u)
        iridescenceTexels = vec2(sampleMaterialSlot(m.slots[kSlotIridescence], inUv, inUv1).r,
                                 sampleMaterialSlot(m.slots[kSlotIridescenceThickness], inUv, inUv1).g);
#ifdef IDK_FORWARD_TRANSMISSION
    vec2 transmissionTexels = vec2(sampleMaterialSlot(m.slots[kSlotTransmission], inUv, inUv1).r,
                                   sampleMaterialSlot(m.slots[kSlotThickness], inUv, inUv1).g);
#endif
    vec3 n = normalize(inNormal);
    vec3 t, b;
    bool haveFrame = materialTangentFrame(n, inTangent, inWorldPosition, inUv, t, b);

    // The opaque surfaces' depth test (LESS against the G-buffer's copy of the kept depth), and facing.
    float opaqueDepth = imageLoad(gImagesR32f[p.depth], ivec2(gl_FragCoord.xy)).r;
    bool front = gl_FrontFacing != ((instance.flags & kInstanceMirrored) != 0u);
    if (gl_FragCoord.z >= opaqueDepth || (!front && (m.flags & kMaterialDoubleSided) == 0u)) discard;
#ifdef IDK_FORWARD_TRANSMISSION
    if (m.alphaMode == kAlphaMask && baseColor.a < m.alphaCutoff) discard;  // as the G-buffer's alpha test
#endif
#ifdef IDK_OIT_LAYER_DEPTHS
    oitInsertDepth(oitLayers, ivec2(gl_FragCoord.xy), gl_FragCoord.z);  // fixed-layer rung, first pass: depth only
    return;
#endif

    vec2 xy = nt.xy * 2.0 - 1.0;
    vec3 tn = vec3(xy * m.normalScale, sqrt(max(1.0 - dot(xy, xy), 0.0)));
    vec2 cxy = coatNormalTexel.xy * 2.0 - 1.0;  // the coat's own normal map, from the same frame
    vec3 ctn = vec3(cxy * m.clearcoatNormalScale, sqrt(max(1.0 - dot(cxy, cxy), 0.0)));
    vec3 nc = haveFrame ? normalize(t * ctn.x + b * ctn.y + n * ctn.z) : n;
    if (haveFrame) n = normalize(t * tn.x + b * tn.y + n * tn.z);
    if (!front) {
        n = -n;
        nc = -nc;
    }
    if ((m.flags & kMaterialUnlit) != 0u) {
        writeTransparent(vec4(baseColor.rgb, baseColor.a));
        return;
    }

    GpuFrame f = FrameBuffer(p.frame).frame;
    gPtAlbedoTables = f.albedoTables;
    vec2 ndc = gl_FragCoord.xy / vec2(f.extent) * 2.0 - 1.0;
    vec4 hNear = f.inverseViewProjection * vec4(ndc, 0.0, 1.0);
    vec3 v = normalize(hNear.xyz / hNear.w - inWorldPosition);  // towards the eye (orthographic views too)
    float metallic = clamp(m.metallicFactor * mr.b, 0.0, 1.0);
    float roughness = clamp(m.roughnessFactor * mr.g, 0.0, 1.0);
    float occlusion = 1.0 + m.occlusionStrength * (ao - 1.0);
    SurfaceLayers layers = withIridescenceTexels(texturedLayers(materialLayers(m), layerTexels), m, iridescenceTexels);
    if ((m.flags & kMaterialClearcoatNormal) != 0u) layers.clearcoatNormal = nc;
    layers = withAnisotropyStrengthTexel(layers, anisotropyTexel.b);
    if (haveFrame) layers = withAnisotropyFrame(layers, m, t, b, anisotropyTexel.rg);
#ifdef IDK_FORWARD_TRANSMISSION
    writeTransparent(vec4(emissive + shadeTransmissive(f, p.pointShadows, tp, instance, m, inWorldPosition, n, v,
                                                       baseColor.rgb, metallic, roughness, occlusion, layers,
                                                       transmissionTexels),
                          1.0));  // opaque over the frame: the light behind is in the refracted term
    return;
#endif
    vec3 radiance = emissive + shadeSurface(f, p.pointShadows, inWorldPosition, n, v, baseColor.rgb, metallic,
                                            roughness, occlusion, layers);
#ifdef IDK_FORWARD_VXGI
    if (p.vxgiCones != kNoVxgi) {
        VxgiConeParams c = gVxgiCones[p.vxgiCones].data[0];  // one index for the whole draw
        if (insideVoxelGrid(c, inWorldPosition)) {
            // The geometric normal on the shading normal's side (a degenerate plane: the shading normal).
            vec3 plane = dot(geometric, geometric) > 0.0 ? normalize(geometric) : n;
            if (dot(plane, n) < 0.0) plane = -plane;
            vec3 e = traceMeanRadiance(f, c, inWorldPosition, plane, n);
            vec3 specular = traceSpecular(f, c, inWorldPosition, plane, n, v, roughness, e);
            radiance += vxgiAmbientDeltaOf(f, e * 3.14159265358979, specular, n, v, baseColor.rgb, metallic, roughness,
                                           occlusion, layers);
        }
    }
#endif
    writeTransparent(vec4(radiance, baseColor.a));
}
