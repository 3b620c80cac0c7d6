#version 460
// ssao.comp.glsl: screen-space ambient occlusion: the fraction of cosine-distributed rays of length `radius` from
// each G-buffer surface that the depth buffer shows blocked. Each ray is tested at kSsaoSteps points; a point is
// blocked when the depth buffer's surface at its pixel lies in front of it by less than `radius` (a thickness
// test: a much nearer surface is taken to be a foreground object the ray passes behind). Rays leaving the screen
// count as unblocked. Estimates the quantity the CPU reference computes with rays through the BVH (tests). Ports
// IDKEngine's SSAO/compute.glsl (reference 2.16: 10 cosine samples, one depth test each, no range check, x1.3)
// with a ray march and a range check; the result scales ambient light only.
#extension GL_GOOGLE_include_directive : require
#include "scene_buffers.glsl"
#include "bindless.glsl"
#include "octahedral.glsl"
#include "ssao_types.h"

layout(local_size_x = kSsaoGroupSize, local_size_y = kSsaoGroupSize) in;
layout(push_constant, scalar) uniform Push { SsaoPush p; };

// Interleaved gradient noise (Jimenez 2014), as IDKEngine varies it with the TAA frame.
float ign(vec2 q) { return fract(52.9829189 * fract(dot(q, vec2(0.06711056, 0.00583715)))); }

vec3 worldAt(GpuFrame f, vec2 ndc, float depth) {
    vec4 h = f.inverseViewProjection * vec4(ndc, depth, 1.0);
    return h.xyz / h.w;
}

void main() {
    GpuFrame f = FrameBuffer(p.frame).frame;
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = ivec2(f.extent);
    if (any(greaterThanEqual(pixel, size))) return;
    float depth = imageLoad(gImagesR32f[p.depth], pixel).r;
    if (depth >= 1.0) {
        imageStore(gImagesR32f[p.target], pixel, vec4(1.0));
        return;
    }
    vec3 position = worldAt(f, (vec2(pixel) + 0.5) / vec2(size) * 2.0 - 1.0, depth);
    vec3 n = octDecode(unpackSnorm2x16(imageLoad(gImagesR32ui[p.normal], pixel).r));
    vec3 t = normalize(abs(n.x) > 0.5 ? cross(n, vec3(0.0, 1.0, 0.0)) : cross(n, vec3(1.0, 0.0, 0.0)));
    vec3 b = cross(n, t);
    float eye = distance(position, f.cameraPosition);

    vec2 q = vec2(pixel) + 5.588238 * float(p.frameIndex % 64u);
    float n0 = ign(q), n1 = ign(q + vec2(17.0, 31.0)), n2 = ign(q + vec2(59.0, 7.0));
    uint blocked = 0u;
    for (uint s = 0u; s < p.samples; ++s) {
        // Stratified in the first coordinate, a golden-ratio sequence in the second, rotated by the noise.
        float u1 = fract((float(s) + n0) / float(p.samples));
        float u2 = fract(float(s) * 0.61803399 + n1);
        float r = sqrt(u1), phi = 6.28318531 * u2;
        vec3 dir = normalize(t * (r * cos(phi)) + b * (r * sin(phi)) + n * sqrt(max(1.0 - u1, 0.0)));
        for (uint k = 0u; k < kSsaoSteps; ++k) {
            vec3 sp = position + dir * (p.radius * (float(k) + n2) / float(kSsaoSteps));
            vec4 clip = f.viewProjection * vec4(sp, 1.0);
            if (clip.w <= 0.0) break;
            vec2 ndc = clip.xy / clip.w;
            if (any(greaterThanEqual(abs(ndc), vec2(1.0)))) break;  // off screen: unknown, counted unblocked
            ivec2 sq = clamp(ivec2((ndc * 0.5 + 0.5) * vec2(size)), ivec2(0), size - 1);
            float sceneDepth = imageLoad(gImagesR32f[p.depth], sq).r;
            if (sceneDepth >= 1.0) continue;
            vec3 surface = worldAt(f, (vec2(sq) + 0.5) / vec2(size) * 2.0 - 1.0, sceneDepth);
            float inFront = distance(sp, f.cameraPosition) - distance(surface, f.cameraPosition);
            // In front by more than a sliver (the surface's own depth varies across a pixel) and less than the
            // ray length (thickness).
            if (inFront > 0.002 * eye + 0.05 * p.radius && inFront < p.radius) {
                ++blocked;
                break;
            }
        }
    }
    imageStore(gImagesR32f[p.target], pixel, vec4(1.0 - float(blocked) / float(p.samples)));
}
