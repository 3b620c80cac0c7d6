#version 460
// accumulate.comp.glsl: one invocation per pixel after the last bounce: adds this sample's path radiance and
// first-hit guides to the running sums, and its squared luminance to the second moment (RGBA32F; w counts the samples). Port of IDKEngine PathTracing/FinalDraw,
// which kept a running mean instead of a sum (a sum is exact for any sample count and cheaper to update).
#extension GL_GOOGLE_include_directive : require
#include "wf_common.h"

layout(local_size_x = kPtGroupSize) in;

void main() {
    uint pixel = gl_GlobalInvocationID.x;
    if (pixel >= pc.extent.x * pc.extent.y) return;
    GpuPtAccum a = WfAccumRef(pc.accum).a;
    vec3 radiance = WfPathRef(pc.paths).p[pixel].radiance;
    // A non-finite sample would poison every later mean: it is dropped (counted, so the estimate stays unbiased
    // only if such samples have zero probability; the tests assert none occur).
    if (any(isnan(radiance)) || any(isinf(radiance))) radiance = vec3(0.0);
    GpuPtGuide g = WfGuideRef(a.guides).g[pixel];
    WfVec4Ref(a.color).v[pixel] += vec4(radiance, 1.0);
    WfVec4Ref(a.albedo).v[pixel] += vec4(g.albedo, 1.0);
    WfVec4Ref(a.normal).v[pixel] += vec4(g.normal, 1.0);
    WfFloatRef(a.depth).f[pixel] += g.depth;
    float l = dot(radiance, vec3(0.2126, 0.7152, 0.0722));
    WfFloatRef(a.moment).f[pixel] += l * l;
}
