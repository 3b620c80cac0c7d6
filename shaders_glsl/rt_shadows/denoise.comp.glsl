#version 460
// denoise.comp.glsl: edge-aware spatial filter of the soft ray-traced shadow mask (rt_shadows/mask_body.h with a
// light radius): per pixel and light, the Gaussian-weighted mean (5x5) of the neighbours' visibility
// that lie on the pixel's surface: weights fall with the neighbour's distance from the pixel's tangent plane
// (relative to the camera distance) and with the angle between the normals, so shadows do not bleed across depth
// or orientation edges. The Gaussian's sigma is 1.5 px at 8 rays and shrinks as 1 / sqrt(rays) (the estimate's
// standard deviation), so many rays are blurred little (the filter's bias: penumbrae widen by about sigma). Sky pixels keep 1. One pass, no history: a real GPU would add temporal accumulation with
// motion vectors on top and trace fewer rays; this keeps stills deterministic.
#extension GL_GOOGLE_include_directive : require
#include "scene_buffers.glsl"
#include "bindless.glsl"
#include "octahedral.glsl"
#include "rt_shadow_types.h"

layout(local_size_x = kRtShadowGroupSize, local_size_y = kRtShadowGroupSize) in;
layout(push_constant, scalar) uniform Push { RtShadowDenoisePush p; };
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer RtNoisyRef { float v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) writeonly buffer RtFilteredRef { float v[]; };

vec3 positionAt(GpuFrame f, ivec2 pixel, float depth) {
    vec2 ndc = (vec2(pixel) + 0.5) / vec2(f.extent) * 2.0 - 1.0;
    vec4 h = f.inverseViewProjection * vec4(ndc, depth, 1.0);
    return h.xyz / h.w;
}

void main() {
    GpuFrame f = FrameBuffer(p.frame).frame;
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    uint slot = gl_GlobalInvocationID.z;
    if (any(greaterThanEqual(uvec2(pixel), f.extent)) || slot >= p.slots) return;
    uint base = slot * f.extent.y * f.extent.x;
    uint index = base + uint(pixel.y) * f.extent.x + uint(pixel.x);
    float depth = imageLoad(gImagesR32f[p.depth], pixel).r;
    if (depth >= 1.0) {
        RtFilteredRef(p.filtered).v[index] = RtNoisyRef(p.noisy).v[index];
        return;
    }
    vec3 position = positionAt(f, pixel, depth);
    vec3 n = octDecode(unpackSnorm2x16(imageLoad(gImagesR32ui[p.normal], pixel).r));
    float planeScale = 1.0 / (0.01 * max(distance(position, f.cameraPosition), 1e-3));  // 1 % of the distance
    float sigma = clamp(1.5 * sqrt(8.0 / float(max(p.rays, 1u))), 0.25, 2.0);
    float sum = 0.0, weights = 0.0;
    for (int dy = -2; dy <= 2; ++dy) {
        for (int dx = -2; dx <= 2; ++dx) {
            ivec2 q = pixel + ivec2(dx, dy);
            if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(uvec2(q), f.extent))) continue;
            float dq = imageLoad(gImagesR32f[p.depth], q).r;
            if (dq >= 1.0) continue;
            vec3 nq = octDecode(unpackSnorm2x16(imageLoad(gImagesR32ui[p.normal], q).r));
            float plane = abs(dot(n, positionAt(f, q, dq) - position)) * planeScale;
            float w = exp(-float(dx * dx + dy * dy) / (2.0 * sigma * sigma)) * exp(-plane * plane) *
                      pow(max(dot(n, nq), 0.0), 32.0);
            sum += w * RtNoisyRef(p.noisy).v[base + uint(q.y) * f.extent.x + uint(q.x)];
            weights += w;
        }
    }
    RtFilteredRef(p.filtered).v[index] = sum / max(weights, 1e-6);  // the centre's weight is 1: never 0
}
