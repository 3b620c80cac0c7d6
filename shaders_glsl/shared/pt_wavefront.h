// pt_wavefront.h: GPU structs of the wavefront path tracer (engine/render/path_tracer.cpp records the stages,
// shaders_glsl/pathtrace/*.comp.glsl run them): the per-pixel path state, the hit record, shadow rays, ray queues
// with their indirect-dispatch header, the static scene descriptor and the push block shared by every stage.
// Counterpart of IDKEngine's GpuWavefrontRay / GpuWavefrontPTHeader / GpuAovRay (reference 2.1), with the path
// state split from the ray queue so compaction moves 4-byte indices, never whole rays. Scalar layout.
#ifndef IDK_PT_WAVEFRONT_H
#define IDK_PT_WAVEFRONT_H
#include "interop.h"

IDK_GPU_BEGIN

IDK_CONST(uint, kPtGroupSize, 64);        // invocations per workgroup of every per-ray stage
IDK_CONST(uint, kPtQueueHeaderWords, 4);  // GpuPtQueue header: count + 3 padding words
IDK_CONST(uint, kPtMaxAlphaSkips, 64);    // alpha-tested surfaces one trace may pass (pathtrace::kMaxAlphaSkips)

// Specialization-constant ids.
IDK_CONST(uint, kSpecPtHasAlpha, 0);      // 1: the scene has MASK/BLEND materials (trace loops over alpha tests)
IDK_CONST(uint, kSpecPtNee, 1);           // 1: next-event estimation + MIS, 0: BSDF sampling only
IDK_CONST(uint, kSpecPtStackSize, 2);     // BLAS traversal stack entries
IDK_CONST(uint, kSpecPtTlasStackSize, 3); // TLAS traversal stack entries

// GpuPtPath::flags
IDK_CONST(uint, kPtPathDeltaBounce, 1u);  // the ray came from a delta (specular) lobe: no MIS on the next hit
IDK_CONST(uint, kPtPathInMedium, 2u);     // the ray travels inside a transmissive volume (absorption applies)
IDK_CONST(uint, kPtPathAlive, 4u);        // shade extended the path (it is in the next ray queue)
// KHR_materials_dispersion: bits 4-5 hold 1 + the channel the path carries alone (0: all three, pt_dispersion.h)
IDK_CONST(uint, kPtPathChannelShift, 4u);
IDK_CONST(uint, kPtPathChannelMask, 48u);

// GpuPtStagePush::flags
IDK_CONST(uint, kPtPushSobol, 1u);        // the paths draw from the sobol sampler (shared/pt_sampler.h)

// Sort keys: hit rays by material then direction octant, misses after them, dead queue slots last.
IDK_CONST(uint, kPtSortKeyBits, 16);
IDK_CONST(uint, kPtSortKeyMiss, 0x7FFFu);
IDK_CONST(uint, kPtSortKeyDead, 0xFFFFu);

// One path per pixel (ray index = pixel index = y * width + x): the state pathtrace::traceRadiance keeps in locals
// between two path vertices.
struct GpuPtPath {
    vec3 origin;
    uint depth;                 // segments traced so far
    vec3 direction;             // unit
    uint flags;                 // kPtPath*
    vec3 throughput;
    float bsdfPdf;              // pdf of the BSDF sample that made this ray (MIS weight of what it hits)
    vec3 radiance;              // accumulated along the path this sample
    uint rngState;              // gpu::PtRng of the path (the CPU reference's draw order)
    vec3 previousPosition;      // the surface point the ray left (light pdf of an emitter it hits)
    float attenuationDistance;  // medium of kPtPathInMedium (Beer-Lambert)
    vec3 attenuationColor;
    float pad;
};
IDK_GPU_SIZE(GpuPtPath, 96);

// Closest hit of a path's current ray (triangle kPtInvalid on a miss). u, v: barycentric weights of v1, v2.
struct GpuPtHit {
    float t;
    uint triangle;  // triangle of the instance's mesh (all primitives in order)
    uint instance;  // index into GpuPtSceneDesc::instances
    float u;
    float v;
};
IDK_GPU_SIZE(GpuPtHit, 20);
IDK_CONST(uint, kPtInvalid, 0xFFFFFFFFu);

// A next-event-estimation shadow ray: `contribution` is added to the pixel when nothing blocks (0, tMax).
struct GpuPtShadowRay {
    vec3 origin;
    float tMax;
    vec3 direction;
    uint pixel;
    vec3 contribution;
    float pad;
};
IDK_GPU_SIZE(GpuPtShadowRay, 48);

// One vertex of a traced geometry (pathtrace::PtGeometry, PT-A's shading data: object space, or world space for
// deformed copies).
struct GpuPtVertex {
    vec3 position;
    vec3 normal;
    vec4 tangent;  // xyz + handedness w; w = 0: no tangent
    vec2 uv0;
    vec2 uv1;
    vec4 color;    // COLOR_0, (1, 1, 1, 1) when absent
};
IDK_GPU_SIZE(GpuPtVertex, 72);

// One BLAS's shading data (the BLAS triangle numbering).
struct GpuPtGeometry {
    DeviceAddress vertices;   // GpuPtVertex[]
    DeviceAddress triangles;  // uvec3[]
    DeviceAddress materials;  // uint[] per triangle: GpuMaterial / GpuPtMaterial index
};
IDK_GPU_SIZE(GpuPtGeometry, 24);

IDK_CONST(uint, kPtInstanceMirrored, 1u);  // GpuPtTraceInstance::flags: det < 0, the winding's normal is flipped

