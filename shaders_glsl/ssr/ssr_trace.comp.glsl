#version 460
// ssr_trace.comp.glsl: screen-space reflections. Each smooth enough G-buffer pixel marches its mirror ray through
// the closest-depth Hi-Z pyramid (ssr/hiz_min.comp) in screen space, where x, y (pixels) and the projected depth
// are all linear along the ray. A cell whose nearest depth lies behind the ray for the whole of the ray's way
// through it is skipped at once and the march climbs a level; otherwise it descends, down to single pixels. At a
// pixel the ray is a hit when it lies behind the surface by at most `thickness` (world units, along the view ray)
// and the surface faces it; a ray passing farther behind a surface goes on (it passes behind an object). Hits
// return last frame's lit image at the hit point reprojected with last frame's matrix (the current lit image does
// not exist yet: this runs before deferred lighting, which applies the result as its specular ambient term).
// Misses (leaving the screen, reaching the far plane, running out of steps) return weight 0: the lighting keeps
// the environment (or VXGI) specular there. Ports IDKEngine's SSR/compute.glsl (reference 2.16: a 30-step linear
// view-space march with binary refinement, no thickness test, current pre-TAA image) as a Hi-Z march.
// On a real GPU rays of one 8x8 tile diverge in step count; a tile-level early-out for rough or sky tiles would
// pay there, lavapipe runs lanes mostly independently.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_buffer_reference : require
#include "scene_buffers.glsl"
#include "bindless.glsl"
#include "octahedral.glsl"
#include "depth_pyramid.h"
#include "ssr_types.h"

layout(local_size_x = kSsrGroupSize, local_size_y = kSsrGroupSize) in;
layout(push_constant, scalar) uniform Push { SsrPush p; };
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer Pyramid { float data[]; };

uvec2 gSize;
uint gLevels;                  // pyramid levels; march level L > 0 reads pyramid level L - 1 (cells of 2^L pixels)
uint gOffsets[kHizMaxLevels];

float cellMinDepth(uint level, vec2 cell) {
    if (level == 0u) return imageLoad(gImagesR32f[p.depth], ivec2(min(uvec2(cell), gSize - 1u))).r;
    uvec2 s = hizLevelSize(gSize, level - 1u);
    uvec2 c = min(uvec2(cell), s - 1u);
    return Pyramid(p.pyramid).data[gOffsets[level - 1u] + c.y * s.x + c.x];
}

vec3 unproject(GpuFrame f, vec2 pixel, float depth) {
    vec4 h = f.inverseViewProjection * vec4(pixel / vec2(gSize) * 2.0 - 1.0, depth, 1.0);
    return h.xyz / h.w;
}

