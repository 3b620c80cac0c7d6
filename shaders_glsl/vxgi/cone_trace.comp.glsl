#version 460
// cone_trace.comp.glsl: voxel cone tracing per G-buffer pixel inside the grid. Diffuse: a cosine-weighted cone
// set: one cap cone along the normal (polar angles 0..30 degrees, 1/4 of the cosine-weighted hemisphere) and
// `ringCones` cones evenly in azimuth at 52.2 degrees (the cosine-weighted median of the 30..90 degree ring, which
// holds the other 3/4); irradiance E = pi * sum(weight_i * L_i). Specular: one cone along the reflection, its
// half-angle the GGX lobe's (2 atan(0.64 alpha), as environmentLod). Ports IDKEngine's ConeTraceGI compute
// shader, deterministic (no per-frame random cone, no TAA needed) and without its boost factors.
#extension GL_GOOGLE_include_directive : require
#include "scene_buffers.glsl"
#include "bindless.glsl"
#include "octahedral.glsl"
#include "cone_trace.glsl"

layout(local_size_x = kConeGroupSize, local_size_y = kConeGroupSize) in;
layout(push_constant, scalar) uniform Push { ConeTracePush p; };

const float kTwoPi = 6.28318530717959;

void main() {
    GpuFrame f = FrameBuffer(p.frame).frame;
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(uvec2(pixel), f.extent))) return;
    float depth = imageLoad(gImagesR32f[p.depth], pixel).r;
    vec2 ndc = (vec2(pixel) + 0.5) / vec2(f.extent) * 2.0 - 1.0;
    vec4 h = f.inverseViewProjection * vec4(ndc, depth, 1.0);
    vec4 hNear = f.inverseViewProjection * vec4(ndc, 0.0, 1.0);
    vec3 position = h.xyz / h.w;
    vec3 g = (position - p.gridMin) / (p.voxelSize * float(p.gridSize));
    if (depth >= 1.0 || any(lessThan(g, vec3(0.0))) || any(greaterThan(g, vec3(1.0)))) {
        imageStore(gImagesRgba16f[p.diffuse], pixel, vec4(0.0));  // alpha 0: outside, keep the SH ambient
        imageStore(gImagesRgba16f[p.specular], pixel, vec4(0.0));
        return;
    }
    vec3 v = normalize(hNear.xyz / hNear.w - position);
    vec3 n = octDecode(unpackSnorm2x16(imageLoad(gImagesR32ui[p.normal], pixel).r));
    float roughness = imageLoad(gImagesRgba8[p.material], pixel).g;
    vec3 origin = position + n * p.voxelSize;  // off the surface's own voxel

    vec3 t = normalize(abs(n.y) < 0.9 ? cross(n, vec3(0.0, 1.0, 0.0)) : cross(n, vec3(1.0, 0.0, 0.0)));
    vec3 b = cross(n, t);
    const float kCapTan = 0.57735027;                      // tan 30 degrees
    const float kRingSin = 0.79056942, kRingCos = 0.61237244;  // sin^2 = 0.625: the ring's cosine-weighted median
    vec3 e = 0.25 * traceCone(f, p, origin, n, kCapTan);
    // Each ring cone spans its azimuth sector: half-angle ~ half the sector's width at the ring's angle.
    float ringTan = min(tan(0.5 * kTwoPi * kRingSin / float(p.ringCones)), kCapTan);
    for (uint i = 0; i < p.ringCones; ++i) {
        float phi = kTwoPi * (float(i) + 0.5) / float(p.ringCones);
        vec3 d = kRingSin * (cos(phi) * t + sin(phi) * b) + kRingCos * n;
        e += (0.75 / float(p.ringCones)) * traceCone(f, p, origin, d, ringTan);
    }
    imageStore(gImagesRgba16f[p.diffuse], pixel, vec4(e * 3.14159265358979, 1.0));

    float alpha = max(roughness * roughness, 1e-3);
    vec3 r = reflect(-v, n);
    vec3 spec = traceCone(f, p, origin, r, tan(min(2.0 * atan(0.64 * alpha), 1.2)));
    imageStore(gImagesRgba16f[p.specular], pixel, vec4(spec, 1.0));
}
