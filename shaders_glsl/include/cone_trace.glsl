// cone_trace.glsl: marching one cone through the voxel grid's mip chain with front-to-back compositing, and the
// sky seen through what the cone leaves transparent. Ports IDKEngine's include/TraceCone.glsl without its
// GIBoost / GISkyBoxBoost factors; the step's opacity is corrected for the step length (Beer-Lambert over the
// sample's width) so the result does not depend on the step factor beyond sampling error.
#ifndef IDK_CONE_TRACE_GLSL
#define IDK_CONE_TRACE_GLSL
#include "bindless.glsl"
#include "environment.glsl"
#include "vxgi_types.h"

// Radiance arriving at `origin` from the cone (unit axis `dir`, tangent of its half-angle `tanHalf`).
vec3 traceCone(GpuFrame f, ConeTracePush c, vec3 origin, vec3 dir, float tanHalf) {
    const float gridWorld = c.voxelSize * float(c.gridSize);
    vec3 radiance = vec3(0.0);
    float opacity = 0.0;
    float dist = c.voxelSize;  // the first voxel around the origin is the surface's own
    while (opacity < 0.99) {
        float diameter = max(c.voxelSize, 2.0 * tanHalf * dist);
        float lod = log2(diameter / c.voxelSize);
        if (lod > c.maxLod) break;
        vec3 uvw = (origin + dir * dist - c.gridMin) / gridWorld;
        if (any(lessThan(uvw, vec3(0.0))) || any(greaterThan(uvw, vec3(1.0)))) break;
        vec4 s = textureLod(sampler3D(gTextures3D[nonuniformEXT(c.grid)], gSamplers[nonuniformEXT(c.gridSampler)]),
                            uvw, lod);
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
