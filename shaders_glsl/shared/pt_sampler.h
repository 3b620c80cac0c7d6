// pt_sampler.h: the path tracer's sample generators, one source for C++ (the CPU reference) and GLSL (the
// wavefront stages), included by pt_common.h. Two samplers behind one call, ptSample(rng, dimension):
// * independent: a PCG hash seeds a 32-bit PCG per pixel and sample (Jarzynski & Olano 2020); `dimension` is
//   ignored and the draws come in call order (both tracers call in the same order);
// * sobol: Owen-scrambled Sobol' points, padded in 2D (Burley 2020, "Practical Hash-based Owen Scrambling"):
//   every pair of dimensions (2k, 2k + 1) is the first two Sobol' dimensions (a (0,2)-sequence) of the sample
//   index, with the index shuffled and the point Owen-scrambled by hashes of (pixel, seed, pair), so each pair is
//   stratified in 2D over a pixel's samples, pairs are decorrelated from each other, and pixels are independent
//   (white error between pixels, no structured patterns). The index shuffle is itself a nested uniform scramble
//   of the index bits: any 2^k consecutive-from-0 shuffled indices cover every residue mod 2^k, so the first
//   2^k samples of a pair stay a (0,k,2)-net. The Owen scramble uses the Laine-Karras style hash with the
//   constants of N. Vegdahl's improved variant ("Owen scrambling based on Laine-Karras", 2021).
// Dimensions are named below (kPtDim*): the camera's pixel jitter, then per path vertex a block of
// kPtDimsPerVertex for light selection, the light sample, the BSDF lobe and direction, and Russian roulette;
// each 2D quantity sits on an aligned pair. IDKEngine draws its diffuse directions from an R2 sequence shared by
// all bounces (reference section 5); there is no lens (pinhole camera), so no lens dimensions are allocated.
// Cost: a sobol draw is two 5-step hash scrambles, two bit reversals and a loop over the index bits (at most 32,
// ~log2(spp) in practice): pure ALU, no tables, no per-path state beyond the vertex number. In the memory-bound
// wavefront stages of a real GPU that is hidden behind the path-state loads. On lavapipe the samples/s of the Sobol'
// rows are 0.88-1.02x the independent rows' (per-scene medians, BENCHMARKS.md; a loaded 2-core machine, so noisy).
#ifndef IDK_PT_SAMPLER_H
#define IDK_PT_SAMPLER_H
#include "interop.h"

IDK_GPU_BEGIN

IDK_CONST(uint, kPtSamplerIndependent, 0u);
IDK_CONST(uint, kPtSamplerSobol, 1u);

// Dimensions: (0, 1) pixel jitter; vertex k (1 = the camera ray's hit) uses kPtDimVertexBase(k) + offset.
IDK_CONST(uint, kPtDimJitterX, 0u);
IDK_CONST(uint, kPtDimJitterY, 1u);
IDK_CONST(uint, kPtDimsPerVertex, 10u);
IDK_CONST(uint, kPtDimLightX, 0u);       // pair: point on the light / environment texel
IDK_CONST(uint, kPtDimLightY, 1u);
IDK_CONST(uint, kPtDimBsdfX, 2u);        // pair: BSDF direction (u.y, u.z of ptSampleBsdf)
IDK_CONST(uint, kPtDimBsdfY, 3u);
IDK_CONST(uint, kPtDimLightSlot, 4u);    // pair: alias-table slot and its coin
IDK_CONST(uint, kPtDimLightAlias, 5u);
IDK_CONST(uint, kPtDimBsdfLobe, 6u);     // pair: BSDF lobe choice and environment-vs-lights choice
IDK_CONST(uint, kPtDimLightChoice, 7u);
IDK_CONST(uint, kPtDimRoulette, 8u);     // pair: Russian roulette and the dispersion channel (pt_dispersion.h,
IDK_CONST(uint, kPtDimDispersion, 9u);   // drawn only at a path's first dispersive surface)

struct PtRng {
    uint state;        // PCG state (independent sampler; also the sobol sampler's stream for BLEND alpha coins)
    uint kind;         // kPtSampler*
    uint scramble;     // hash of (pixel, seed): the sobol sampler's per-pixel scrambling seed
    uint sampleIndex;  // global sample number (the Sobol' index)
};

