// edge_function.hpp: the 2D edge functions a*b - c*d of the single-precision watertight ray/triangle test
// (intersect.hpp) with an exact sign, in float and 32/64-bit integers only. GLSL twin, operation for operation:
// shaders_glsl/include/bvh_edge_function.glsl. Replaces the double-precision edge functions (GPUs run fp64 at
// 1/16-1/64 rate or not at all); Woop, Benthin & Wald 2013 use fp32 with a double fallback, this falls back to
// integers instead, and a certified error bound rather than "== 0" selects the fallback (see below why).
//
// Why the sign is exact. Inputs a, b, c, d are sheared vertex coordinates, passed through flushSubnormal() so
// that they are zero or normal on every device (a GPU may flush subnormal inputs to zero, the CPU does not;
// decodeFloat() also reads a subnormal as zero, so even a compiler that drops the explicit flush cannot make the two
// paths see different numbers). Let u = 2^-24, eta = 2^-126. Vulkan guarantees for OpFMul/OpFSub/OpFAdd only a
// faithful result (exact if representable, else one of the two neighbours; the rounding direction is unspecified,
// and subnormal results may be flushed), so every operation's error is below 3u|result| + eta (|x - fl(x)| <
// ulp(x) <= 2u|x|, and |x| <= |fl(x)| + |x - fl(x)|). With p = fl(ab), q = fl(cd), e = fl(p - q) and the exact
// D = ab - cd:
//     |e - D| <= |e - (p - q)| + |p - ab| + |q - cd| < 3u|e| + 3u(|p| + |q|) + 3 eta.
// Fast path: sign(e) is taken when |e| > fl(fl(|p| + |q|) * 2^-20) and |e| > 2^-120. The computed bound is at
// least 16u(|p| + |q|)(1 - 3u) - 2 eta (faithful roundings, a possible flush), so then |e|(1 - 3u) exceeds
// 3u(|p| + |q|) + 3 eta, i.e. |e| > |e - D|, and sign(e) = sign(D). No assumption about the rounding mode, no
// FMA (the C++ is compiled with -ffp-contract=off, the GLSL is `precise`), and NaN or inf (products beyond 2^128)
// fail both comparisons and take the exact path. GLSL fma() is not used: Vulkan does not require it to be fused.
// Exact path: a float is m * 2^(E - 150) with a 24-bit integer m (implicit bit set) and biased exponent E, so
// ab = (ma mb) * 2^(Ea + Eb - 300) with a product below 2^48, exact in 64 bits. The two products are aligned in
// int64: a shift left by at most 14 keeps both below 2^62, so their difference fits; when the exponents differ by
// more, the smaller product is below 2^33 after a right shift while the larger is at least 2^46, so truncating it
// cannot change the sign. The sign of the integer difference is the exact sign of D. Its value (for det and t
// only) is the difference converted to float and scaled with two ldexp steps of at most 2^+-126 each (GLSL leaves
// larger steps undefined); the exponent is clamped to [-230, 60], which saturates the magnitude (never the sign)
// for products beyond 2^106.
//
// Consequences. A shared edge (B, C) gives D and -D in its two triangles (the sheared coordinates of a vertex are
// the same in both, and both paths are exact), so with edges counted as inside no ray passes between them: the test
// is watertight for every input whose sheared coordinates are normal or zero and whose products stay below 2^128
// (|coordinate| < 2^64 from the ray origin; beyond that the fp32 t is not finite and the triangle misses). The value
// has the exact sign (or is 0 after underflow), so det = U + V + W never cancels and t is a convex combination of
// the vertices' ray-space depths up to rounding. Decisions depend on no rounding at all, so CPU and GPU agree on
// them exactly; values agree bit for bit where the device rounds to nearest even like the CPU (lavapipe does).
#pragma once

#include <cmath>
#include <cstdint>

namespace idk::bvh {

struct EdgeValue {
    float value = 0.0f;  // a*b - c*d, accurate to a few ulps, with the sign below (or 0 after underflow)
    int sign = 0;        // exact sign of a*b - c*d: -1, 0, 1
};

// Subnormals become (signed) zero, so every device sees the same normal-or-zero coordinates.
inline float flushSubnormal(float x) { return std::abs(x) < 0x1p-126f ? 0.0f : x; }

namespace detail {

// a*b - c*d exactly (sign) and rounded (value), in integers (edge_function.cpp). See the header comment. Out of
// line: it runs for about one edge function in 10^5 (random rays in the rotated atrium), so it stays off the hot path.
EdgeValue exactDifference(float a, float b, float c, float d);

}  // namespace detail

// a*b - c*d with its exact sign: fp32 with a certified error bound, integers where the bound cannot decide.
inline EdgeValue edgeFunction(float a, float b, float c, float d) {
    const float p = a * b;
    const float q = c * d;
    const float e = p - q;
    const float bound = (std::abs(p) + std::abs(q)) * 0x1p-20f;
    if (std::abs(e) > bound && std::abs(e) > 0x1p-120f) [[likely]]
        return {e, e > 0.0f ? 1 : -1};
    return detail::exactDifference(a, b, c, d);
}

}  // namespace idk::bvh
