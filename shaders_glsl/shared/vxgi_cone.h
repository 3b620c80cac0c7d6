// vxgi_cone.h: the voxel cone tracer's maths, ONE source compiled as GLSL (include/cone_trace.glsl,
// vxgi/cone_trace.comp) and as C++ (the CPU cone tracer tests/support/vxgi_cone_oracle.cpp): the diffuse cone set,
// the specular aperture, the march (level choice, receiver-plane clamp, step, grid bounds), front-to-back
// compositing and the rule that combines the directional volumes. Only the texture fetches differ between the
// two sides. Ports the loop of IDKEngine's include/TraceCone.glsl, without its GIBoost / GISkyBoxBoost factors.
//
// The march, for a cone from the receiver point P (geometric normal g) along `dir` with half-angle tangent t:
//  * a sample at distance d has diameter D = 2 t d; its level is lod = log2(D / v) (v the voxel size), so the
//    sampled cell c = 2^lod v matches the cone's width;
//  * receiver-plane clamp: a trilinear fetch at level L reads cells whose centres lie within c of the sample, and
//    the receiver's own cell reaches c / 2 above its plane, so a sample at height h = (x - P).g above the plane
//    sees the receiver unless h >= 1.5 c. The level is clamped to that (for fractional levels the upper level's
//    cell, twice as big, counts: lod <= log2(h / 3v); level 0 alone down to h = 1.5 v, where the march starts).
//    Without it the ring cones at 52 degrees, whose width grows faster than their height, see the surface they
//    start from (a white floor under a uniform sky rendered 0.28 instead of 0.5);
//  * the level is also capped at kVxgiMaxLodBelowRoot under the root (coarser cells blur a room into one cell and
//    carry light through walls); past the cap the cone keeps its cell and marches on. The cap is not what keeps the
//    Cornell box's indirect error at 0.296 (measured with BM_VxgiCornell/N, relative L1 against the depth-matched
//    path tracer; the panel's and the point light's parts in brackets): cap N / 8 (kept) 0.296 (0.251 / 0.461) at
//    64^3; N / 4: 0.283 (0.282 / 0.392) at 64^3, 0.285 (0.288 / 0.388) at 128^3 (N / 8: 0.295); N / 2 and no cap at
//    all (the receiver-plane clamp alone): 0.284 (0.287 / 0.391) at 64^3. So at most 0.013 of it is the cap's, and
//    wider cells trade the panel's part for the point light's (and both parts are too dark as a whole, which wider
//    cells do not mend: the summed indirect light over the reference's, indirect_ratio, is 0.834 / 0.758 with the
//    cap N / 8, 0.774 / 0.782 with N / 4, 0.768 / 0.797 without a cap). N / 4 makes the closed room
//    (tests/gpu/vxgi/vxgi_frame_test.cpp) 8.1% darker instead of 10.6%, but its thin wall leaks 0.175 (bound 0.06).
//    An occupancy gate, tried and not kept: a sample widens past the cap by the weight 1 - S / tau, S the coverages
//    at the wider level seen along each axis times 1 - dir_a^2 (the share of a surface beside the travel, which a
//    wide cell averages across; at tau 0.3 all or nothing): tau 0.3: room 9.2% darker, thin wall 0.0555, but the
//    one-voxel wall of tests/conformance/vxgi/footprint_cone_test.cpp leaks 0.094 / 0.076 / 0.144 of the mirror
//    point (1 / 4 / 7 footprint cones; same grid with the cap: 0.064 / 0.047 / 0.115, bound 0.13): a wide cell's
//    trilinear fetch reads the panel's cell across a wall met head on before the wall's coverage is composited; tau
//    0.2: room 10.4%, 7 cones leak 0.136; tau 0.1: room 10.6%, Cornell 0.296. Widening only in empty space (the
//    three coverages below 0.02 together): the same error, and no faster (cone trace 412 ms against 398 ms at
//    64^3). The receiver-plane clamp's h >= 1.5 c is near its best: 1.0 c gives 0.312, 2.25 c 0.300. Nor is it the
//    march's sampling: step 0.25 instead of 0.5 gives 0.2955 (ratios 0.836 / 0.759). The edge opacity
//    (vxgiVoxelTowards) moves it: 0.25 instead of 0.5 gives 0.281 (0.860 / 0.792), the closed room 7.3% darker, but
//    the thin wall 0.0791 (bound 0.06) and the one-voxel wall 0.154 / 0.130 / 0.173 (bound 0.13);
//  * a sample's alpha is the coverage of one cell of size c along the march, so a step of length s takes
//    1 - (1 - alpha)^(s / c) (Beer-Lambert over the cell), with s = c * stepFactor;
//  * the march ends when opacity reaches 0.99 or the sample's cell leaves the grid; the sky fills the rest.
// The clamp and the cap keep a cone's sampled cell at 0.2..0.3 of its width, so the diffuse set traces each of its
// cones as footprint cones (vxgiFootprintCone): narrower cones tiling it, whose cells come closer to their width.
//
// Common-subset rules as pt_sampling.h: no swizzles longer than one component, IDK_OUT / IDK_INOUT, float
// literals with f, no overloading.
#ifndef IDK_VXGI_CONE_H
#define IDK_VXGI_CONE_H
#include "interop.h"

