// shadow_types.h: point-light cube shadows (engine/render/point_shadow_maps.cpp, passes/point_shadows.cpp) and the
// forward transparency pass (passes/transparency.cpp): the per-light shadow table the lighting reads and the push
// blocks of both passes. Ports IDKEngine's GpuPointShadow (reference 2.12) and the RecordTransparent push state
// (2.14); the cube-face projection itself is in include/shadows.glsl.
#ifndef IDK_SHADOW_TYPES_H
#define IDK_SHADOW_TYPES_H
#include "interop.h"

IDK_GPU_BEGIN

IDK_CONST(uint, kNoShadow, 0xFFFFFFFFu);  // GpuPointShadow::cube of a light that casts no shadow

// One entry per scene light (indexed like GpuLight). A cube face f renders the light's view along face f's
// major axis with a 90-degree frustum; the stored depth is d(ma) = far / (far - near) * (1 - near / ma) of the
// major-axis distance ma = max(|x|, |y|, |z|) of (point - position): 0 at near, 1 at far (cleared to 1).
struct GpuPointShadow {
    vec3 position;     // world; the cube's centre (the light's position this frame)
    float nearPlane;   // of every face's projection
    float farPlane;    // beyond it nothing is stored and nothing is shadowed
    uint cube;         // bindless textureCube (D32), or kNoShadow
    uint samplerIndex; // bindless comparison sampler (LESS_OR_EQUAL, linear, clamp)
    float texelScale;  // 2 / resolution: one texel's world size at major-axis distance 1
    uint mapOffset;    // directional and spot lights: byte offset of their GpuShadowMap records from the table's
    uint mapCount;     // start (cube: the bindless 2D-array image of the maps); 0 records: a cube or no shadow
};
IDK_GPU_SIZE(GpuPointShadow, 40);

// Texels between a projected map's border and the centre of a lookup it serves: the 3x3 PCF kernel (1 texel) and
// its bilinear footprint (1 texel), plus room for the normal offset. Cascades and spot maps are fitted with it.
IDK_CONST(float, kShadowMapMargin, 3.0f);

// One projected shadow map (a cascade of a directional light, or a spot light's single map), appended after the
// per-light entries of the table: uv = ndc.xy * 0.5 + 0.5 and depth = ndc.z of viewProjection * world, stored in
// layer `layer` of the light's 2D-array image (cleared to 1). Built by render/shadow_cascades.cpp.
struct GpuShadowMap {
    mat4 viewProjection;  // orthographic (cascade) or perspective (spot), Vulkan clip space
    float texelScale;     // world size of one texel: times clip.w for a perspective map
    float invResolution;  // 1 / map size in texels
    uint layer;
    uint perspective;     // 1: spot map
};
IDK_GPU_SIZE(GpuShadowMap, 80);

// light_shadows/map.vert + mask.frag: one layer of a directional or spot light's maps.
struct ShadowMapPush {
    DeviceAddress vertices;   // GpuVertex[]
    DeviceAddress instances;  // GpuInstance[], indexed by gl_DrawID
    DeviceAddress meshes;     // GpuMesh[]
    DeviceAddress materials;  // GpuMaterial[] (alpha MASK only)
    DeviceAddress colors;     // vec4[] COLOR_0 or 0
    DeviceAddress uv1;        // vec2[] TEXCOORD_1 or 0
    mat4 viewProjection;
};
IDK_GPU_SIZE(ShadowMapPush, 112);

// point_shadows/{layered,face}.vert + mask.frag: one light, all faces (layered) or one face (face index).
struct PointShadowPush {
    DeviceAddress vertices;   // GpuVertex[]
    DeviceAddress instances;  // GpuInstance[], indexed by gl_DrawID
    DeviceAddress meshes;     // GpuMesh[]
    DeviceAddress materials;  // GpuMaterial[] (alpha MASK only)
    DeviceAddress colors;     // vec4[] COLOR_0 or 0
    DeviceAddress uv1;        // vec2[] TEXCOORD_1 or 0
    vec3 lightPosition;
    float nearPlane;
    float farPlane;
    uint face;                // face.vert only: the cube face this draw renders (layered.vert: gl_InstanceIndex)
};
IDK_GPU_SIZE(PointShadowPush, 72);

// transparency/forward.vert/.frag: BLEND draws, instance = gl_InstanceIndex (firstInstance of the sorted command).
struct TransparencyPush {
    DeviceAddress frame;         // GpuFrame
    DeviceAddress vertices;
    DeviceAddress instances;
    DeviceAddress meshes;
    DeviceAddress materials;
    DeviceAddress colors;        // 0 when absent
    DeviceAddress uv1;           // 0 when absent
    DeviceAddress pointShadows;  // GpuPointShadow[lightCount] or 0 (no shadow-casting light)
    uint depth;                  // R32F storage image: the G-buffer depth (the opaque surfaces, 1 = sky)
    uint vxgiCones;              // --gi vxgi: bindless storage buffer of one VxgiConeParams (vxgi_types.h): the
                                 // fragments inside the grid trace cones; kNoVxgi (0xFFFFFFFF): the SH ambient
};
IDK_GPU_SIZE(TransparencyPush, 72);

IDK_GPU_END
#endif
