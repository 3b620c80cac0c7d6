// pt_lights.h: next-event estimation for the path tracers (C++ and GLSL, see pt_sampling.h): alias-table
// selection, sampling a GpuPtLight (punctual lights as the raster's include/pbr.glsl attenuates them, emissive
// triangles uniformly by area) and the solid-angle pdf MIS needs when a BSDF ray hits an emissive triangle, and the
// equirectangular environment (the raster's mapping, include/environment.glsl) sampled texel by texel.
// Tables live in buffers (GPU) or vectors (C++), so the functions take the entries the caller has fetched:
//   slot = ptAliasSlot(u1, count); entry = table[slot]; index = ptAliasResolve(entry, slot, u2);
// IDKEngine samples no light at all (reference 2.1); this whole file is new.
#ifndef IDK_PT_LIGHTS_H
#define IDK_PT_LIGHTS_H
#include "pt_common.h"

IDK_GPU_BEGIN

// ---------------------------------------------------------------------------------------------------- alias
IDK_INLINE uint ptAliasSlot(float u, uint count) { return min(uint(u * float(count)), count - 1u); }
IDK_INLINE uint ptAliasResolve(GpuPtAliasEntry entry, uint slot, float u) {
    return u < entry.threshold ? slot : entry.alias;
}

// ---------------------------------------------------------------------------------------------------- lights
struct PtLightSample {
    vec3 direction;  // unit, from the shading point toward the light
    float distance;  // to the sampled point (kPtFar for directional lights and the environment)
    vec3 radiance;   // punctual: intensity * attenuation (the estimate is f * radiance / pdf); triangle: the
                     // light's emissive factor (multiply by the emissive texture at (u, v) when kPtLightTextured)
    float pdf;       // given this light was chosen: solid angle (triangle, environment), 1 for punctual lights
    vec3 position;   // sampled point (triangles)
    float u;         // barycentric weight of vertex 1 (triangles)
    float v;         // barycentric weight of vertex 2
    bool isDelta;    // punctual: MIS does not apply
};

// Unit front normal and area of a triangle light (area 0 for a degenerate one).
IDK_INLINE vec3 ptTriangleLightNormal(GpuPtLight light, IDK_OUT(float) area) {
    vec3 c = cross(light.direction, light.edge2);
    float len = length(c);
    area = 0.5f * len;
    if (!(len > 0.0f) || !ptFinite(len)) {
        area = 0.0f;
        return vec3(0.0f, 0.0f, 1.0f);
    }
    return c * (((light.flags & kPtLightFlipped) != 0u ? -1.0f : 1.0f) / len);
}

// Samples `light` from shading point p with two uniforms. False when it cannot contribute (degenerate triangle,
// back of a single-sided emitter, outside a spot cone or range).
IDK_INLINE bool ptSampleLight(GpuPtLight light, vec3 p, vec2 u, IDK_OUT(PtLightSample) s) {
    s.direction = vec3(0.0f, 0.0f, 1.0f);
    s.distance = 0.0f;
    s.radiance = vec3(0.0f);
    s.pdf = 0.0f;
    s.position = p;
    s.u = 0.0f;
    s.v = 0.0f;
    s.isDelta = light.type != kPtLightTriangle;
    if (light.type == kPtLightDirectional) {
        s.direction = -light.direction;
        s.distance = kPtFar;
        s.radiance = light.intensity;
        s.pdf = 1.0f;
        return ptFinite3(s.direction) && dot(s.direction, s.direction) > 0.5f;
    }
    if (light.type == kPtLightPoint || light.type == kPtLightSpot) {
        vec3 toLight = light.position - p;
        float d2 = dot(toLight, toLight);
        if (!(d2 > 1.0e-12f) || !ptFinite(d2)) return false;
        s.distance = sqrt(d2);
        s.direction = toLight / s.distance;
        s.position = light.position;
        float attenuation = 1.0f / d2;
        if (light.range > 0.0f) {  // KHR_lights_punctual's recommended window, as in include/pbr.glsl
            float r = d2 / (light.range * light.range);
            float w = clamp(1.0f - r * r, 0.0f, 1.0f);
            attenuation *= w * w;
        }
        if (light.type == kPtLightSpot) {
            float a = clamp(dot(light.direction, -s.direction) * light.spotScale + light.spotOffset, 0.0f, 1.0f);
            attenuation *= a * a;
        }
        s.radiance = light.intensity * attenuation;
        s.pdf = 1.0f;
        return attenuation > 0.0f;
    }
    // Triangle: uniform by area (square-root parametrisation).
    float area;
    vec3 normal = ptTriangleLightNormal(light, area);
    if (!(area > 0.0f)) return false;
    float su = sqrt(u.x);
    s.u = 1.0f - su;
    s.v = u.y * su;
    s.position = light.position + light.direction * s.u + light.edge2 * s.v;
    vec3 d = s.position - p;
    float dist2 = dot(d, d);
    if (!(dist2 > 1.0e-20f) || !ptFinite(dist2)) return false;
    s.distance = sqrt(dist2);
    s.direction = d / s.distance;
    float cosLight = -dot(s.direction, normal);  // > 0: p sees the front face
    if (cosLight < 0.0f && (light.flags & kPtLightDoubleSided) != 0u) cosLight = -cosLight;
    if (!(cosLight > 1.0e-7f)) return false;
    s.radiance = light.intensity;
    s.pdf = dist2 / (area * cosLight);
    return ptFinite(s.pdf);
}

