// pt_albedo_layout.h: the grids of the precomputed directional-albedo tables (pt_albedo_tables.h, written by
// `idk_albedo_tables` from engine/pathtrace/albedo_integrator.cpp) and the maps between table nodes and
// (cos theta, roughness, IOR), one source for the C++ integrator and the GLSL/C++ lookups (pt_energy.h).
//   metal       E(mu, r): albedo of the GGX reflection lobe with F = 1 (kPtAlbedoMu x kPtAlbedoRough nodes)
//   metalAvg    Eavg(r) = 2 * integral E(mu, r) mu dmu, of the piecewise-linear E the lookup reads
//   dielectric  E(mu, r, ior, side): reflection + refraction of a rough dielectric interface (energy, no eta^2
//               radiance factor), white; side 0: light arrives from outside (eta = ior), 1: inside (eta = 1/ior)
//   sheen       E(mu, r): albedo of the KHR_materials_sheen Charlie lobe with sheen colour 1
//   msBins      [r][k]: probability of cos theta bin k (kPtAlbedoMsBins equal bins of [0, 1]) under the density
//               ~ (1 - E(mu, r)) mu of the multiple-scattering lobe (pt_energy.h samples it)
//   anisoMetal  [s][r][q][mu]: albedo of the anisotropic GGX reflection lobe (KHR_materials_anisotropy,
//               pt_anisotropy.h) with F = 1, for view (sin theta q, sin theta sqrt(1 - q^2), mu) in the frame of the
//               anisotropy direction: q = |cos phi| of the view's azimuth from it, r the perceptual base roughness
//               (alpha_b = r^2), s the strength (alpha_t = mix(alpha_b, 1, s^2)). E is even in x and y (D and
//               Lambda see x^2 and y^2), so q in [0, 1] covers every azimuth; it is nodal in q = |cos phi| rather
//               than phi or cos^2 phi because the projected alpha Lambda sees grows like alpha_t q across a narrow
//               lobe (a linear interpolant in q errs 5x less than one in cos^2 phi at equal nodes). Grid 32 x 8 x 16
//               x 16 (256 KB): random (mu >= 0.12, q, r, s) points are within 0.74% (mean 0.06%) of the integrator,
//               1.0% down to mu 0.05; 16 or 24 roughness or strength nodes gain < 0.1%. Indexed by (r, s), the
//               glTF parameters, the table spans exactly the reachable alphas (alpha_t >= alpha_b)
//   anisoAvg    [s][r]: Eavg = (1 / pi) integral E cos over the hemisphere, of the interpolant the lookup reads
//   specular    E(mu, r, ior): albedo of GGX reflection alone with the exact dielectric Fresnel, light from outside
//               (eta = ior); the opaque dielectric's diffuse weight is built on it (pt_bsdf_frame.h)
//   specularAvg Eavg(r, ior) of the specular table, like metalAvg
// Nodes: mu_i = max(i / (N - 1), kPtAlbedoMinMu); roughness r_j = j / (N - 1) (perceptual, alpha = r^2), and
// likewise |cos phi| and strength;
// IOR axis x_k = 0.6 k / (N - 1) with x = (ior - 1) / (ior + 1) (ior 1 .. 4, the BSDF's clamp).
#ifndef IDK_PT_ALBEDO_LAYOUT_H
#define IDK_PT_ALBEDO_LAYOUT_H
#include "pt_common.h"

IDK_GPU_BEGIN

IDK_CONST(uint, kPtAlbedoMu, 32u);     // metal and sheen tables: cos theta nodes
IDK_CONST(uint, kPtAlbedoRough, 32u);  // metal and sheen tables: roughness nodes
IDK_CONST(uint, kPtAlbedoDielMu, 32u);  // dielectric table: cos theta, roughness and IOR nodes
IDK_CONST(uint, kPtAlbedoDielRough, 16u);
IDK_CONST(uint, kPtAlbedoDielIor, 16u);
IDK_CONST(uint, kPtAlbedoSpecRough, 32u);  // specular table: roughness and IOR nodes (cos theta: kPtAlbedoDielMu)
IDK_CONST(uint, kPtAlbedoSpecIor, 16u);
IDK_CONST(uint, kPtAlbedoMsBins, 31u);  // = kPtAlbedoMu - 1: one bin per cell of the metal table
IDK_CONST(uint, kPtAlbedoAnisoMu, 32u);  // anisotropic metal table: cos theta, |cos phi|, roughness, strength
IDK_CONST(uint, kPtAlbedoAnisoAz, 8u);
IDK_CONST(uint, kPtAlbedoAnisoRough, 16u);
IDK_CONST(uint, kPtAlbedoAnisoStrength, 16u);
IDK_CONST(float, kPtAlbedoMinMu, 1.0e-3f);
IDK_CONST(float, kPtAlbedoMaxIorX, 0.6f);  // x = (ior - 1) / (ior + 1) at ior 4

IDK_INLINE float ptAlbedoNodeMu(uint i, uint n) { return max(float(i) / float(n - 1u), kPtAlbedoMinMu); }
IDK_INLINE float ptAlbedoNodeRough(uint j, uint n) { return float(j) / float(n - 1u); }  // also |cos phi|, strength
IDK_INLINE float ptAlbedoNodeIor(uint k, uint n) {
    float x = kPtAlbedoMaxIorX * float(k) / float(n - 1u);
    return (1.0f + x) / (1.0f - x);
}
IDK_INLINE float ptAlbedoIorCoord(float ior) {  // continuous node coordinate in [0, 1]
    float x = (ior - 1.0f) / (ior + 1.0f);
    return clamp(x / kPtAlbedoMaxIorX, 0.0f, 1.0f);
}

IDK_GPU_END

#endif
