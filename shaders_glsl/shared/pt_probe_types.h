// pt_probe_types.h: input and output records of the path-tracing maths conformance probe
// (shaders_glsl/conformance/pt_bsdf_probe.comp.glsl, tests/conformance/pt_math): one random case per invocation,
// evaluated by the GLSL compilation of pt_sampling.h and compared with the C++ one.
#ifndef IDK_PT_PROBE_TYPES_H
#define IDK_PT_PROBE_TYPES_H
#include "pt_types.h"

IDK_GPU_BEGIN

struct GpuPtProbeCase {
    PtSurface surface;
    vec3 wo;
    vec3 wi;          // direction ptEvalBsdf is evaluated for
    vec3 u;           // ptSampleBsdf's uniforms
    uint pixel;       // RNG seed inputs
    uint sampleIndex;
    uint seed;
    GpuPtLight light;
    vec3 point;       // shading point for the light
    vec2 lightU;
    vec3 envDir;      // direction for ptEquirectUv / ptEnvironmentTexel / ptEnvironmentPdf
    vec2 envU;        // uniforms for ptSampleEnvironment
    uint envTexel;
    float envProbability;
};
IDK_GPU_SIZE(GpuPtProbeCase, 188 + 36 + 12 + 80 + 12 + 8 + 12 + 8 + 8);

struct GpuPtProbeResult {
    vec3 evalValue;
    float evalPdf;
    vec3 sampleWi;
    float samplePdf;
    vec3 sampleWeight;
    uint sampleLobe;
    uvec4 rngUints;     // ptNextUint x4 after ptRngInit
    float rngFloat;     // the 5th draw as ptRandom
    uint lightOk;
    float lightDistance;
    float lightPdf;
    vec3 lightDirection;
    float lightPdfAtSample;  // ptLightPdf(light, point, sampled position)
    vec3 lightRadiance;
    uint envTexel;
    vec2 envUv;
    float envPdf;
    float envSamplePdf;
    vec3 envSampleDir;
    uint hash;          // ptHash(pixel)
};
IDK_GPU_SIZE(GpuPtProbeResult, 16 + 16 + 16 + 16 + 4 + 4 + 4 + 4 + 12 + 4 + 12 + 4 + 8 + 4 + 4 + 12 + 4);

IDK_GPU_END
#endif