#ifdef __cplusplus
#include <cmath>
#endif

IDK_GPU_BEGIN

#ifdef __cplusplus
using glm::abs;
using glm::clamp;
using glm::cross;
using glm::dot;
using glm::exp2;
using glm::log2;
using glm::max;
using glm::min;
using glm::normalize;
using glm::pow;
using std::atan;
using std::cos;
using std::sin;
using std::tan;
#endif

IDK_CONST(float, kVxgiCapTan, 0.57735027f);   // the cap cone: polar angles 0..30 degrees (1/4 of cos-weighted)
IDK_CONST(float, kVxgiRingSin, 0.79056942f);  // ring cones at sin^2 = 0.625: the 30..90 ring's cos-weighted median
IDK_CONST(float, kVxgiRingCos, 0.61237244f);
IDK_CONST(float, kVxgiMaxSpecularAngle, 0.5f);    // widest specular cone half-angle (radians), see vxgiSpecularCone
IDK_CONST(float, kVxgiMaxLodBelowRoot, 3.0f);     // lod <= log2(N) - 3: cells of at most N / 8 voxels
IDK_CONST(float, kVxgiOpaque, 0.99f);
IDK_CONST(float, kVxgiEdgeOpacity, 0.5f);         // see vxgiVoxelTowards

// An orthonormal tangent frame around n (the cone set's azimuth origin).
IDK_INLINE void vxgiTangents(vec3 n, IDK_OUT(vec3) t, IDK_OUT(vec3) b) {
    t = normalize(abs(n.y) < 0.9f ? cross(n, vec3(0.0f, 1.0f, 0.0f)) : cross(n, vec3(1.0f, 0.0f, 0.0f)));
    b = cross(n, t);
}

// Ring cone half-angle tangent: each of `ringCones` cones spans its azimuth sector (half the sector's width at
// the ring's polar angle), at most the cap's.
IDK_INLINE float vxgiRingTan(uint ringCones) {
    return min(tan(0.5f * 6.28318530717959f * kVxgiRingSin / float(ringCones)), kVxgiCapTan);
}

// Axis of ring cone i of `ringCones` around n; its weight in the irradiance sum is 0.75 / ringCones (the cap's 0.25).
IDK_INLINE vec3 vxgiRingDirection(uint i, uint ringCones, vec3 n, vec3 t, vec3 b) {
    float phi = 6.28318530717959f * (float(i) + 0.5f) / float(ringCones);
    return kVxgiRingSin * (cos(phi) * t + sin(phi) * b) + kVxgiRingCos * n;
}

