// temporal_common.glsl: helpers of the temporal passes: the per-frame camera matrices (GpuTemporalFrame), YCoCg,
// Catmull-Rom weights, variance clipping, per-pixel motion (background pixels reprojected from the camera) and
// the disocclusion test against last frame's depth and motion. Used by taa_resolve.comp and upscale.comp.
#ifndef IDK_TEMPORAL_COMMON_GLSL
#define IDK_TEMPORAL_COMMON_GLSL

layout(buffer_reference, scalar, buffer_reference_align = 8) readonly buffer TemporalBuffer { GpuTemporalFrame t; };

vec3 rgbToYCoCg(vec3 c) {
    return vec3(0.25 * c.r + 0.5 * c.g + 0.25 * c.b, 0.5 * c.r - 0.5 * c.b, -0.25 * c.r + 0.5 * c.g - 0.25 * c.b);
}
vec3 yCoCgToRgb(vec3 c) { return vec3(c.x + c.y - c.z, c.x + c.z, c.x - c.y - c.z); }

// Catmull-Rom (tension 0.5) weights of the four taps at -1, 0, 1, 2 for a fraction t in [0, 1).
vec4 catmullRomWeights(float t) {
    float t2 = t * t, t3 = t2 * t;
    return vec4(-0.5 * t3 + t2 - 0.5 * t, 1.5 * t3 - 2.5 * t2 + 1.0, -1.5 * t3 + 2.0 * t2 + 0.5 * t, 0.5 * t3 - 0.5 * t2);
}

// Moves `v` toward the box centre until it lies in the box (Salvi's variance clipping: clip, not clamp, so the
// colour's hue is kept).
vec3 clipToBox(vec3 center, vec3 extents, vec3 v) {
    vec3 d = v - center;
    vec3 units = abs(d) / max(extents, vec3(1e-5));
    float m = max(units.x, max(units.y, units.z));
    return m > 1.0 ? center + d / m : v;
}

vec2 pixelNdc(ivec2 q, uvec2 extent) { return (vec2(q) + 0.5) / vec2(extent) * 2.0 - 1.0; }

// Motion of the background (and of anything static) at pixel q with depth d: the camera's reprojection. Works
// for d == 1 with an infinite far plane too (the homogeneous point is never divided before reprojecting).
vec2 cameraMotion(GpuTemporalFrame t, ivec2 q, float d) {
    vec2 ndc = pixelNdc(q, t.extent);
    vec4 previous = t.previous * (t.inverseUnjittered * vec4(ndc, d, 1.0));
    return (ndc - previous.xy / previous.w) * 0.5;
}

// Motion (current uv - previous uv) at pixel q: the motion-vector target where there is geometry, the camera's
// reprojection for the background (the motion pass writes no background fragments).
vec2 pixelMotion(GpuTemporalFrame t, uint motionImage, uint depthImage, ivec2 q) {
    float d = imageLoad(gImagesR32f[depthImage], q).r;
    if (d >= 1.0) return cameraMotion(t, q, 1.0);
    return unpackHalf2x16(imageLoad(gImagesR32ui[motionImage], q).r);
}

// World position of the sample at pixel q with depth d, in a frame with matrix `inverse` (unjittered) and jitter.
vec3 samplePosition(mat4 inverse, ivec2 q, float d, vec2 jitter, uvec2 extent) {
    vec4 h = inverse * vec4(pixelNdc(q, extent) + 2.0 * jitter / vec2(extent), d, 1.0);
    return h.xyz / h.w;
}

// True when the history at previousUv does not show this pixel's surface. The nearest history texel must have
// moved (nearly) as this pixel did: a background uncovered by a moving object finds the object's motion there.
// Pixels that do not move at all (and whose history did not) keep their history: a jittered edge is geometry in
// one frame and background in the next. Otherwise the background must find background, and a static surface seen
// by a moving camera must find a history texel in the 3x3 around previousUv whose depth reconstructs a point
// within two pixel footprints of this pixel's (the footprint: the distance to the neighbouring pixels' points,
// large at grazing angles and edges).
bool disoccluded(GpuTemporalFrame t, uint depthImage, uint historyDepth, uint historyMotion, ivec2 pixel,
                 float depth, vec2 motion, vec2 previousUv) {
    ivec2 size = ivec2(t.extent);
    vec2 pixels = vec2(size);
    ivec2 center = clamp(ivec2(previousUv * pixels), ivec2(0), size - 1);
    vec2 hm = unpackHalf2x16(imageLoad(gImagesR32ui[historyMotion], center).r);
    if (length((hm - motion) * pixels) > max(0.5, 0.25 * length(motion * pixels))) return true;
    if (length(motion * pixels) < 1e-3 && length(hm * pixels) < 1e-3) return false;
    bool background = depth >= 1.0;
    if (background) return imageLoad(gImagesR32f[historyDepth], center).r < 1.0;
    if (length((motion - cameraMotion(t, pixel, depth)) * pixels) > 0.25) return false;  // moving surface
    vec3 position = samplePosition(t.inverseUnjittered, pixel, depth, t.jitterPixels, t.extent);
    float footprint = 0.0;
    for (int k = 0; k < 2; ++k) {
        ivec2 step = k == 0 ? ivec2(pixel.x + 1 < size.x ? 1 : -1, 0) : ivec2(0, pixel.y + 1 < size.y ? 1 : -1);
        float dn = imageLoad(gImagesR32f[depthImage], pixel + step).r;
        if (dn < 1.0)
            footprint = max(footprint, distance(position, samplePosition(t.inverseUnjittered, pixel + step, dn,
                                                                          t.jitterPixels, t.extent)));
    }
    float tolerance = 2.0 * footprint + 0.005 * distance(position, t.cameraPosition);
    for (int y = -1; y <= 1; ++y)
        for (int x = -1; x <= 1; ++x) {
            ivec2 q = clamp(center + ivec2(x, y), ivec2(0), size - 1);
            float hd = imageLoad(gImagesR32f[historyDepth], q).r;
            if (hd >= 1.0) continue;
            vec3 h = samplePosition(t.inversePrevious, q, hd, t.previousJitter, t.extent);
            if (distance(h, position) <= tolerance) return false;
        }
    return true;
}

#endif
