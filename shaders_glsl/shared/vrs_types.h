// vrs_types.h: variable-rate shading (issue 14), shared by C++ and GLSL: the rate buffer's layout, the passes'
// push blocks, and the per-pixel and per-tile arithmetic of the classifier (vrs/classify.comp.glsl), which the CPU
// oracle (engine/frame/vrs_oracle.cpp) calls too. Ports IDKEngine's ShadingRateClassification/compute.glsl
// (reference internals 2.13): palette {1x1, 2x1, 2x2, 4x2, 4x4}; rate = round(lerp(0,4, meanSpeed * 0.2) +
// lerp(0,4, 0.04 / CV)) clamped to [0, 4]; tiles of mean luminance <= 0.001 get 4x4; luminance = mean of RGB.
//
// Exactness: GPU and CPU compute bit-identical rates. The tile sums are integers (fixed point), so subgroup and
// shared-memory reductions, in any order and for any subgroup size, give the same sums as the CPU. Luminance is
// quantised per tile to B bits of the tile's maximum (B = (32 - log2 pixels) / 2: the sum of squares fits 32 bits);
// the scale is a power of two taken from the maximum's exponent, so L * scale is exact and floor() is the only
// rounding. Everything else uses only operations that Vulkan requires to be correctly rounded (float add, subtract,
// multiply and conversions; spec appendix "Precision and Operation of SPIR-V Instructions"), marked precise so no
// compiler fuses them into an fma, and integer arithmetic: no division and no float sqrt, whose GPU precision is
// only 2.5 ULP (a value at a rounding boundary used to go either way). The speed's square root is an integer
// square root (a float estimate corrected by 64-bit products); the rate compares the value with each rounding
// threshold after multiplying out the divisions and squaring the square root away (vrsTileRate). The C++ side
// must not contract either: the oracle (frame/vrs_oracle.cpp) is compiled with -ffp-contract=off.
// Denormals, which a GPU may flush, arise only below 1 in the speed (floored to 0 either way) and not at all in
// the decision (factors below kVrsMinFactor count as 0).
#ifndef IDK_VRS_TYPES_H
#define IDK_VRS_TYPES_H
#include "interop.h"

#ifdef __cplusplus
#include <cmath>
namespace idk::gpu {
using glm::floatBitsToUint;
using glm::uintBitsToFloat;
using std::abs;
using std::sqrt;
}  // namespace idk::gpu
#define IDK_PRECISE
#else
#define IDK_PRECISE precise
#endif

IDK_GPU_BEGIN

IDK_CONST(uint, kVrsDefaultTileSize, 16);     // pixels per tile side without hardware VRS (the original's)
IDK_CONST(uint, kVrsRateCount, 5);            // palette entries: 1x1, 2x1, 2x2, 4x2, 4x4
IDK_CONST(float, kVrsSpeedFactor, 0.2f);      // the original's SpeedFactor
IDK_CONST(float, kVrsLumVarianceFactor, 0.04f);  // the original's LumVarianceFactor
IDK_CONST(float, kVrsDarkLuminance, 0.001f);  // mean luminance at or below: 4x4
IDK_CONST(float, kVrsMaxLuminance, 65504.0f); // larger (and +inf) luminance is clamped (RGBA16F's largest)
IDK_CONST(float, kVrsMaxSpeed, 32.0f);        // UV units per second; larger is clamped (saturated long before)
IDK_CONST(uint, kVrsGroupSize, 256);          // classifier invocations per workgroup (one workgroup per tile)

// Specialization constants of classify.comp.
IDK_CONST(uint, kSpecVrsTileSize, 0);         // pixels per tile side: 8, 16 or 32
IDK_CONST(uint, kSpecVrsSubgroupReduce, 1);   // 1: subgroupMax/subgroupAdd + shared slots; 0: shared-memory tree

// The rate buffer: this header, then one uint palette index per tile, row-major. The classifier of frame N writes
// it, frame N + 1's lighting and sky read it.
struct VrsRatesHeader {
    uint tileSize;
    uint tilesX;
    uint tilesY;
    uint pad;
};
IDK_GPU_SIZE(VrsRatesHeader, 16);

// classify.comp: lit image + per-pixel velocity -> rates (one workgroup per tile).
struct VrsClassifyPush {
    DeviceAddress rates;     // VrsRatesHeader + uint[tilesX * tilesY]
    DeviceAddress velocity;  // vec2[width * height], UV units per frame; 0: no motion
    uint lit;                // RGBA16F storage image: the lit frame (after transparency)
    uint width;
    uint height;
    float invFrameSeconds;   // 1 / frame time: UV per frame -> UV per second
    float speedFactor;
    float lumVarianceFactor;
};
IDK_GPU_SIZE(VrsClassifyPush, 40);

