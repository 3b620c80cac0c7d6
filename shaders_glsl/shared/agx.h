// agx.h: the AgX display transform, one source for GLSL (the raster's tonemap pass, tonemap.frag.glsl) and C++
// (the path tracer's PNG output, engine/app/render_pathtrace.cpp), so both show radiance the same way. Maps
// exposure-scaled linear radiance (Rec.709/sRGB primaries) to display-linear values in [0, 1]; the caller applies
// the sRGB encoding. Ports IDKEngine's TonemapAndGammaCorrect/compute.glsl (AgX there too, reference 2.20).
// The independent C++ twin used as the tests' oracle is agx() in tests/support/pbr_oracle.cpp.
//
// Constants and their sources:
//  * inset matrix and the log2 exposure range [-12.47393, +4.026069] stops around middle grey: Troy Sobotka's
//    AgX OCIO configuration (github.com/sobotka/AgX);
//  * the base-contrast sigmoid as a 6th-order polynomial on the normalized log2 value: the least-squares fit
//    published by B. Wrensch, "Minimal AgX Implementation" (iolite-engine.com, 2023; mean squared error 3.7e-6);
//  * the outset is the inverse of the inset; the curve's output is display-referred for a 2.2 power display,
//    which is linearized here with 2.2.
#ifndef IDK_AGX_H
#define IDK_AGX_H
#include "interop.h"

#ifdef __cplusplus
namespace idk::gpu {
using glm::clamp;
using glm::inverse;
using glm::log2;
using glm::max;
using glm::pow;
#endif

IDK_INLINE mat3 agxInset() {
    return mat3(0.842479062253094f, 0.0423282422610123f, 0.0423756549057051f,
                0.0784335999999992f, 0.878468636469772f, 0.0784336f,
                0.0792237451477643f, 0.0791661274605434f, 0.879142973793104f);
}

IDK_INLINE vec3 agxContrast(vec3 x) {  // Horner form of the published polynomial
    return ((((((15.5f * x - 40.14f) * x + 31.96f) * x - 6.868f) * x + 0.4298f) * x + 0.1191f) * x) - 0.00232f;
}

IDK_INLINE vec3 agx(vec3 linearRadiance) {
    const float minEv = -12.47393f;
    const float maxEv = 4.026069f;
    vec3 v = agxInset() * max(linearRadiance, vec3(0.0f));
    v = clamp(log2(max(v, vec3(1e-10f))), minEv, maxEv);
    v = (v - minEv) / (maxEv - minEv);
    v = agxContrast(v);
    v = inverse(agxInset()) * v;
    return pow(clamp(v, 0.0f, 1.0f), vec3(2.2f));  // display linear
}

#ifdef __cplusplus
}  // namespace idk::gpu
#endif

#endif
