// albedo_integrator.hpp: directional albedos of the path tracer's single-scattering lobes (shared/pt_microfacet.h,
// shared/pt_sheen.h), integrated on the CPU with deterministic stratified quadrature, and the tables the energy
// compensation reads (shared/pt_albedo_tables.h, written by `idk_albedo_tables`; a unit test recomputes them).
#pragma once
#include <string>
#include <vector>

namespace idk::pathtrace {

// Albedo of GGX reflection with F = 1 at cos theta mu, perceptual roughness r: the mean of G2 / G1 over
// visible-normal samples (strata x strata cells) whose mirror direction is above the horizon.
double ggxReflectionAlbedo(float mu, float roughness, int strata);

// Albedo of the anisotropic GGX reflection (KHR_materials_anisotropy, F = 1) for the view at cos theta mu and
// azimuth |cos phi| = q from the anisotropy direction, perceptual base roughness r and strength s (the alphas of
// pt_anisotropy.h); the same quadrature as ggxReflectionAlbedo.
double ggxAnisoReflectionAlbedo(float mu, float q, float roughness, float strength, int strata);

// Reflection + refraction of a rough dielectric interface (white, energy: no eta^2 radiance factor) for light
// leaving at mu on the side where the far medium has relative IOR eta (eta = ior outside, 1 / ior inside).
double ggxDielectricAlbedo(float mu, float roughness, float eta, int strata);

// Reflection alone of that interface (light from outside, eta >= 1): the GGX lobe with the exact Fresnel term.
double ggxDielectricReflectionAlbedo(float mu, float roughness, float eta, int strata);

// Albedo of the Charlie sheen lobe (colour 1) at mu and sheen roughness r, midpoint rule over the hemisphere.
double sheenAlbedo(float mu, float roughness, int strata);

struct AlbedoTables {
    std::vector<float> metal;       // [r][mu], kPtAlbedoRough x kPtAlbedoMu
    std::vector<float> metalAvg;    // [r]
    std::vector<float> dielectric;  // [side][ior][r][mu]
    std::vector<float> sheen;       // [r][mu]
    std::vector<float> msBins;      // [r][bin]
    std::vector<float> anisoMetal;  // [s][r][q][mu], kPtAlbedoAnisoStrength x Rough x Az x Mu
    std::vector<float> anisoAvg;    // [s][r]
    std::vector<float> specular;    // [ior][r][mu], kPtAlbedoSpecIor x kPtAlbedoSpecRough x kPtAlbedoDielMu
    std::vector<float> specularAvg; // [ior][r]
};

// Every table at its nodes (pt_albedo_layout.h). strata: the quadrature of each entry (the committed tables use
// kAlbedoTableStrata).
AlbedoTables computeAlbedoTables(int strata);
inline constexpr int kAlbedoTableStrata = 48;

// The text of shared/pt_albedo_tables.h for these tables (C++ arrays, their offsets in the packed buffer).
std::string albedoTablesHeader(const AlbedoTables& tables);

// The committed tables packed as the GPU reads them (kPtAlbedoTableFloats floats, each at its k*Offset):
// albedo_data.cpp. Upload once and give the shaders its address (pt_energy.h's gPtAlbedoTables).
std::vector<float> albedoTableData();

}  // namespace idk::pathtrace
