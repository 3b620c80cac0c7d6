// plastic_weight.hpp: the albedo-scaled weight of the shared BSDF's Lambert lobes (shared/pt_bsdf_frame.h)
// written out by hand in double for the by-hand tests, from the formula and the committed tables (which
// energy_test.cpp checks against the integrator): W(mu_o, mu_i) = (1 - Es(mu_o)) (1 - Es(mu_i)) / (1 - Es_avg),
// Es the albedo of the dielectric reflection lobe with KHR_materials_specular's weight `specular` and strongest
// f0' (min(f0 specularColor, 1)) and its Kulla-Conty multiple scattering.
#pragma once
#include <algorithm>

#include "shared/pt_sampling.h"

namespace idk::test {

struct PlasticSpec {
    float roughness;
    double ior;
    double specular = 1.0;
    double f0Max = -1.0;  // < 0: the IOR's own f0
};

inline double plasticSpecAlbedo(const PlasticSpec& p, double mu, bool average) {
    const double f0 = ((p.ior - 1.0) / (p.ior + 1.0)) * ((p.ior - 1.0) / (p.ior + 1.0));
    const double f0s = p.f0Max < 0.0 ? f0 : p.f0Max;
    const double favgExact = (p.ior - 1.0) / (4.08567 + 1.00071 * p.ior);  // Kulla-Conty's fit
    const double favg = p.specular * (f0s + (1.0 - f0s) * (favgExact - f0) / (1.0 - f0));
    const double eavg = gpu::ptAlbedoMetalAvg(p.roughness);
    const double fms = favg * favg * eavg / (1.0 - favg * (1.0 - eavg));
    const double em = average ? eavg : gpu::ptAlbedoMetal(float(mu), p.roughness);
    const double er = average ? gpu::ptAlbedoSpecularAvg(p.roughness, float(p.ior))
                              : gpu::ptAlbedoSpecular(float(mu), p.roughness, float(p.ior));
    return p.specular * (f0s * em + (1.0 - f0s) * (er - f0 * em) / (1.0 - f0)) + fms * (1.0 - em);
}

inline double plasticDiffuseWeight(const PlasticSpec& p, double muO, double muI) {
    return (1.0 - plasticSpecAlbedo(p, muO, false)) * (1.0 - plasticSpecAlbedo(p, muI, false)) /
           (1.0 - plasticSpecAlbedo(p, 0.0, true));
}

}  // namespace idk::test
