#version 460
// pt_bsdf_probe.comp.glsl: runs the GLSL compilation of the path tracer's shared maths (shared/pt_sampling.h) on
// one GpuPtProbeCase per invocation: RNG, BSDF evaluate and sample, light sample and pdf, environment mapping,
// texel lookup, pdf and sampling. tests/conformance/pt_math compares every field with the C++ compilation.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_buffer_reference : require
#include "interop.h"
#include "pt_sampling.h"
#include "pt_probe_types.h"

layout(local_size_x = 64) in;
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer CaseArray { GpuPtProbeCase data[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) writeonly buffer ResultArray { GpuPtProbeResult data[]; };
layout(push_constant, scalar) uniform Push { CaseArray cases; ResultArray results; uint count; uint envWidth;
                                             uint envHeight; uint pad; uint64_t albedoTables; } p;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= p.count) return;
    gPtAlbedoTables = p.albedoTables;
    GpuPtProbeCase c = p.cases.data[i];
    GpuPtProbeResult r;

    r.evalValue = ptEvalBsdf(c.surface, c.wo, c.wi, r.evalPdf);
    ptSampleBsdf(c.surface, c.wo, c.u, r.sampleWi, r.sampleWeight, r.samplePdf, r.sampleLobe);

    PtRng rng = ptRngInit(c.pixel, c.sampleIndex, c.seed);
    r.rngUints.x = ptNextUint(rng);
    r.rngUints.y = ptNextUint(rng);
    r.rngUints.z = ptNextUint(rng);
    r.rngUints.w = ptNextUint(rng);
    r.rngFloat = ptRandom(rng);
    r.hash = ptHash(c.pixel);

    PtLightSample ls;
    r.lightOk = ptSampleLight(c.light, c.point, c.lightU, ls) ? 1u : 0u;
    r.lightDistance = ls.distance;
    r.lightPdf = ls.pdf;
    r.lightDirection = ls.direction;
    r.lightRadiance = ls.radiance;
    r.lightPdfAtSample = ptLightPdf(c.light, c.point, ls.position);

    r.envUv = ptEquirectUv(c.envDir);
    r.envTexel = ptEnvironmentTexel(c.envDir, p.envWidth, p.envHeight);
    r.envPdf = ptEnvironmentPdf(c.envProbability, c.envDir, p.envWidth, p.envHeight);
    r.envSamplePdf = ptSampleEnvironment(c.envTexel, c.envProbability, p.envWidth, p.envHeight, c.envU,
                                         r.envSampleDir);
    p.results.data[i] = r;
}
