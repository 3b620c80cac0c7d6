// deferred_types.h: per-frame constants and the push blocks of the deferred renderer's passes (gbuffer,
// deferred_lighting, sky, tonemap). Ports the role of IDKEngine's per-frame UBO (binding 1), its lights UBO
// (binding 2) and skybox UBO (binding 5): here one GpuFrame in host-visible memory, reached by device address.
#ifndef IDK_DEFERRED_TYPES_H
#define IDK_DEFERRED_TYPES_H
#include "interop.h"

IDK_GPU_BEGIN

IDK_CONST(uint, kShCoefficients, 9);  // order-2 spherical harmonics (Ramamoorthi & Hanrahan 2001)

struct GpuFrame {
    mat4 viewProjection;         // world -> Vulkan clip (y down, depth 0 near .. 1 far, test LESS)
    mat4 inverseViewProjection;  // clip -> world
    vec3 cameraPosition;         // world
    uint lightCount;
    DeviceAddress lights;        // GpuLight[lightCount]; 0 when the scene has none
    DeviceAddress albedoTables;  // float[]: the GGX/sheen albedo tables (shared/pt_energy.h, gPtAlbedoTables)
    uvec2 extent;                // render size in pixels
    // Diffuse irradiance E(n) = sh[0] + sh[1] y + sh[2] z + sh[3] x + sh[4] xy + sh[5] yz + sh[6] (3z^2 - 1)
    // + sh[7] xz + sh[8] (x^2 - y^2): the SH9 projection of the environment with the cosine-lobe factors and
    // the basis constants folded in (environment.cpp). Multiplied by environmentIntensity already.
    vec3 irradianceSh[kShCoefficients];
    uint environmentTexture;     // bindless equirectangular radiance, full mip chain
    uint environmentSampler;     // linear, mip linear, repeat (v is clamped in the shader)
    float environmentMaxLod;     // mip count - 1
    float environmentIntensity;  // scales the background and the specular ambient (0: black, no ambient)
    float environmentWidth;      // mip 0 width in texels (for the roughness -> lod mapping)
    float environmentHeight;     // mip 0 height in texels (keeps filtering off the poles' far side)
    uint pad;
};
IDK_GPU_SIZE(GpuFrame, 304);

// gbuffer.vert/.frag: scene buffers by device address (they may exceed a descriptor's range).
struct GBufferPush {
    DeviceAddress frame;      // GpuFrame
    DeviceAddress vertices;   // GpuVertex[]
    DeviceAddress instances;  // GpuInstance[], indexed by gl_DrawID
    DeviceAddress meshes;     // GpuMesh[]
    DeviceAddress materials;  // GpuMaterial[]
    DeviceAddress colors;     // vec4[] per vertex (COLOR_0), 0 when no primitive has vertex colours
    DeviceAddress uv1;        // vec2[] per vertex (TEXCOORD_1), 0 when no primitive has a second UV set
};
IDK_GPU_SIZE(GBufferPush, 56);

// The G-buffer is read with imageLoad (bindless storage indices), never sampled: a render target that sits in
// the sampled-image array while a pass writes it would trip the synchronization validation of the layers we
// run (1.3.239 treats every element of a bindless array as accessed), and storage loads are exact anyway.
// Formats: albedo RGBA8 (sRGB-encoded by the shader), normal R32UI (octahedral, packSnorm2x16), material
// RGBA8, emissive RGBA16F, depth R32F (gl_FragCoord.z; the depth attachment itself is transient), and only for
// scenes with BSDF-extension textures layers RGBA32UI (include/gbuffer_fragment.glsl packs the texels).

// deferred_lighting.comp: G-buffer and output (bindless storage-image indices).
struct LightingPush {
    DeviceAddress frame;
    uint albedo;     // RGBA8: sRGB-encoded base colour, alpha
    uint normal;     // R32UI: octahedral world normal, packSnorm2x16
    uint material;   // RGBA8: metallic, roughness, occlusion, lit (0: unlit, output = albedo)
    uint emissive;   // RGBA16F: emitted radiance; alpha 1 + material index of a layered material (else 0)
    uint depth;      // R32F: 0 near .. 1 far (1 = background)
    uint target;     // RGBA16F: linear radiance
    DeviceAddress pointShadows;  // GpuPointShadow[lightCount] (shared/shadow_types.h), 0: no light casts one
    DeviceAddress materials;     // GpuMaterial[] (the BSDF extension factors of layered materials), 0: none
    DeviceAddress vrsRates;      // software VRS: shade only cell anchors (shared/vrs_types.h); 0: every pixel
    uint ambientOcclusion;       // R32F storage: SSAO visibility of the ambient light; kLightingNoAo: none
    uint vxgiDiffuse;            // RGBA16F VXGI irradiance (include/vxgi_ambient.glsl), kNoVxgi: GI off
    uint vxgiSpecular;           // RGBA16F VXGI reflection radiance
    uint ssr;                    // RGBA16F screen-space reflections (shared/ssr_types.h), kSsrNoImage: off
    uint layers;                 // RGBA32UI G-buffer extension texels, kLightingNoLayers: none
    uint layerSpill;             // RG32UI G-buffer texels the layers target has no bits for, kLightingNoLayers: none
};
IDK_GPU_SIZE(LightingPush, 80);
IDK_CONST(uint, kLightingNoAo, 0xFFFFFFFFu);
IDK_CONST(uint, kLightingNoLayers, 0xFFFFFFFFu);

// sky.comp: writes the environment where depth == 1.
struct SkyPush {
    DeviceAddress frame;
    uint depth;      // R32F storage image
    uint target;     // RGBA16F storage image
    DeviceAddress vrsRates;  // as LightingPush::vrsRates
};
IDK_GPU_SIZE(SkyPush, 24);

// tonemap.frag: AgX of exposure * radiance, sRGB-encoded into an RGBA8 colour attachment. A fragment pass, not
// compute: the displayed image is then no storage image, so it needs no layout change after the compute passes
// that use the bindless storage-image array (old validation layers count those as touching every element).
struct TonemapPush {
    uint source;     // RGBA16F storage image (imageLoad)
    float exposure;  // linear scale applied before the curve
};
IDK_GPU_SIZE(TonemapPush, 8);

IDK_CONST(uint, kLightingGroupSize, 8);  // 8x8 invocations per workgroup (lighting, sky)

IDK_GPU_END
#endif