// velocity.comp: the classifier's velocity field from the temporal motion vectors (object, skinned and camera
// motion), the background reprojected by the camera.
struct VrsVelocityPush {
    DeviceAddress temporal;  // GpuTemporalFrame (shared/temporal_types.h): this and last frame's camera
    DeviceAddress velocity;  // vec2[width * height], UV units per frame
    uint motion;             // R32UI storage: packHalf2x16(current uv - previous uv), zero on the background
    uint depth;              // R32F G-buffer depth (1: background)
    uint width;
    uint height;
};
IDK_GPU_SIZE(VrsVelocityPush, 32);

// reconstruct.comp: fills the pixels the coarse lighting and sky did not shade, edge-aware from the G-buffer.
struct VrsReconstructPush {
    DeviceAddress frame;     // GpuFrame
    DeviceAddress rates;
    uint depth;              // R32F
    uint normal;             // R32UI octahedral
    uint target;             // RGBA16F, shaded at the cell anchors
    uint fillSentinel;       // test hook: 1 writes kVrsSentinel to every pixel instead (run before lighting)
};
IDK_GPU_SIZE(VrsReconstructPush, 32);
IDK_CONST(float, kVrsSentinel, -1.0f);  // a radiance no pass writes

// overlay.comp (--vrs-debug): tints each tile of the HDR image by its rate.
struct VrsOverlayPush {
    DeviceAddress rates;
    uint target;
    uint pad;
};
IDK_GPU_SIZE(VrsOverlayPush, 16);

// Coarse cell of a palette index, in pixels (x, y).
IDK_INLINE uvec2 vrsCellSize(uint rate) {
    return rate == 0u ? uvec2(1u, 1u)
         : rate == 1u ? uvec2(2u, 1u)
         : rate == 2u ? uvec2(2u, 2u)
         : rate == 3u ? uvec2(4u, 2u)
                      : uvec2(4u, 4u);
}

IDK_INLINE uint vrsLog2(uint v) {  // v a power of two
    uint l = 0u;
    while ((1u << l) < v) l++;
    return l;
}

// Luminance fraction bits B for tiles of `tilePixels` pixels (a power of two): n * (2^B - 1)^2 < 2^32.
IDK_INLINE uint vrsLumBits(uint tilePixels) { return (32u - vrsLog2(tilePixels)) / 2u; }
// Speed fraction bits: n * kVrsMaxSpeed * 2^bits <= 2^31.
IDK_INLINE uint vrsSpeedBits(uint tilePixels) { return 26u - vrsLog2(tilePixels); }

// The pixel's luminance (mean of RGB, as the original), NaN and negative -> 0, above kVrsMaxLuminance clamped.
IDK_INLINE float vrsLuminance(vec3 rgb) {
    IDK_PRECISE float sum = (rgb.x + rgb.y) + rgb.z;
    IDK_PRECISE float l = sum * (1.0f / 3.0f);
    if (!(l >= 0.0f)) return 0.0f;
    return l > kVrsMaxLuminance ? kVrsMaxLuminance : l;
}

// The pixel's speed in fixed point: floor(|velocity| * invFrameSeconds * 2^speedBits), NaN -> 0, clamped to
// kVrsMaxSpeed. Products and a sum (correctly rounded, no contraction), then the integer square root of their floor.
IDK_INLINE uint vrsSpeedFixed(vec2 velocity, float invFrameSeconds, uint tilePixels) {
    uint bits = vrsSpeedBits(tilePixels);
    IDK_PRECISE float k = invFrameSeconds * float(1u << bits);  // a power of two: exact
    IDK_PRECISE float vx = velocity.x * k;
    IDK_PRECISE float vy = velocity.y * k;
    IDK_PRECISE float sq = vx * vx + vy * vy;
    if (!(sq >= 0.0f)) return 0u;  // NaN
    uint maxFixed = uint(kVrsMaxSpeed) << bits;
    if (sq >= float(maxFixed) * float(maxFixed)) return maxFixed;  // also +inf; 2^(2 (5 + bits)) is exact
    uint64_t m = uint64_t(sq);  // floor (sq < 2^52)
    uint r = uint(sqrt(float(m)));  // an estimate (GPU sqrt is not correctly rounded), corrected in integers
    while (uint64_t(r) * uint64_t(r) > m) r--;
    while (uint64_t(r + 1u) * uint64_t(r + 1u) <= m) r++;
    return r;
}

