// cone_trace.glsl: marching one cone through the voxel grid's mip chain (the march, level choice and compositing
// are shared/vxgi_cone.h, which the CPU cone tracer compiles too; here only the fetches), the sky seen through
// what the cone leaves transparent, and the cone set of one receiver (diffuse irradiance, specular radiance), shared
// by the G-buffer pass (vxgi/cone_trace.comp) and the forward pass of transparent surfaces
// (transparency/forward_body.h). Ports IDKEngine's include/TraceCone.glsl without its GIBoost / GISkyBoxBoost.
#ifndef IDK_CONE_TRACE_GLSL
#define IDK_CONE_TRACE_GLSL
#include "bindless.glsl"
#include "environment.glsl"
#include "vxgi_types.h"
#include "vxgi_cone.h"

vec4 sampleVolume(VxgiConeParams c, uint volume, vec3 uvw, float lod) {
    return textureLod(sampler3D(gTextures3D[nonuniformEXT(volume)], gSamplers[nonuniformEXT(c.gridSampler)]), uvw, lod);
}

// The grid seen along `dir` at `lod` (grid levels: level L of the directional volumes): the directional volume
// facing the travel on each axis (0..5: +x -x +y -y +z -z), combined by vxgiCombine. Packed volumes (ladder
// "vxgi-volume-format" native) keep premultiplied rgb in a B10G11R11_UFLOAT volume and coverage in an R8_UNORM one,
// both filtered trilinearly; the fallback keeps both in one RGBA16F volume (opacity index == colour index). The
// indices are the same for the whole dispatch or draw.
// Packed, the three coverages are fetched first: where they combine to zero the march takes nothing from the
// sample whatever its rgb (vxgiMarchTake), so the colour fetches are skipped; in the air that most cones cross
// that keeps the fetches at three per sample, as with RGBA16F (lavapipe pays per fetch; a GPU diverges only
// where a warp's samples straddle a surface).
vec4 sampleVoxels(VxgiConeParams c, vec3 uvw, vec3 dir, float lod) {
    uint kx = vxgiDirectionIndex(dir, 0u), ky = vxgiDirectionIndex(dir, 1u), kz = vxgiDirectionIndex(dir, 2u);
    if (c.opacity[kx] == c.directions[kx])
        return vxgiCombine(dir, sampleVolume(c, c.directions[kx], uvw, lod),
                           sampleVolume(c, c.directions[ky], uvw, lod), sampleVolume(c, c.directions[kz], uvw, lod));
    vec3 a = vec3(sampleVolume(c, c.opacity[kx], uvw, lod).r, sampleVolume(c, c.opacity[ky], uvw, lod).r,
                  sampleVolume(c, c.opacity[kz], uvw, lod).r);
    if (dot(abs(dir), a) <= 0.0) return vec4(0.0);
    return vxgiCombine(dir, vec4(sampleVolume(c, c.directions[kx], uvw, lod).rgb, a.x),
                       vec4(sampleVolume(c, c.directions[ky], uvw, lod).rgb, a.y),
                       vec4(sampleVolume(c, c.directions[kz], uvw, lod).rgb, a.z));
}

// Radiance arriving at the receiver `origin` (geometric normal `plane`) through the cone (unit axis `dir`, tangent
// of its half-angle `tanHalf`).
vec3 traceCone(GpuFrame f, VxgiConeParams c, vec3 origin, vec3 plane, vec3 dir, float tanHalf) {
    VxgiMarch m = vxgiMarchBegin(origin, plane, dir, tanHalf, c.voxelSize);
    while (vxgiMarchNext(m, c.gridMin, c.voxelSize, c.gridSize, c.maxLod))
        vxgiMarchTake(m, sampleVoxels(c, m.uvw, dir, m.lod), c.stepFactor);
    // The sky through the cone: the environment mip whose texels span the cone's full angle.
    float texels = 2.0 * atan(tanHalf) * f.environmentWidth / 6.28318530717959;
    float skyLod = clamp(log2(max(texels, 1.0)), 0.0, f.environmentMaxLod);
    return m.radiance + (1.0 - m.opacity) * environmentRadiance(f, dir, skyLod);
}

// Whether `position` lies inside the grid (outside it the SH ambient stays).
bool insideVoxelGrid(VxgiConeParams c, vec3 position) {
    vec3 g = (position - c.gridMin) / (c.voxelSize * float(c.gridSize));
    return all(greaterThanEqual(g, vec3(0.0))) && all(lessThanEqual(g, vec3(1.0)));
}

// Irradiance E at `position` (geometric normal `plane`, shading normal `n`) from the cosine-weighted cone set: one
// cap cone along n (polar angles 0..30 degrees, 1/4 of the cosine-weighted hemisphere) and c.ringCones cones evenly
// in azimuth at 52.2 degrees (the cosine-weighted median of the 30..90 degree ring, which holds the other 3/4), each
// traced as c.footprintCones narrower cones across its footprint (vxgiDiffuseCone); returns E / pi = sum(w_i L_i),
// the cosine-weighted mean radiance.
vec3 traceMeanRadiance(GpuFrame f, VxgiConeParams c, vec3 position, vec3 plane, vec3 n) {
    vec3 t, b;
    vxgiTangents(n, t, b);
    vec3 e = vec3(0.0);
    uint count = vxgiDiffuseConeCount(c.ringCones, c.footprintCones);
    for (uint k = 0u; k < count; ++k) {
        vec3 dir;
        float tanHalf;
        float w = vxgiDiffuseCone(k, c.ringCones, c.footprintCones, n, t, b, dir, tanHalf);
        e += w * traceCone(f, c, position, plane, dir, tanHalf);
    }
    return e;
}

// Radiance along the reflection of `v` about n through the specular cone of `roughness` (its half-angle the GGX
// lobe's up to 0.5 rad), blended towards the diffuse set's E / pi (`meanRadiance`) for wider lobes
// (vxgiSpecularCone).
vec3 traceSpecular(GpuFrame f, VxgiConeParams c, vec3 position, vec3 plane, vec3 n, vec3 v, float roughness,
                   vec3 meanRadiance) {
    float specularTan;
    float toDiffuse = vxgiSpecularCone(roughness, specularTan);
    vec3 spec = toDiffuse < 1.0 ? traceCone(f, c, position, plane, reflect(-v, n), specularTan) : vec3(0.0);
    return mix(spec, meanRadiance, toDiffuse);
}

#endif
