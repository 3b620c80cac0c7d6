#version 460
// cone_trace.comp.glsl: voxel cone tracing per G-buffer pixel inside the grid (cone set and march:
// shared/vxgi_cone.h). Diffuse: a cosine-weighted cone set: one cap cone along the normal (polar angles 0..30
// degrees, 1/4 of the cosine-weighted hemisphere) and `ringCones` cones evenly in azimuth at 52.2 degrees (the
// cosine-weighted median of the 30..90 degree ring, which holds the other 3/4), each traced as `footprintCones`
// narrower cones tiling it (vxgiDiffuseCone); irradiance E = pi * sum(w_i L_i).
// Specular: one cone along the reflection, its half-angle the GGX lobe's up to 0.5 rad, blended towards E / pi for
// wider lobes. The cones start from the surface point and clamp their level by the height above the surface's
// geometric plane (from the depth buffer: the shading normal may tilt off it). Ports IDKEngine's ConeTraceGI
// compute shader, deterministic (no per-frame random cone, no TAA needed) and without its boost factors.
// Resolution: the outputs' size says it. Outputs smaller than the frame: half resolution, each output pixel traces
// one G-buffer pixel of its 2x2 block (include/vxgi_half_res.glsl) and vxgi/upsample.comp.glsl fills the frame;
// then this shader runs again at render resolution with unmatchedOnly and traces only the pixels the upsample marked
// (diffuse alpha -1). (On a real GPU those few pixels diverge from their idle neighbours within a wave; compacting
// them into a list first would keep waves full. On lavapipe the early return costs nothing.)
#extension GL_GOOGLE_include_directive : require
#include "scene_buffers.glsl"
#include "bindless.glsl"
#include "octahedral.glsl"
#include "cone_trace.glsl"
#include "vxgi_half_res.glsl"

layout(local_size_x = kConeGroupSize, local_size_y = kConeGroupSize) in;
layout(push_constant, scalar) uniform Push { ConeTracePush p; };

VxgiConeParams coneParams(ConeTracePush q) {
    VxgiConeParams c;
    c.gridMin = q.gridMin;
    c.voxelSize = q.voxelSize;
    c.gridSize = q.gridSize;
    c.maxLod = q.maxLod;
    c.stepFactor = q.stepFactor;
    c.ringCones = q.ringCones;
    c.directions = q.directions;
    c.opacity = q.opacity;
    c.gridSampler = q.gridSampler;
    c.footprintCones = q.footprintCones;
    return c;
}

vec3 worldPosition(GpuFrame f, ivec2 pixel, float depth) {
    vec2 ndc = (vec2(pixel) + 0.5) / vec2(f.extent) * 2.0 - 1.0;
    vec4 h = f.inverseViewProjection * vec4(ndc, depth, 1.0);
    return h.xyz / h.w;
}

// The neighbour's position difference along one image axis, from the side whose depth continues the surface best
// (the smaller step); false when neither neighbour has geometry.
bool neighbourDelta(GpuFrame f, ivec2 pixel, ivec2 axis, vec3 position, out vec3 delta) {
    float best = 1e30;
    for (int s = -1; s <= 1; s += 2) {
        ivec2 q = pixel + s * axis;
        if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(uvec2(q), f.extent))) continue;
        float d = imageLoad(gImagesR32f[p.depth], q).r;
        if (d >= 1.0) continue;
        vec3 e = float(s) * (worldPosition(f, q, d) - position);
        if (dot(e, e) < best) {
            best = dot(e, e);
            delta = e;
        }
    }
    return best < 1e30;
}

void main() {
    GpuFrame f = FrameBuffer(p.frame).frame;
    ivec2 dst = ivec2(gl_GlobalInvocationID.xy);
    ivec2 outSize = imageSize(gImagesRgba16f[p.diffuse]);
    if (any(greaterThanEqual(dst, outSize))) return;
    if (p.unmatchedOnly != 0u && imageLoad(gImagesRgba16f[p.diffuse], dst).a >= 0.0) return;
    ivec2 pixel = outSize == ivec2(f.extent) ? dst : vxgiHalfResSource(dst, f.extent);
    float depth = imageLoad(gImagesR32f[p.depth], pixel).r;
    vec3 position = worldPosition(f, pixel, depth);
    vec2 ndc = (vec2(pixel) + 0.5) / vec2(f.extent) * 2.0 - 1.0;
    vec4 hNear = f.inverseViewProjection * vec4(ndc, 0.0, 1.0);
    vec3 g = (position - p.gridMin) / (p.voxelSize * float(p.gridSize));
    if (depth >= 1.0 || any(lessThan(g, vec3(0.0))) || any(greaterThan(g, vec3(1.0)))) {
        imageStore(gImagesRgba16f[p.diffuse], dst, vec4(0.0));  // alpha 0: outside, keep the SH ambient
        imageStore(gImagesRgba16f[p.specular], dst, vec4(0.0));
        return;
    }
    vec3 v = normalize(hNear.xyz / hNear.w - position);
    vec3 n = octDecode(unpackSnorm2x16(imageLoad(gImagesR32ui[p.normal], pixel).r));
    float roughness = imageLoad(gImagesRgba8[p.material], pixel).g;

    // Geometric normal: across the depth buffer's neighbours, on the shading normal's side.
    vec3 plane = n, dx, dy;
    if (neighbourDelta(f, pixel, ivec2(1, 0), position, dx) && neighbourDelta(f, pixel, ivec2(0, 1), position, dy)) {
        vec3 c = cross(dx, dy);
        if (dot(c, c) > 0.0) plane = normalize(c) * (dot(c, n) < 0.0 ? -1.0 : 1.0);
    }

    VxgiConeParams c = coneParams(p);
    vec3 e = traceMeanRadiance(f, c, position, plane, n);
    imageStore(gImagesRgba16f[p.diffuse], dst, vec4(e * 3.14159265358979, 1.0));
    imageStore(gImagesRgba16f[p.specular], dst, vec4(traceSpecular(f, c, position, plane, n, v, roughness, e), 1.0));
}