// The hit's radiance and weight; vec4(0) for a miss.
vec4 trace(GpuFrame f, ivec2 pixel, float depth, vec3 n) {
    vec3 position = unproject(f, vec2(pixel) + 0.5, depth);
    vec3 eye = unproject(f, vec2(pixel) + 0.5, 0.0);
    vec3 v = normalize(eye - position);
    vec3 r = reflect(-v, n);
    if (dot(r, n) <= 0.0) return vec4(0.0);

    // The ray from its start to far away, clipped in homogeneous space to the near plane (z >= 0) and the far plane
    // (z <= w), then projected to pixels + depth.
    vec4 c0 = f.viewProjection * vec4(position, 1.0);
    vec4 c1 = f.viewProjection * vec4(position + r * (1e3 * max(distance(eye, position), 1.0)), 1.0);
    if (c1.z < 0.0) c1 = mix(c0, c1, c0.z / (c0.z - c1.z) * 0.9999);
    if (c1.z > c1.w) c1 = mix(c0, c1, (c0.w - c0.z) / ((c0.w - c0.z) - (c1.w - c1.z)));
    vec3 s0 = vec3((c0.xy / c0.w * 0.5 + 0.5) * vec2(gSize), c0.z / c0.w);
    vec3 s1 = vec3((c1.xy / c1.w * 0.5 + 0.5) * vec2(gSize), c1.z / c1.w);
    vec3 d = s1 - s0;
    float span = max(abs(d.x), abs(d.y));
    if (span < 1.0) return vec4(0.0);  // (almost) straight at the camera or away along the view ray: unknown

    // Where the ray leaves the screen.
    float tMax = 1.0;
    if (d.x > 0.0) tMax = min(tMax, (float(gSize.x) - s0.x) / d.x);
    if (d.x < 0.0) tMax = min(tMax, -s0.x / d.x);
    if (d.y > 0.0) tMax = min(tMax, (float(gSize.y) - s0.y) / d.y);
    if (d.y < 0.0) tMax = min(tMax, -s0.y / d.y);
    float eps = 0.01 / span;   // a hundredth of a pixel: steps across a cell border
    float t = 1.0 / span;      // one pixel away from the start: the surface itself is behind the ray there

    uint level = 0u;
    for (uint i = 0u; i < p.maxSteps && t < tMax; ++i) {
        vec3 at = s0 + d * t;
        float cellSize = float(1u << level);
        vec2 cell = floor(at.xy / cellSize);
        float nearest = cellMinDepth(level, cell);
        // t where the ray leaves the cell, and where it reaches the cell's nearest depth (when going deeper).
        vec2 border = (cell + step(vec2(0.0), d.xy)) * cellSize;
        vec2 tBorder = vec2(d.x != 0.0 ? (border.x - s0.x) / d.x : 1e30, d.y != 0.0 ? (border.y - s0.y) / d.y : 1e30);
        float tExit = min(tBorder.x, tBorder.y);
        float tDepth = d.z > 0.0 ? (nearest - s0.z) / d.z : 1e30;
        bool candidate = false;
        if (at.z < nearest) {
            if (tDepth >= tExit) {  // in front of everything in the cell all the way through it
                t = tExit + eps;
                level = min(level + 1u, gLevels);
                continue;
            }
            t = max(t, tDepth);
            if (level > 0u) {
                --level;
                continue;
            }
            candidate = true;
        } else if (level > 0u) {  // behind the cell's nearest surface: look closer
            --level;
            continue;
        } else {
            candidate = true;
        }
        // Level 0: the ray is at or behind this pixel's surface. Thickness (distance along the view ray) and facing.
        if (candidate && nearest < 1.0) {
            vec2 centre = cell + 0.5;
            vec3 surface = unproject(f, centre, nearest);
            float behind = distance(eye, unproject(f, centre, min(s0.z + d.z * t, 1.0))) - distance(eye, surface);
            ivec2 hitPixel = ivec2(min(uvec2(cell), gSize - 1u));
            vec3 hitNormal = octDecode(unpackSnorm2x16(imageLoad(gImagesR32ui[p.normal], hitPixel).r));
            if (behind <= p.thickness && dot(hitNormal, r) < 0.0) {
                vec4 prev = p.previousViewProjection * vec4(surface, 1.0);
                if (prev.w <= 0.0) return vec4(0.0);
                vec2 uv = prev.xy / prev.w * 0.5 + 0.5;
                if (any(lessThan(uv, vec2(0.0))) || any(greaterThanEqual(uv, vec2(1.0)))) return vec4(0.0);
                vec3 radiance = imageLoad(gImagesRgba16f[p.history], ivec2(uv * vec2(gSize))).rgb;
                // Fade out near the screen's borders, where a slightly different ray would have left the screen.
                vec2 hitUv = centre / vec2(gSize);
                vec2 edge = min(hitUv, 1.0 - hitUv) / kSsrEdgeFade;
                return vec4(radiance, clamp(min(edge.x, edge.y), 0.0, 1.0));
            }
        }
        t = tExit + eps;  // passes behind this pixel's surface
    }
    return vec4(0.0);
}

void main() {
    GpuFrame f = FrameBuffer(p.frame).frame;
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    gSize = f.extent;
    if (any(greaterThanEqual(uvec2(pixel), gSize))) return;
    vec4 result = vec4(0.0);
    float depth = imageLoad(gImagesR32f[p.depth], pixel).r;
    vec4 mro = imageLoad(gImagesRgba8[p.material], pixel);
    if (p.historyValid != 0u && depth < 1.0 && mro.a >= 0.5 && mro.g < kSsrMaxRoughness) {
        gLevels = hizLevelCount(gSize);
        uint offset = 0u;
        for (uint k = 0u; k < gLevels; ++k) {
            gOffsets[k] = offset;
            uvec2 s = hizLevelSize(gSize, k);
            offset += s.x * s.y;
        }
        vec3 n = octDecode(unpackSnorm2x16(imageLoad(gImagesR32ui[p.normal], pixel).r));
        result = trace(f, pixel, depth, n);
        result.a *= clamp((kSsrMaxRoughness - mro.g) / (kSsrMaxRoughness - kSsrRoughnessFade), 0.0, 1.0);
    }
    imageStore(gImagesRgba16f[p.target], pixel, result);
}
