#version 460
// upsample.comp.glsl: the half-resolution cone trace (vxgi/cone_trace.comp.glsl) to full resolution, edge-aware
// (joint bilateral on the G-buffer). Each pixel takes the half-resolution samples whose traced G-buffer pixel
// (include/vxgi_half_res.glsl) lies within one pixel on each axis, weighted by that distance (1, 1/2, 1/4), by
// how far the sample's surface point lies off this pixel's tangent plane (Gaussian, scale half a voxel: the cones
// gather light at voxel scale, so points closer than that receive nearly the same light; a foreground object in
// front of a wall is many voxels off its plane and gets weight ~0) and by the normals' agreement (cos^8: the
// cosine-weighted cone set turns with the normal). A pixel none of whose samples lies on its own surface (best depth +
// normal weight below kMatched: a feature thinner than the sample spacing, a silhouette the quincunx missed, or every
// sample outside the grid) gets diffuse alpha -1, and the fix-up pass (cone_trace.comp with unmatchedOnly) traces
// it at full resolution. Pixels outside the grid get alpha 0 (the SH ambient stays), as the full-resolution trace.
// IDKEngine's ConeTracer writes at render resolution (idkengine-internals.md 2.4): this pass is the port's own.
#extension GL_GOOGLE_include_directive : require
#include "scene_buffers.glsl"
#include "bindless.glsl"
#include "octahedral.glsl"
#include "vxgi_half_res.glsl"
#include "vxgi_types.h"

layout(local_size_x = kConeGroupSize, local_size_y = kConeGroupSize) in;
layout(push_constant, scalar) uniform Push { VxgiUpsamplePush p; };

// A sample on the pixel's own surface: off its plane by under ~1.5 half-voxels, normals within ~40 degrees.
const float kMatched = 0.1;

vec3 worldPosition(GpuFrame f, ivec2 pixel, float depth) {
    vec2 ndc = (vec2(pixel) + 0.5) / vec2(f.extent) * 2.0 - 1.0;
    vec4 h = f.inverseViewProjection * vec4(ndc, depth, 1.0);
    return h.xyz / h.w;
}

vec3 gbufferNormal(ivec2 pixel) { return octDecode(unpackSnorm2x16(imageLoad(gImagesR32ui[p.normal], pixel).r)); }

void main() {
    GpuFrame f = FrameBuffer(p.frame).frame;
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(uvec2(pixel), f.extent))) return;
    float depth = imageLoad(gImagesR32f[p.depth], pixel).r;
    vec3 position = worldPosition(f, pixel, depth);
    vec3 g = (position - p.gridMin) / (p.voxelSize * float(p.gridSize));
    if (depth >= 1.0 || any(lessThan(g, vec3(0.0))) || any(greaterThan(g, vec3(1.0)))) {
        imageStore(gImagesRgba16f[p.diffuse], pixel, vec4(0.0));
        imageStore(gImagesRgba16f[p.specular], pixel, vec4(0.0));
        return;
    }
    vec3 n = gbufferNormal(pixel);
    ivec2 halfSize = imageSize(gImagesRgba16f[p.halfDiffuse]);
    ivec2 block = pixel / 2;
    float invScale = 1.0 / (0.5 * p.voxelSize);
    vec3 diffuse = vec3(0.0), specular = vec3(0.0);
    float weight = 0.0, bestGeometry = -1.0;
    for (int y = -1; y <= 1; ++y) {
        for (int x = -1; x <= 1; ++x) {
            ivec2 h = block + ivec2(x, y);
            if (any(lessThan(h, ivec2(0))) || any(greaterThanEqual(h, halfSize))) continue;
            ivec2 s = vxgiHalfResSource(h, f.extent);
            ivec2 d = abs(s - pixel);
            if (d.x > 1 || d.y > 1) continue;
            vec4 traced = imageLoad(gImagesRgba16f[p.halfDiffuse], h);
            if (traced.a <= 0.0) continue;  // sky or outside the grid
            vec3 sp = worldPosition(f, s, imageLoad(gImagesR32f[p.depth], s).r);
            float off = dot(sp - position, n) * invScale;
            float geometry = exp(-off * off) * pow(max(dot(n, gbufferNormal(s)), 0.0), 8.0);
            float w = geometry * (d.x == 0 ? 1.0 : 0.5) * (d.y == 0 ? 1.0 : 0.5);
            diffuse += w * traced.rgb;
            specular += w * imageLoad(gImagesRgba16f[p.halfSpecular], h).rgb;
            weight += w;
            bestGeometry = max(bestGeometry, geometry);
        }
    }
    // No sample of this surface (or none inside the grid while this pixel is): leave it to the fix-up trace.
    if (bestGeometry < kMatched) {
        imageStore(gImagesRgba16f[p.diffuse], pixel, vec4(0.0, 0.0, 0.0, -1.0));
        return;
    }
    diffuse /= weight;
    specular /= weight;
    imageStore(gImagesRgba16f[p.diffuse], pixel, vec4(diffuse, 1.0));
    imageStore(gImagesRgba16f[p.specular], pixel, vec4(specular, 1.0));
}
