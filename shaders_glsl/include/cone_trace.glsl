// cone_trace.glsl: marching one cone through the voxel grid's mip chain (the march, level choice and compositing
// are shared/vxgi_cone.h, which the CPU cone tracer compiles too; here only the fetches), and the sky seen through
// what the cone leaves transparent. Ports IDKEngine's include/TraceCone.glsl without its GIBoost / GISkyBoxBoost.
#ifndef IDK_CONE_TRACE_GLSL
#define IDK_CONE_TRACE_GLSL
#include "bindless.glsl"
#include "environment.glsl"
#include "vxgi_types.h"
#include "vxgi_cone.h"

vec4 sampleVolume(ConeTracePush c, uint volume, vec3 uvw, float lod) {
    return textureLod(sampler3D(gTextures3D[nonuniformEXT(volume)], gSamplers[nonuniformEXT(c.gridSampler)]), uvw, lod);
}

// The grid seen along `dir` at `lod` (grid levels: level L of the directional volumes).
vec4 sampleVoxels(ConeTracePush c, vec3 uvw, vec3 dir, float lod) {
    vec4 sx = sampleVolume(c, c.directions[vxgiDirectionIndex(dir, 0u)], uvw, lod);
    vec4 sy = sampleVolume(c, c.directions[vxgiDirectionIndex(dir, 1u)], uvw, lod);
    vec4 sz = sampleVolume(c, c.directions[vxgiDirectionIndex(dir, 2u)], uvw, lod);
    return vxgiCombine(dir, sx, sy, sz);
}

// Radiance arriving at the receiver `origin` (geometric normal `plane`) through the cone (unit axis `dir`, tangent
// of its half-angle `tanHalf`).
vec3 traceCone(GpuFrame f, ConeTracePush c, vec3 origin, vec3 plane, vec3 dir, float tanHalf) {
    VxgiMarch m = vxgiMarchBegin(origin, plane, dir, tanHalf, c.voxelSize);
    while (vxgiMarchNext(m, c.gridMin, c.voxelSize, c.gridSize, c.maxLod))
        vxgiMarchTake(m, sampleVoxels(c, m.uvw, dir, m.lod), c.stepFactor);
    // The sky through the cone: the environment mip whose texels span the cone's full angle.
    float texels = 2.0 * atan(tanHalf) * f.environmentWidth / 6.28318530717959;
    float skyLod = clamp(log2(max(texels, 1.0)), 0.0, f.environmentMaxLod);
    return m.radiance + (1.0 - m.opacity) * environmentRadiance(f, dir, skyLod);
}

#endif