// Solid-angle pdf (given the light was chosen) with which ptSampleLight picks `hitPoint` on a triangle light, seen
// from p; 0 for punctual lights (a BSDF ray never hits them) and degenerate triangles.
IDK_INLINE float ptLightPdf(GpuPtLight light, vec3 p, vec3 hitPoint) {
    if (light.type != kPtLightTriangle) return 0.0f;
    float area;
    vec3 normal = ptTriangleLightNormal(light, area);
    if (!(area > 0.0f)) return 0.0f;
    vec3 d = hitPoint - p;
    float dist2 = dot(d, d);
    if (!(dist2 > 0.0f)) return 0.0f;
    float cosLight = abs(dot(d, normal)) * inversesqrt(dist2);
    if (!(cosLight > 1.0e-7f)) return 0.0f;
    float pdf = dist2 / (area * cosLight);
    return ptFinite(pdf) ? pdf : 0.0f;
}

// ---------------------------------------------------------------------------------------------------- environment
// u = 0.5 looks down -Z, v = 0 is straight up (+Y): dir = (sin t sin p, cos t, -sin t cos p), p = 2 pi (u - 0.5),
// t = pi v (include/environment.glsl, render/environment.cpp).
IDK_INLINE vec2 ptEquirectUv(vec3 dir) {
    float phi = atan(dir.x, -dir.z);
    float theta = acos(clamp(dir.y, -1.0f, 1.0f));
    return vec2(phi * (0.5f / kPtPi) + 0.5f, theta * (1.0f / kPtPi));
}

IDK_INLINE vec3 ptEquirectDirection(vec2 uv) {
    float phi = 2.0f * kPtPi * (uv.x - 0.5f);
    float theta = kPtPi * uv.y;
    float st = sin(theta);
    return vec3(st * sin(phi), cos(theta), -st * cos(phi));
}

// The texel (row-major, row 0 = up) a direction falls in: its radiance is what the environment returns there.
IDK_INLINE uint ptEnvironmentTexel(vec3 dir, uint width, uint height) {
    vec2 uv = ptEquirectUv(dir);
    float u = uv.x >= 0.0f ? min(uv.x, 1.0f) : 0.0f;  // also maps NaN to 0 (float -> uint of NaN is undefined)
    float v = uv.y >= 0.0f ? min(uv.y, 1.0f) : 0.0f;
    uint x = min(uint(u * float(width)), width - 1u);
    uint y = min(uint(v * float(height)), height - 1u);
    return y * width + x;
}

// Solid-angle pdf of sampling `dir` (given the environment was chosen), where texelProbability is the alias-table
// probability of ptEnvironmentTexel(dir): uniform in the texel's (u, v) rectangle, d(omega) = 2 pi^2 sin(t) du dv.
IDK_INLINE float ptEnvironmentPdf(float texelProbability, vec3 dir, uint width, uint height) {
    float sinTheta = sqrt(dir.x * dir.x + dir.z * dir.z);  // not sqrt(1 - y^2): that cancels near the poles
    if (!(sinTheta > 1.0e-7f)) return 0.0f;
    return texelProbability * float(width) * float(height) / (2.0f * kPtPi * kPtPi * sinTheta);
}

// A direction uniform in the (u, v) rectangle of `texel` (chosen by the alias table with texelProbability);
// returns its solid-angle pdf (0 at the poles, where the sample must be dropped).
IDK_INLINE float ptSampleEnvironment(uint texel, float texelProbability, uint width, uint height, vec2 u,
                                     IDK_OUT(vec3) dir) {
    uint x = texel % width;
    uint y = texel / width;
    vec2 uv = vec2((float(x) + u.x) / float(width), (float(y) + u.y) / float(height));
    dir = ptEquirectDirection(uv);
    float sinTheta = sin(kPtPi * uv.y);
    if (!(sinTheta > 1.0e-7f)) return 0.0f;
    return texelProbability * float(width) * float(height) / (2.0f * kPtPi * kPtPi * sinTheta);
}

IDK_GPU_END

#endif
