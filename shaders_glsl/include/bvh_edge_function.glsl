// bvh_edge_function.glsl: the 2D edge functions a*b - c*d of the single-precision watertight ray/triangle test with
// an exact sign, in float and integers only (no shaderFloat64). Twin of engine/bvh/edge_function.hpp, operation for
// operation; the proof of exactness (certified fp32 error bound valid for any faithful Vulkan rounding, exact
// int64 fallback) is written there. Every float expression is `precise`: no contraction into FMA, no reassociation.
// fma() is deliberately not used: GLSL.std.450 Fma is not required to be fused on Vulkan devices.
// On a real GPU the fallback (64-bit integer multiply and shifts, emulated with 32-bit ops) runs for the few rays
// that pass within rounding distance of an edge or vertex: a divergent but rare branch.
#ifndef IDK_BVH_EDGE_FUNCTION_GLSL
#define IDK_BVH_EDGE_FUNCTION_GLSL
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require

// bvh::flushSubnormal: subnormals become zero, so every device sees the same normal-or-zero coordinates.
float bvhFlushSubnormal(float x) { return abs(x) < 1.17549435082228750797e-38 ? 0.0 : x; }

// bvh::detail::decodeFloat: x = m * 2^(e - 150); m = 0 for zero, subnormal, inf and NaN.
void bvhDecodeFloat(float x, out uint m, out int e) {
    uint bits = floatBitsToUint(x);
    uint biased = (bits >> 23) & 0xFFu;
    bool regular = biased != 0u && biased != 0xFFu;
    m = regular ? ((bits & 0x7FFFFFu) | 0x800000u) : 0u;
    e = regular ? int(biased) : 0;
}

// bvh::detail::exactDifference: the exact sign of a*b - c*d and its value rounded to float.
float bvhExactDifference(float a, float b, float c, float d, out int sign) {
    uint ma, mb, mc, md;
    int ea, eb, ec, ed;
    bvhDecodeFloat(a, ma, ea);
    bvhDecodeFloat(b, mb, eb);
    bvhDecodeFloat(c, mc, ec);
    bvhDecodeFloat(d, md, ed);
    uint64_t p = uint64_t(ma) * uint64_t(mb);  // < 2^48
    uint64_t q = uint64_t(mc) * uint64_t(md);
    int ep = ea + eb;
    int eq = ec + ed;
    if (p == 0ul) ep = eq;  // a zero product aligns with anything
    if (q == 0ul) eq = ep;
    int shift = ep - eq;
    uint64_t alignedP = p;
    uint64_t alignedQ = q;
    int exponent = 0;
    if (shift >= 0) {
        alignedP = shift <= 14 ? p << shift : p;
        alignedQ = shift <= 14 ? q : (shift < 64 ? q >> shift : 0ul);
        exponent = shift <= 14 ? eq : ep;
    } else {
        alignedP = -shift <= 14 ? p : (-shift < 64 ? p >> -shift : 0ul);
        alignedQ = -shift <= 14 ? q << -shift : q;
        exponent = -shift <= 14 ? ep : eq;
    }
    bool negP = ((floatBitsToUint(a) ^ floatBitsToUint(b)) & 0x80000000u) != 0u;
    bool negQ = ((floatBitsToUint(c) ^ floatBitsToUint(d)) & 0x80000000u) != 0u;
    int64_t sp = negP ? -int64_t(alignedP) : int64_t(alignedP);
    int64_t sq = negQ ? -int64_t(alignedQ) : int64_t(alignedQ);
    int64_t diff = sp - sq;
    int scale = clamp(exponent - 300, -230, 60);
    int firstStep = scale / 2;  // truncates towards zero, as C++
    precise float value = ldexp(ldexp(float(diff), firstStep), scale - firstStep);
    sign = diff > 0l ? 1 : (diff < 0l ? -1 : 0);
    return value;
}

// bvh::edgeFunction: a*b - c*d with its exact sign; fp32 with a certified error bound, integers otherwise.
float bvhEdgeFunction(float a, float b, float c, float d, out int sign) {
    precise float p = a * b;
    precise float q = c * d;
    precise float e = p - q;
    precise float bound = (abs(p) + abs(q)) * 9.5367431640625e-7;  // 2^-20
    if (abs(e) > bound && abs(e) > 7.52316384526264005100e-37) {   // 2^-120
        sign = e > 0.0 ? 1 : -1;
        return e;
    }
    return bvhExactDifference(a, b, c, d, sign);
}

#endif