// Footprint cones: each cone of the diffuse set is traced as `split` (1, 4 or 7) narrower cones that tile its
// solid angle, each with its own march and transmittance, averaged: a sample's cell is held to h / 3 by the
// receiver-plane clamp (and to the level cap), so one wide cone samples a tube 0.2..0.3 of its width and hits or
// misses a small bright source as a whole; narrower cones keep their cell near their own width and together cover
// the footprint, while each one's opacity still composites front to back along its own axis, so a sample never
// sees past an occluder the way one cell spread across the footprint with a shared transmittance would.
// Layout (angles as fractions of the parent half-angle a, equal solid angles): 4: half-angle a / 2, axes at
// 0.60 a (the centroids of four 90 degree sectors); 7: half-angle a / sqrt(7), one along the axis and six at
// 0.70 a (the centroids of the annulus' six sectors around the central disc).
IDK_INLINE vec3 vxgiFootprintCone(vec3 dir, float tanHalf, uint j, uint split, IDK_OUT(float) subTan) {
    float a = atan(tanHalf);
    if (split <= 1u) {
        subTan = tanHalf;
        return dir;
    }
    float offset = split == 4u ? 0.6f * a : 0.7f * a;
    subTan = tan(split == 4u ? 0.5f * a : 0.37796447f * a);
    if (split != 4u) {
        if (j == 0u) return dir;
        j = j - 1u;
    }
    float around = split == 4u ? 4.0f : 6.0f;
    float phi = 6.28318530717959f * (float(j) + 0.5f) / around;
    vec3 u, v;
    vxgiTangents(dir, u, v);
    return cos(offset) * dir + sin(offset) * (cos(phi) * u + sin(phi) * v);
}

// Number of cones the diffuse set traces: (1 cap + ringCones) * split.
IDK_INLINE uint vxgiDiffuseConeCount(uint ringCones, uint split) { return (1u + ringCones) * max(split, 1u); }

// Cone k of the diffuse set (0 <= k < vxgiDiffuseConeCount): its axis, half-angle tangent and weight in
// E / pi = sum(w_k L_k) (the cap 0.25, each ring cone 0.75 / ringCones, shared equally by its footprint cones).
IDK_INLINE float vxgiDiffuseCone(uint k, uint ringCones, uint split, vec3 n, vec3 t, vec3 b, IDK_OUT(vec3) dir,
                                 IDK_OUT(float) tanHalf) {
    uint s = max(split, 1u);
    uint parent = k / s;
    vec3 axis = parent == 0u ? n : vxgiRingDirection(parent - 1u, ringCones, n, t, b);
    float parentTan = parent == 0u ? kVxgiCapTan : vxgiRingTan(ringCones);
    dir = vxgiFootprintCone(axis, parentTan, k - parent * s, s, tanHalf);
    return (parent == 0u ? 0.25f : 0.75f / float(ringCones)) / float(s);
}

// The specular cone of a GGX lobe of roughness r (alpha = r^2): half-angle 2 atan(0.64 alpha) as environmentLod,
// clamped to kVxgiMaxSpecularAngle; returns the weight of the diffuse irradiance / pi that replaces the cone's
// radiance for lobes wider than the clamp (0 below it, 1 at a 1.2 radian lobe): a wide cone's samples grow coarse
// at once and see the receiver's neighbourhood as one blur, which the cosine-weighted diffuse set resolves better.
IDK_INLINE float vxgiSpecularCone(float roughness, IDK_OUT(float) tanHalf) {
    float alpha = max(roughness * roughness, 1e-3f);
    float angle = 2.0f * atan(0.64f * alpha);
    tanHalf = tan(min(angle, kVxgiMaxSpecularAngle));
    return clamp((angle - kVxgiMaxSpecularAngle) / (1.2f - kVxgiMaxSpecularAngle), 0.0f, 1.0f);
}

