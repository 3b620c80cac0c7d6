// edge_function.cpp: the exact integer path of the edge functions (edge_function.hpp has the proof); GLSL twin:
// bvhExactDifference in shaders_glsl/include/bvh_edge_function.glsl.
#include "bvh/edge_function.hpp"

#include <algorithm>
#include <bit>

namespace idk::bvh::detail {
namespace {

// x = m * 2^(e - 150): m with the implicit bit, e the biased exponent; m = 0 for zero, subnormal, inf, NaN.
void decodeFloat(float x, uint32_t& m, int& e) {
    const uint32_t bits = std::bit_cast<uint32_t>(x);
    const uint32_t biased = (bits >> 23) & 0xFFu;
    const bool regular = biased != 0u && biased != 0xFFu;
    m = regular ? ((bits & 0x7FFFFFu) | 0x800000u) : 0u;
    e = regular ? int(biased) : 0;
}

}  // namespace

EdgeValue exactDifference(float a, float b, float c, float d) {
    uint32_t ma = 0, mb = 0, mc = 0, md = 0;
    int ea = 0, eb = 0, ec = 0, ed = 0;
    decodeFloat(a, ma, ea);
    decodeFloat(b, mb, eb);
    decodeFloat(c, mc, ec);
    decodeFloat(d, md, ed);
    const uint64_t p = uint64_t(ma) * uint64_t(mb);  // < 2^48
    const uint64_t q = uint64_t(mc) * uint64_t(md);
    int ep = ea + eb;
    int eq = ec + ed;
    if (p == 0u) ep = eq;  // a zero product aligns with anything
    if (q == 0u) eq = ep;
    const int shift = ep - eq;
    uint64_t alignedP = p, alignedQ = q;
    int exponent = 0;
    if (shift >= 0) {
        alignedP = shift <= 14 ? p << shift : p;
        alignedQ = shift <= 14 ? q : (shift < 64 ? q >> shift : 0u);
        exponent = shift <= 14 ? eq : ep;
    } else {
        alignedP = -shift <= 14 ? p : (-shift < 64 ? p >> -shift : 0u);
        alignedQ = -shift <= 14 ? q << -shift : q;
        exponent = -shift <= 14 ? ep : eq;
    }
    const bool negP = std::signbit(a) != std::signbit(b);
    const bool negQ = std::signbit(c) != std::signbit(d);
    const int64_t sp = negP ? -int64_t(alignedP) : int64_t(alignedP);
    const int64_t sq = negQ ? -int64_t(alignedQ) : int64_t(alignedQ);
    const int64_t diff = sp - sq;
    const int scale = std::clamp(exponent - 300, -230, 60);
    const int firstStep = scale / 2;
    EdgeValue out;
    out.value = std::ldexp(std::ldexp(float(diff), firstStep), scale - firstStep);
    out.sign = diff > 0 ? 1 : (diff < 0 ? -1 : 0);
    return out;
}

}  // namespace idk::bvh::detail