// One TLAS instance (= one scene::Instance, the same index as PT-A's PathTraceScene::instances).
struct GpuPtTraceInstance {
    vec3 objectToWorld[4];  // affine, glm column order
    vec3 normalToWorld[3];  // inverse transpose of the upper 3x3
    uint geometry;          // GpuPtGeometry index (= BLAS)
    uint firstLight;        // first emissive-triangle light of this instance (kPtNoLight: none)
    uint flags;             // kPtInstance*
    uint pad;
};
IDK_GPU_SIZE(GpuPtTraceInstance, 100);

// Everything a stage reads that does not change during a render (uploaded once per PathTracer).
struct GpuPtSceneDesc {
    DeviceAddress tlas;          // GpuTlasDesc (our BVH rung)
    DeviceAddress accel;         // VkAccelerationStructureKHR device address (ray-query rung), 0 otherwise
    DeviceAddress geometries;    // GpuPtGeometry[]
    DeviceAddress instances;     // GpuPtTraceInstance[]
    DeviceAddress materials;     // GpuMaterial[] (GpuScene: factors, bindless texture slots)
    DeviceAddress ptMaterials;   // GpuPtMaterial[] with transmissionTexture as a bindless sampled-image index
    DeviceAddress ptSamplers;    // uint[] per material: bindless sampler of the transmission texture
    DeviceAddress lights;        // GpuPtLight[]
    DeviceAddress lightAlias;    // GpuPtAliasEntry[lightCount]
    DeviceAddress envRadiance;   // float[3 * width * height], intensity applied, row 0 = up
    DeviceAddress envAlias;      // GpuPtAliasEntry[width * height] (0: black environment)
    uint envWidth;
    uint envHeight;
    float envSelectProbability;  // NEE picks the environment with this probability, else the light list
    uint lightCount;
    uint instanceCount;
    uint pad;
    DeviceAddress albedoTables;  // float[kPtAlbedoTableFloats]: the energy-compensation tables (pt_energy.h)
};
IDK_GPU_SIZE(GpuPtSceneDesc, 120);

// The push block of every stage (<= 128 bytes). Per stage: camera fills queueIn (all pixels) and argsOut (its
// dispatch), empties queueOut, shadow and aux (the other shadow queue), reads the GpuPtCamera at `accum`;
// trace reads queueIn and writes hits (and sort keys at `aux` when nonzero); shade reads queueIn, appends to
// queueOut and shadow; args sizes argsOut / argsShadow from queueOut / shadow and empties queueIn and aux;
// shadow reads shadow; accumulate / resolve read `accum` (a GpuPtAccum).
struct GpuPtStagePush {
    DeviceAddress scene;       // GpuPtSceneDesc
    DeviceAddress paths;       // GpuPtPath[pixels]
    DeviceAddress hits;        // GpuPtHit[pixels]
    DeviceAddress queueIn;     // GpuPtQueue
    DeviceAddress queueOut;    // GpuPtQueue
    DeviceAddress shadow;      // GpuPtQueue of shadow-ray indices
    DeviceAddress shadowRays;  // GpuPtShadowRay[pixels]
    DeviceAddress accum;       // GpuPtAccum, or GpuPtCamera for the camera stage
    DeviceAddress aux;         // see above
    DeviceAddress argsOut;     // VkDispatchIndirectCommand of queueOut (camera: of queueIn)
    DeviceAddress argsShadow;  // VkDispatchIndirectCommand of shadow
    uvec2 extent;
    uint sampleIndex;          // global sample number (RNG stream)
    uint seed;
    uint bounce;
    uint maxDepth;
    uint rouletteDepth;
    uint flags;                // kPtPush*
};
IDK_GPU_SIZE(GpuPtStagePush, 120);

// A ray queue: `count` entries of `items` (pixel indices); the header is kPtQueueHeaderWords words so that the
// items start 16 bytes in (the radix sort addresses them as a 32-bit array at element offset 4).
//   struct GpuPtQueue { uint count; uint pad[3]; uint items[]; }   (GLSL: PtQueueRef)

// Camera constants (one small buffer per render; the camera stage reads them).
struct GpuPtCamera {
    mat4 inverseViewProjection;
    vec3 position;
    float pad;
};
IDK_GPU_SIZE(GpuPtCamera, 80);

// Progressive sums per pixel (sum of samples; w counts them), the luminance's second moment and the first-hit
// guides for the denoiser.
struct GpuPtAccum {
    DeviceAddress color;    // vec4[pixels]: sum of radiance, w = samples
    DeviceAddress albedo;   // vec4[pixels]: sum of first-hit albedo (1 for the sky)
    DeviceAddress normal;   // vec4[pixels]: sum of first-hit world normal (0 for the sky)
    DeviceAddress depth;    // float[pixels]: sum of first-hit view distance (0 for the sky)
    DeviceAddress guides;   // GpuPtGuide[pixels]: this sample's first-hit guides (written by shade at bounce 0)
    DeviceAddress moment;   // float[pixels]: sum of squared radiance luminance (the denoiser's per-pixel variance)
    uint colorImage;        // resolve: bindless storage images (rgba32f, rgba16f, rgba16f, r32f, r32f)
    uint albedoImage;
    uint normalImage;
    uint depthImage;
    uint varianceImage;     // variance of the mean luminance, -1 below 2 samples
    uint pad;               // C++ rounds the struct to its 8-byte alignment
};
IDK_GPU_SIZE(GpuPtAccum, 72);

struct GpuPtGuide {
    vec3 albedo;
    float depth;
    vec3 normal;
    float pad;
};
IDK_GPU_SIZE(GpuPtGuide, 32);

IDK_GPU_END

#endif