struct VxgiMarch {
    vec3 origin;    // the receiver point P
    vec3 plane;     // its geometric normal
    vec3 dir;       // the cone's unit axis
    float tanHalf;  // tangent of its half-angle
    float dist;     // distance of the next sample along dir
    vec3 radiance;  // gathered so far (premultiplied)
    float opacity;
    // Set by vxgiMarchNext for the current sample:
    vec3 uvw;   // grid coordinates [0, 1]^3
    float lod;  // grid level (of the directional volumes; 0: voxels)
    float cell; // world size of the level's cell
};

IDK_INLINE VxgiMarch vxgiMarchBegin(vec3 origin, vec3 plane, vec3 dir, float tanHalf, float voxelSize) {
    VxgiMarch m;
    m.origin = origin;
    m.plane = plane;
    m.dir = dir;
    m.tanHalf = tanHalf;
    // The first sample at height 1.5 v (the level-0 fetch then misses the receiver's voxels); grazing cones are
    // started no farther than 6 v.
    m.dist = 1.5f * voxelSize / max(dot(dir, plane), 0.25f);
    m.radiance = vec3(0.0f);
    m.opacity = 0.0f;
    m.uvw = vec3(0.0f);
    m.lod = 0.0f;
    m.cell = voxelSize;
    return m;
}

// Places the next sample; false when the march is over (opaque, or the sample's cell is outside the grid).
IDK_INLINE bool vxgiMarchNext(IDK_INOUT(VxgiMarch) m, vec3 gridMin, float voxelSize, uint gridSize, float maxLod) {
    if (m.opacity >= kVxgiOpaque) return false;
    float diameter = max(voxelSize, 2.0f * m.tanHalf * m.dist);
    float lod = log2(diameter / voxelSize);
    float h = m.dist * dot(m.dir, m.plane);
    float clampLod = h < 3.0f * voxelSize ? 0.0f : log2(h / (3.0f * voxelSize));
    lod = clamp(min(lod, clampLod), 0.0f, max(maxLod - kVxgiMaxLodBelowRoot, 0.0f));
    m.lod = lod;
    m.cell = voxelSize * exp2(lod);
    float gridWorld = voxelSize * float(gridSize);
    vec3 x = m.origin + m.dir * m.dist;
    m.uvw = (x - gridMin) / gridWorld;
    float margin = m.cell / gridWorld;  // a sample within one cell of the grid still reads its edge cells
    return m.uvw.x >= -margin && m.uvw.y >= -margin && m.uvw.z >= -margin && m.uvw.x <= 1.0f + margin &&
           m.uvw.y <= 1.0f + margin && m.uvw.z <= 1.0f + margin;
}

// Composites the current sample (premultiplied rgb, coverage a) and advances the march.
IDK_INLINE void vxgiMarchTake(IDK_INOUT(VxgiMarch) m, vec4 s, float stepFactor) {
    float step = m.cell * stepFactor;
    if (s.w > 0.0f) {
        float a = 1.0f - pow(max(1.0f - min(s.w, 1.0f), 0.0f), stepFactor);
        m.radiance = m.radiance + (1.0f - m.opacity) * vec3(s.x, s.y, s.z) * (a / s.w);
        m.opacity = m.opacity + (1.0f - m.opacity) * a;
    }
    m.dist = m.dist + step;
}

// The directional volume (0..5: +x -x +y -y +z -z) seen travelling along `dir` on `axis`.
IDK_INLINE uint vxgiDirectionIndex(vec3 dir, uint axis) {
    float d = axis == 0u ? dir.x : (axis == 1u ? dir.y : dir.z);
    return 2u * axis + (d >= 0.0f ? 0u : 1u);
}

// Combines the three directional fetches (sx from the x volume facing the travel, ...) weighted by |dir|: a thin
// surface facing axis a covers |dir_a| of what it covers seen straight along a (its projected area); where the
// weights add up to more than full coverage (solid blocks) the sample is scaled back to opacity 1.
IDK_INLINE vec4 vxgiCombine(vec3 dir, vec4 sx, vec4 sy, vec4 sz) {
    vec4 d = abs(dir.x) * sx + abs(dir.y) * sy + abs(dir.z) * sz;
    if (d.w > 1.0f) d = d / d.w;
    return d;
}

