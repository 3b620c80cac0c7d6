// shadows.glsl: point-light cube shadows. cubeFaceClip projects a light-relative position onto one cube face so
// that a textureCube lookup along the same direction finds the texel (Vulkan's cube face selection table), and
// pointShadowVisibility filters the cube with 3x3 bilinear comparison taps after a normal offset.
// Ports IDKEngine's PointShadow vertex path and the PCF of DeferredLighting/fragment.glsl (reference 2.12).
#ifndef IDK_SHADOWS_GLSL
#define IDK_SHADOWS_GLSL
#extension GL_EXT_buffer_reference : require
#include "bindless.glsl"
#include "shadow_types.h"

layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer PointShadowBuffer {
    GpuPointShadow data[];
};

// Depth mapping of the major-axis distance: d = a + b / ma with d(near) = 0, d(far) = 1.
vec2 pointShadowDepthCoefficients(float nearPlane, float farPlane) {
    float a = farPlane / (farPlane - nearPlane);
    return vec2(a, -nearPlane * a);
}

// Clip position of light-relative r on cube face f (0..5 = +X -X +Y -Y +Z -Z): x = sc, y = tc, w = ma (signed, so
// points behind the face are clipped), the face's (s, t) = ((sc / ma + 1) / 2, (tc / ma + 1) / 2) = framebuffer
// (x, y) / size in Vulkan's y-down viewport.
vec4 cubeFaceClip(vec3 r, uint face, vec2 depth) {
    vec3 m;  // (sc, tc, ma)
    switch (face) {
        case 0u: m = vec3(-r.z, -r.y, r.x); break;
        case 1u: m = vec3(r.z, -r.y, -r.x); break;
        case 2u: m = vec3(r.x, r.z, r.y); break;
        case 3u: m = vec3(r.x, -r.z, -r.y); break;
        case 4u: m = vec3(r.x, -r.y, r.z); break;
        default: m = vec3(-r.x, -r.y, -r.z); break;
    }
    return vec4(m.x, m.y, depth.x * m.z + depth.y, m.z);
}

float maxAxis(vec3 r) { return max(abs(r.x), max(abs(r.y), abs(r.z))); }

// Fraction of the light that reaches `position` (1 lit, 0 shadowed). n: unit surface normal facing the viewer's
// side, l: unit direction to the light with dot(n, l) > 0.
// Bias: the lookup point moves along n by texel * (1 + 3 sinT) (T = angle between n and l). A tap up to 2.5
// texels to the side (a diagonal kernel step, sqrt 2, plus the bilinear footprint) sees the flat receiver up to
// 2.5 texel tanT deeper, and the offset buys texel (1 + 3 sinT) / cosT of ray distance, which covers it at every
// angle; the constant texel absorbs rasterization and depth rounding. No depth-slope bias is needed on top.
float pointShadowVisibility(GpuPointShadow s, vec3 position, vec3 n, vec3 l) {
    float cosT = clamp(dot(n, l), 0.0, 1.0);
    float sinT = sqrt(1.0 - cosT * cosT);
    float texel = s.texelScale * maxAxis(position - s.position);  // world size of one texel here
    vec3 r = position + n * (texel * (1.0 + 3.0 * sinT)) - s.position;
    float ma = maxAxis(r);
    if (ma >= s.farPlane) return 1.0;  // beyond the stored range: no occluder was rasterized there
    vec2 k = pointShadowDepthCoefficients(s.nearPlane, s.farPlane);
    float reference = k.x + k.y / max(ma, s.nearPlane);

    // 3x3 taps one texel apart in the plane across r (Duff et al. 2017 orthonormal basis), each a 2x2 bilinear
    // comparison: a 4x4-texel tent-weighted footprint.
    vec3 d = normalize(r);
    float sgn = d.z >= 0.0 ? 1.0 : -1.0;
    float a = -1.0 / (sgn + d.z);
    float b = d.x * d.y * a;
    vec3 t = vec3(1.0 + sgn * d.x * d.x * a, sgn * b, -sgn * d.x);
    vec3 u = vec3(b, sgn + d.y * d.y * a, -d.y);
    float step = s.texelScale * ma;
    float lit = 0.0;
    for (int j = -1; j <= 1; ++j) {
        for (int i = -1; i <= 1; ++i) {
            vec3 dir = r + (t * float(i) + u * float(j)) * step;
            lit += textureGrad(samplerCubeShadow(gTexturesCube[nonuniformEXT(s.cube)], gSamplers[s.samplerIndex]),
                               vec4(dir, reference), vec3(0.0), vec3(0.0));
        }
    }
    return lit / 9.0;
}

#endif
