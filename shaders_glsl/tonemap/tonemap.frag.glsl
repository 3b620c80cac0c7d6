#version 460
// tonemap.frag.glsl: AgX display transform of exposure * linear radiance (Rec.709/sRGB primaries), written
// sRGB-encoded into an RGBA8 colour attachment by a fullscreen triangle. Ports IDKEngine's
// TonemapAndGammaCorrect/compute.glsl (AgX there too, reference 2.20); no bloom/volumetric inputs, no dithering.
// The C++ twin is agx() in tests/support/pbr_oracle.cpp; the constants' sources are given below.
#extension GL_GOOGLE_include_directive : require
#include "interop.h"
#include "bindless.glsl"
#include "deferred_types.h"
#include "color.glsl"

// AgX constants and their sources:
//  * inset matrix and the log2 exposure range [-12.47393, +4.026069] stops around middle grey: Troy Sobotka's
//    AgX OCIO configuration (github.com/sobotka/AgX);
//  * the base-contrast sigmoid as a 6th-order polynomial on the normalized log2 value: the least-squares fit
//    published by B. Wrensch, "Minimal AgX Implementation" (iolite-engine.com, 2023; mean squared error 3.7e-6);
//  * the outset is the inverse of the inset; the curve's output is display-referred for a 2.2 power display,
//    which we linearize with 2.2 and re-encode with the exact sRGB transfer function (IEC 61966-2-1).

layout(push_constant, scalar) uniform Push { TonemapPush p; };
layout(location = 0) out vec4 outColor;

const mat3 kAgxInset = mat3(0.842479062253094, 0.0423282422610123, 0.0423756549057051,
                            0.0784335999999992, 0.878468636469772, 0.0784336,
                            0.0792237451477643, 0.0791661274605434, 0.879142973793104);
const float kAgxMinEv = -12.47393;
const float kAgxMaxEv = 4.026069;

vec3 agxContrast(vec3 x) {  // Horner form of the published polynomial
    return ((((((15.5 * x - 40.14) * x + 31.96) * x - 6.868) * x + 0.4298) * x + 0.1191) * x) - 0.00232;
}

vec3 agx(vec3 linear) {
    vec3 v = kAgxInset * max(linear, vec3(0.0));
    v = clamp(log2(max(v, vec3(1e-10))), kAgxMinEv, kAgxMaxEv);
    v = (v - kAgxMinEv) / (kAgxMaxEv - kAgxMinEv);
    v = agxContrast(v);
    v = inverse(kAgxInset) * v;
    return pow(clamp(v, 0.0, 1.0), vec3(2.2));  // display linear
}


void main() {
    vec3 radiance = imageLoad(gImagesRgba16f[p.source], ivec2(gl_FragCoord.xy)).rgb * p.exposure;
    outColor = vec4(srgbEncode(agx(radiance)), 1.0);
}
