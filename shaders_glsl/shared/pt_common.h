// pt_common.h: the basics of the path tracer's shared maths (one source for C++ and GLSL, see pt_sampling.h):
// small vector helpers, MIS power heuristic, Russian roulette, Beer-Lambert absorption and the camera ray. The
// samplers (independent PCG, Owen-scrambled Sobol') are in pt_sampler.h. IDKEngine seeds a PCG hash per pixel and
// sample too (PathTracing/FirstHit), but draws its diffuse directions from an R2 sequence shared by all bounces
// (reference section 5).
#ifndef IDK_PT_COMMON_H
#define IDK_PT_COMMON_H
#include "pt_types.h"
#include "pt_sampler.h"

#ifdef __cplusplus
#include <glm/gtc/type_ptr.hpp>
namespace idk::gpu {
using glm::abs;
using glm::acos;
using glm::atan;
using glm::clamp;
using glm::cos;
using glm::cross;
using glm::dot;
using glm::exp;
using glm::floatBitsToUint;
using glm::inversesqrt;
using glm::length;
using glm::log;
using glm::max;
using glm::min;
using glm::mix;
using glm::normalize;
using glm::sin;
using glm::sqrt;
}  // namespace idk::gpu
#endif

IDK_GPU_BEGIN

IDK_CONST(float, kPtPi, 3.14159265358979f);
IDK_CONST(float, kPtInvPi, 0.318309886183791f);
IDK_CONST(float, kPtFar, 1.0e30f);          // "infinite" distance of directional and environment samples
IDK_CONST(float, kPtDeltaAlpha, 1.0e-3f);   // GGX alpha below this: the specular lobes are treated as delta
IDK_CONST(float, kPtMinCos, 1.0e-4f);

// ---------------------------------------------------------------------------------------------------- helpers
IDK_INLINE float ptAverage(vec3 c) { return (c.x + c.y + c.z) * (1.0f / 3.0f); }
IDK_INLINE float ptLuminance(vec3 c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }
IDK_INLINE float ptMaxComponent(vec3 c) { return max(c.x, max(c.y, c.z)); }

// True when every component is a finite number (NaN and inf fail).
IDK_INLINE bool ptFinite(float x) { return (floatBitsToUint(x) & 0x7F800000u) != 0x7F800000u; }
IDK_INLINE bool ptFinite3(vec3 v) { return ptFinite(v.x) && ptFinite(v.y) && ptFinite(v.z); }
// Clamps to [0, 1], NaN to 0 (clamp alone leaves NaN undefined in GLSL and NaN in glm).
IDK_INLINE float ptSaturate(float x) { return ptFinite(x) ? clamp(x, 0.0f, 1.0f) : 0.0f; }

// Orthonormal basis around unit n (Duff et al. 2017, "Building an Orthonormal Basis, Revisited").
IDK_INLINE void ptBasis(vec3 n, IDK_OUT(vec3) t, IDK_OUT(vec3) b) {
    float s = n.z >= 0.0f ? 1.0f : -1.0f;
    float a = -1.0f / (s + n.z);
    float c = n.x * n.y * a;
    t = vec3(1.0f + s * n.x * n.x * a, s * c, -s * n.x);
    b = vec3(c, s + n.y * n.y * a, -n.y);
}

IDK_INLINE vec3 ptToLocal(vec3 v, vec3 t, vec3 b, vec3 n) { return vec3(dot(v, t), dot(v, b), dot(v, n)); }
IDK_INLINE vec3 ptToWorld(vec3 v, vec3 t, vec3 b, vec3 n) { return t * v.x + b * v.y + n * v.z; }

// Power heuristic (beta = 2) weight of a strategy with pdf a against one with pdf b.
IDK_INLINE float ptPowerHeuristic(float a, float b) {
    if (!ptFinite(a)) return 1.0f;
    float a2 = a * a, b2 = b * b;
    return a2 + b2 > 0.0f ? a2 / (a2 + b2) : 0.0f;
}

// Russian roulette survival probability (applied from PtSettings::rouletteDepth on).
IDK_INLINE float ptSurvivalProbability(vec3 throughput) { return clamp(ptMaxComponent(throughput), 0.0f, 0.95f); }

// Beer-Lambert transmittance over `distance` inside a volume (KHR_materials_volume): attenuationColor is the
// transmittance after attenuationDistance; attenuationDistance 0 means no absorption.
IDK_INLINE vec3 ptVolumeTransmittance(vec3 attenuationColor, float attenuationDistance, float distance) {
    if (!(attenuationDistance > 0.0f)) return vec3(1.0f);
    vec3 c = max(attenuationColor, vec3(1.0e-6f));
    vec3 sigma = -vec3(log(c.x), log(c.y), log(c.z)) / attenuationDistance;
    return vec3(exp(-sigma.x * distance), exp(-sigma.y * distance), exp(-sigma.z * distance));
}

// ---------------------------------------------------------------------------------------------------- camera
// Ray through pixel position `pixel` (in pixels, (0, 0) = top-left corner of the image, jitter already added) of a
// width x height image, for the inverse of projection * view (engine/scene/camera.hpp: y down in NDC, depth 0 at
// the near plane). The ray starts on the near plane.
IDK_INLINE void ptCameraRay(mat4 inverseViewProjection, vec2 pixel, vec2 size, IDK_OUT(vec3) origin,
                            IDK_OUT(vec3) direction) {
    float x = 2.0f * pixel.x / size.x - 1.0f;
    float y = 2.0f * pixel.y / size.y - 1.0f;
    vec4 nearPoint = inverseViewProjection * vec4(x, y, 0.0f, 1.0f);
    vec4 midPoint = inverseViewProjection * vec4(x, y, 0.5f, 1.0f);
    vec3 p0 = vec3(nearPoint.x, nearPoint.y, nearPoint.z) / nearPoint.w;
    vec3 p1 = vec3(midPoint.x, midPoint.y, midPoint.z) / midPoint.w;
    origin = p0;
    direction = normalize(p1 - p0);
}

IDK_GPU_END

#endif
