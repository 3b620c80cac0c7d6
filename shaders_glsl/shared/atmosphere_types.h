// atmosphere_types.h: the single-scattering sky (engine/render/atmosphere.cpp, atmosphere/bake.comp.glsl): the
// medium, the sun and the quadrature the GPU bake and its C++ twin share. Units: metres, scattering per metre,
// radiance per unit sun irradiance times sunIntensity. Ports the model of IDKEngine's AtmosphericScatterer
// (Rayleigh + Mie single scattering, exponential density, reference section 2 "atmosphere").
#ifndef IDK_ATMOSPHERE_TYPES_H
#define IDK_ATMOSPHERE_TYPES_H
#include "interop.h"

IDK_GPU_BEGIN

IDK_CONST(uint, kAtmosphereGroupSize, 8u);

struct GpuAtmosphere {
    vec3 toSun;              // unit, world (y up)
    float sunIntensity;      // irradiance of the sun at the top of the atmosphere
    vec3 rayleighScattering; // beta_R at sea level (per metre, RGB)
    float rayleighHeight;    // density scale height (m)
    float mieScattering;     // beta_M at sea level (per metre)
    float mieExtinction;     // beta_M / single-scattering albedo
    float mieHeight;         // density scale height (m)
    float mieG;              // Henyey-Greenstein asymmetry
    float planetRadius;      // m
    float atmosphereRadius;  // m
    float viewHeight;        // eye altitude above sea level (m)
    uint viewSamples;        // midpoint quadrature steps along the view ray
    uint lightSamples;       // ... along each sun ray
    uint width;              // equirectangular output size
    uint height;
    uint pad;
    DeviceAddress target;    // vec4[width * height], row 0 = up (environment mapping)
};
IDK_GPU_SIZE(GpuAtmosphere, 88);

IDK_GPU_END
#endif
