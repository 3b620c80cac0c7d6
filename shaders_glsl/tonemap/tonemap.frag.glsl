#version 460
// tonemap.frag.glsl: AgX display transform of exposure * linear radiance (Rec.709/sRGB primaries), written
// sRGB-encoded into an RGBA8 colour attachment by a fullscreen triangle. Ports IDKEngine's
// TonemapAndGammaCorrect/compute.glsl (AgX there too, reference 2.20); no bloom/volumetric inputs, no dithering.
// The curve is shared/agx.h (also the path tracer's PNG output); its independent C++ oracle is agx() in
// tests/support/pbr_oracle.cpp.
#extension GL_GOOGLE_include_directive : require
#include "interop.h"
#include "bindless.glsl"
#include "deferred_types.h"
#include "color.glsl"
#include "agx.h"

layout(push_constant, scalar) uniform Push { TonemapPush p; };
layout(location = 0) out vec4 outColor;

void main() {
    vec3 radiance = imageLoad(gImagesRgba16f[p.source], ivec2(gl_FragCoord.xy)).rgb * p.exposure;
    outColor = vec4(srgbEncode(agx(radiance)), 1.0);
}