IDK_INLINE uint ptHash(uint v) {
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

IDK_INLINE uint ptDimVertexBase(uint vertex) { return 2u + kPtDimsPerVertex * (vertex - 1u); }

IDK_INLINE PtRng ptRngInitSampler(uint pixel, uint sampleIndex, uint seed, uint kind) {
    PtRng rng;
    rng.state = ptHash(pixel ^ ptHash(sampleIndex ^ ptHash(seed + 0x9E3779B9u)));
    rng.kind = kind;
    rng.scramble = ptHash(pixel ^ ptHash(seed + 0x7F4A7C15u));
    rng.sampleIndex = sampleIndex;
    return rng;
}

IDK_INLINE PtRng ptRngInit(uint pixel, uint sampleIndex, uint seed) {
    return ptRngInitSampler(pixel, sampleIndex, seed, kPtSamplerIndependent);
}

IDK_INLINE uint ptNextUint(IDK_INOUT(PtRng) rng) {
    rng.state = rng.state * 747796405u + 2891336453u;
    uint s = rng.state;
    uint word = ((s >> ((s >> 28u) + 4u)) ^ s) * 277803737u;
    return (word >> 22u) ^ word;
}

// Uniform in [0, 1): the top 24 bits, exact in float on both sides.
IDK_INLINE float ptUnitFloat(uint bits) { return float(bits >> 8u) * (1.0f / 16777216.0f); }
IDK_INLINE float ptRandom(IDK_INOUT(PtRng) rng) { return ptUnitFloat(ptNextUint(rng)); }

IDK_INLINE uint ptReverseBits(uint x) {  // GLSL's bitfieldReverse, spelled out so C++ shares it
    x = ((x >> 1u) & 0x55555555u) | ((x & 0x55555555u) << 1u);
    x = ((x >> 2u) & 0x33333333u) | ((x & 0x33333333u) << 2u);
    x = ((x >> 4u) & 0x0F0F0F0Fu) | ((x & 0x0F0F0F0Fu) << 4u);
    x = ((x >> 8u) & 0x00FF00FFu) | ((x & 0x00FF00FFu) << 8u);
    return (x >> 16u) | (x << 16u);
}

// A bijection of 32-bit words in which each bit only depends on itself and lower bits (every step is x ^= x * even,
// x += c or x *= odd), so on bit-reversed fixed-point numbers it is a (hash-driven) nested uniform scramble.
IDK_INLINE uint ptLaineKarras(uint x, uint seed) {
    x ^= x * 0x3D20ADEAu;
    x += seed;
    x *= (seed >> 16u) | 1u;
    x ^= x * 0x05526C56u;
    x ^= x * 0x53A22864u;
    return x;
}

// Owen scramble of a 32-bit fixed-point number in [0, 1) (bit 31 = 1/2): digit j flips by a hash of digits < j.
IDK_INLINE uint ptOwenScramble(uint x, uint seed) { return ptReverseBits(ptLaineKarras(ptReverseBits(x), seed)); }

// Sobol' dimension 0 (van der Corput) and 1 (primitive polynomial x + 1) of index i, 32-bit fixed point.
IDK_INLINE uint ptSobol0(uint i) { return ptReverseBits(i); }
IDK_INLINE uint ptSobol1(uint i) {
    uint r = 0u;
    uint v = 0x80000000u;
    for (; i != 0u; i >>= 1u) {
        if ((i & 1u) != 0u) r ^= v;
        v ^= v >> 1u;
    }
    return r;
}

// The sobol sampler's value of `dimension` (32-bit fixed point), see the file comment.
IDK_INLINE uint ptSobolBits(uint scramble, uint sampleIndex, uint dimension) {
    uint pairSeed = ptHash(scramble ^ ptHash(dimension >> 1u));
    uint index = ptOwenScramble(sampleIndex, pairSeed);
    bool second = (dimension & 1u) != 0u;
    uint point = second ? ptSobol1(index) : ptSobol0(index);
    return ptOwenScramble(point, ptHash(pairSeed ^ (second ? 0x68E31DA4u : 0xB5297A4Du)));
}

// One uniform in [0, 1) for `dimension`. The independent sampler ignores it (call order decides).
IDK_INLINE float ptSample(IDK_INOUT(PtRng) rng, uint dimension) {
    if (rng.kind == kPtSamplerSobol) return ptUnitFloat(ptSobolBits(rng.scramble, rng.sampleIndex, dimension));
    return ptRandom(rng);
}

IDK_GPU_END

#endif
