// lambert_types.h: GPU structs of the minimal Lambert rasterizer (the foundation's first pass, replaced by the
// deferred PBR renderer later). Vertices are pre-transformed to world space and pulled from a bindless buffer.
#ifndef IDK_LAMBERT_TYPES_H
#define IDK_LAMBERT_TYPES_H
#include "interop.h"

IDK_GPU_BEGIN

struct GpuLambertVertex {
    vec3 position;  // world space
    vec3 normal;    // world space, unit
    uint material;  // index into the material buffer
};
IDK_GPU_SIZE(GpuLambertVertex, 28);

struct GpuLambertMaterial {
    vec3 albedo;    // linear base colour
    vec3 emissive;  // linear radiance, emissive strength applied
};
IDK_GPU_SIZE(GpuLambertMaterial, 24);

struct GpuLambertLight {
    vec3 position;   // world space
    vec3 intensity;  // colour * intensity in candela (W/sr for our purposes)
};
IDK_GPU_SIZE(GpuLambertLight, 24);

IDK_CONST(uint, kLambertMaxLights, 8);

struct LambertPush {
    mat4 viewProjection;
    vec3 ambient;          // constant ambient radiance
    uint vertexBuffer;     // bindless storage-buffer indices
    uint materialBuffer;
    uint lightBuffer;
    uint lightCount;
};
IDK_GPU_SIZE(LambertPush, 92);

IDK_GPU_END
#endif