// 2^(bits - e) where the tile maximum is f * 2^e, f in [0.5, 1): luminance * scale < 2^bits, exact.
IDK_INLINE float vrsLumScale(uint maxLumBits, uint bits) {
    int e = int((maxLumBits >> 23u) & 0xffu) - 126;
    return uintBitsToFloat(uint(127 + int(bits) - e) << 23u);
}

IDK_INLINE uint vrsLumFixed(float luminance, float scale) {
    IDK_PRECISE float q = luminance * scale;
    return uint(q);
}

// The tile's palette index: round(lerp(0,4, meanSpeed * speedFactor) + lerp(0,4, lumVarianceFactor / CV)) clamped
// to [0, 4] (round half up); 4x4 for dark tiles (mean luminance <= 0.001) and constant ones (CV = 0). n = pixels
// of the tile inside the image; maxLumBits = the tile's maximum sanitised luminance as float bits; s1, s2 = sums of
// the fixed-point luminance and its square; speedSum = sum of vrsSpeedFixed. With meanSpeed = speedSum 2^-bits / n
// and CV = sqrt(V) / s1, V = n s2 - s1^2 (exact in 64 bits), the value reaches the rounding threshold h (0.5, 1.5,
// 2.5, 3.5; the rate is how many it reaches) iff, multiplied by n, L >= D sqrt(V) with L = 4 lvf s1 n and
// D = n h - 4 sf speedSum 2^-bits: decided by signs and L^2 against D^2 V, without division or square root.
IDK_CONST(float, kVrsMinFactor, 1.0e-15f);  // smaller |factors| count as 0 (keeps every product above denormals)

IDK_INLINE uint vrsTileRate(uint n, uint tilePixels, uint maxLumBits, uint s1, uint s2, uint speedSum,
                            float speedFactor, float lumVarianceFactor) {
    const uint coarsest = kVrsRateCount - 1u;
    if (n == 0u || maxLumBits < floatBitsToUint(kVrsDarkLuminance)) return coarsest;  // max <= 0.001: dark
    float scale = vrsLumScale(maxLumBits, vrsLumBits(tilePixels));
    IDK_PRECISE float darkSum = kVrsDarkLuminance * float(n) * scale;
    if (float(s1) <= darkSum) return coarsest;  // mean <= 0.001
    uint64_t variance = uint64_t(n) * uint64_t(s2) - uint64_t(s1) * uint64_t(s1);  // n^2 times the variance
    if (variance == uint64_t(0)) return coarsest;  // constant tile: CV = 0, the term is infinite
    float sf = abs(speedFactor) < kVrsMinFactor ? 0.0f : speedFactor;
    float lf = abs(lumVarianceFactor) < kVrsMinFactor ? 0.0f : lumVarianceFactor;
    float speedStep = uintBitsToFloat(uint(127 - int(vrsSpeedBits(tilePixels))) << 23u);  // 2^-bits
    IDK_PRECISE float speedN = (4.0f * sf) * (float(speedSum) * speedStep);  // the speed term times n
    IDK_PRECISE float l = ((4.0f * lf) * float(s1)) * float(n);
    IDK_PRECISE float l2 = l * l;
    float v = float(variance);
    uint rate = 0u;
    for (uint k = 0u; k < coarsest; ++k) {
        IDK_PRECISE float d = float(n) * (float(k) + 0.5f) - speedN;
        IDK_PRECISE float d2v = (d * d) * v;
        bool reached = l >= 0.0f ? (d <= 0.0f || l2 >= d2v) : (d <= 0.0f && l2 <= d2v);
        rate += reached ? 1u : 0u;
    }
    return rate;
}

// The palette index as a VK_KHR_fragment_shading_rate attachment texel: (log2(width) << 2) | log2(height) of its
// cell (spec, "Attachment Fragment Shading Rate"); larger indices are clamped to 4x4. The NV shading-rate image
// stores the palette index itself (the palette is bound in this order: vk/shading_rate.cpp).
IDK_INLINE uint vrsKhrRateTexel(uint rate) {
    uvec2 cell = vrsCellSize(rate < kVrsRateCount ? rate : kVrsRateCount - 1u);
    return (vrsLog2(cell.x) << 2u) | vrsLog2(cell.y);
}

IDK_GPU_END
#endif