// Level 0 of directional volume k (0..5: travelling along +x -x +y -y +z -z) from a merged voxel: `voxel` its
// radiance (rgb) and coverage (a), `facing` its mean facing (vxgi_types.h: the radiating side's normal s, the
// other side's share w). Seen along axis a a surface covers |s_a| of the voxel (its projected area) and shows its
// radiance only from the side it radiates to: travelling along +a meets the faces whose normal points to -a. So
// a one-sided emitter does not glow backwards, a wall lit on one side does not light the room behind it, and a
// panel seen edge-on shows little of itself, where a voxel radiating equally in all directions does all three
// (the closed room of tests/gpu/vxgi/vxgi_frame_test.cpp was 32% too bright with that, 7% with this).
// The edge share: the projected area alone makes a thin wall crossed obliquely a Beer-Lambert medium of
// opacity |s_a| per cell, which the march's compositing passes e^-1 of however long it crosses it (the split
// room's dark half then got 24% of the lit half's light instead of 5%). So a surface also covers
// kVxgiEdgeOpacity of the part it does not face, standing for the rays that cross its plane at grazing angles
// inside the voxel, which meet either side equally: they show the mean of both sides' radiance.
// Measured (Cornell box 128x128, indirect rel. L1 vs the depth-3 path tracer at 64/128/256^3 voxels; closed room
// mean error; split room dark / lit): edge 0.5: 0.451/0.450/0.502, +7.4%, 0.063. Edge 0.25: 0.439/0.439/0.497,
// +9.5%, 0.095. Edge 0: 0.417/0.412/0.486, +10.3%, 0.236. Isotropic level 0 (opacity 1 from every side):
// 0.455/0.452/0.506. The edge only trades the Cornell box against the room and the wall (1 + 12 cones:
// 0.418/0.416/0.471). The Cornell error comes from elsewhere, measured against exact values (CPU ray casts over
// the scene's triangles, the read-back grid, this file's march on the CPU): (1) the light panel, which carries
// most of the one-bounce light (its emission and the point light 1 cm below it), lies 0.5 mm under the ceiling,
// in the same voxel layer, and the voxels average it with the ceiling behind it (shadowed): they hold 0.53 of
// its radiance (the walls' voxels: 0.98..0.99, tests/gpu/vxgi/vxgi_cornell_injection_test.cpp); (2) the
// receiver-plane clamp (c <= h / 3) and the level cap leave every cone sampling a tube 0.2..0.3 of its width, so
// the small bright panel is either hit (too bright) or missed (floor and block-top points at 0.05..0.1 of the
// exact irradiance, where the same 1 + 5 cone set integrated exactly is within -31%..+17%). Indirect rel. L1 at
// 64^3 against the bench's per-source reference: 0.440; panel voxels holding the panel alone (experiment): 0.497;
// 16 samples across each cone's footprint: 0.399 (cone trace 20x slower); both: 0.346. Footprint cones (each cone
// traced as 4 narrower ones with their own transmittance, the default): 0.330/0.328/0.294 at 64/128/256^3.
IDK_INLINE vec4 vxgiVoxelTowards(vec4 voxel, vec4 facing, uint k) {
    uint axis = k / 2u;
    float s = axis == 0u ? facing.x : (axis == 1u ? facing.y : facing.z);
    if ((k & 1u) == 1u) s = -s;  // now positive when the radiating side faces the travel (is seen from behind)
    float edge = kVxgiEdgeOpacity * (1.0f - abs(s));
    float shown = max(-s, 0.0f) + facing.w * max(s, 0.0f) + edge * 0.5f * (1.0f + facing.w);
    float opacity = abs(s) + edge;
    return vec4(vec3(voxel.x, voxel.y, voxel.z) * (voxel.w * shown), voxel.w * opacity);
}

IDK_GPU_END

#endif
