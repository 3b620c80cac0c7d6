// cone_trace.glsl: marching one cone through the voxel grid's mip chain with front-to-back compositing, and the
// sky seen through what the cone leaves transparent. Ports IDKEngine's include/TraceCone.glsl without its
// GIBoost / GISkyBoxBoost factors; the step's opacity is corrected for the step length (Beer-Lambert over the
// sample's width) so the result does not depend on the step factor beyond sampling error.
#ifndef IDK_CONE_TRACE_GLSL
#define IDK_CONE_TRACE_GLSL
#include "bindless.glsl"
#include "environment.glsl"
#include "vxgi_types.h"

vec4 sampleVolume(ConeTracePush c, uint volume, vec3 uvw, float lod) {
    return textureLod(sampler3D(gTextures3D[nonuniformEXT(volume)], gSamplers[nonuniformEXT(c.gridSampler)]), uvw, lod);
}

// The grid seen along `dir` at `lod` (in grid levels): level 0 is the grid, above it the three directional volumes
// facing the travel direction, weighted by |dir|: a thin surface facing axis a covers |dir_a| of what it covers
// seen straight along a (its projected area), which dir^2 weights would understate; where the weights add up to
// more than full coverage (solid blocks), the sample is scaled back to opacity 1. Between levels 0 and 1 a blend.
vec4 sampleVoxels(ConeTracePush c, vec3 uvw, vec3 dir, float lod) {
    vec3 w = abs(dir);
    float l = max(lod - 1.0, 0.0);
    vec4 directional = w.x * sampleVolume(c, c.directions[dir.x >= 0.0 ? 0 : 1], uvw, l) +
                       w.y * sampleVolume(c, c.directions[dir.y >= 0.0 ? 2 : 3], uvw, l) +
                       w.z * sampleVolume(c, c.directions[dir.z >= 0.0 ? 4 : 5], uvw, l);
    if (directional.a > 1.0) directional /= directional.a;
    if (lod >= 1.0) return directional;
    return mix(sampleVolume(c, c.grid, uvw, 0.0), directional, lod);
}

// Radiance arriving at `origin` from the cone (unit axis `dir`, tangent of its half-angle `tanHalf`).
vec3 traceCone(GpuFrame f, ConeTracePush c, vec3 origin, vec3 dir, float tanHalf) {
    const float gridWorld = c.voxelSize * float(c.gridSize);
    vec3 radiance = vec3(0.0);
    float opacity = 0.0;
    float dist = c.voxelSize;  // the first voxel around the origin is the surface's own
    while (opacity < 0.99) {
        float diameter = max(c.voxelSize, 2.0 * tanHalf * dist);
        // Trilinear filtering at level L blends cells of 2^L voxels with a tent two cells wide: the level whose
        // filter spans the sample's diameter is one below log2(diameter / voxel). (Taking log2 itself would filter
        // over twice the cone's width, and the cone would see the surface it starts from.)
        float lod = max(log2(diameter / c.voxelSize) - 1.0, 0.0);
        if (lod > c.maxLod) break;
        vec3 uvw = (origin + dir * dist - c.gridMin) / gridWorld;
        if (any(lessThan(uvw, vec3(0.0))) || any(greaterThan(uvw, vec3(1.0)))) break;
        vec4 s = sampleVoxels(c, uvw, dir, lod);
        float step = diameter * c.stepFactor;
        if (s.a > 0.0) {
            // The sample's coverage is that of a slab `diameter` thick; a step of `step` crosses step / diameter
            // of it. Premultiplied rgb scales with the opacity actually taken.
            float a = 1.0 - pow(max(1.0 - s.a, 0.0), step / diameter);
            radiance += (1.0 - opacity) * s.rgb * (a / s.a);
            opacity += (1.0 - opacity) * a;
        }
        dist += step;
    }
    // The sky through the cone: the environment mip whose texels span the cone's full angle.
    float texels = 2.0 * atan(tanHalf) * f.environmentWidth / 6.28318530717959;
    float skyLod = clamp(log2(max(texels, 1.0)), 0.0, f.environmentMaxLod);
    return radiance + (1.0 - opacity) * environmentRadiance(f, dir, skyLod);
}

#endif
