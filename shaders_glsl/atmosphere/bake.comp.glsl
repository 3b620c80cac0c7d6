#version 460
// bake.comp.glsl: the atmosphere's sky radiance into an equirectangular map (one invocation per texel, the
// environment's mapping: u = 0.5 looks down -Z, v = 0 up): single scattering of sunlight by Rayleigh and Mie
// particles with exponential density, midpoint quadrature along the view ray (to the top of the atmosphere or the
// ground; steps growing with distance) and along the sun ray from each sample (zero where the planet blocks the sun). engine/render/
// atmosphere.cpp holds the C++ twin the conformance test integrates finely. Ports IDKEngine's
// AtmosphericScattering compute shader (reference: atmosphere), baked only when the sun moves.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#include "atmosphere_types.h"

layout(local_size_x = kAtmosphereGroupSize, local_size_y = kAtmosphereGroupSize) in;
layout(push_constant, scalar) uniform Push { GpuAtmosphere a; };
layout(buffer_reference, scalar, buffer_reference_align = 4) writeonly buffer OutRef { vec4 v[]; };

const float kPi = 3.14159265358979;

// Distance along unit d from o to the sphere of radius r around the origin: (near, far); far < 0: no hit.
vec2 sphereHit(vec3 o, vec3 d, float r) {
    // c = |o|^2 - r^2 as (|o| - r)(|o| + r): with r ~ 6.4e6 m the plain difference of squares loses the
    // altitude to float rounding (an ulp of 4e13 is ~4e6).
    float lo = length(o);
    float b = dot(o, d), c = (lo - r) * (lo + r);
    float disc = b * b - c;
    if (disc < 0.0) return vec2(-1.0);
    float s = sqrt(disc);
    return vec2(-b - s, -b + s);
}

vec2 density(vec3 p) {  // (Rayleigh, Mie) relative density at p
    float h = max(length(p) - a.planetRadius, 0.0);
    return exp(-vec2(h / a.rayleighHeight, h / a.mieHeight));
}

void main() {
    uvec2 texel = gl_GlobalInvocationID.xy;
    if (texel.x >= a.width || texel.y >= a.height) return;
    vec2 uv = (vec2(texel) + 0.5) / vec2(a.width, a.height);
    float phi = 2.0 * kPi * (uv.x - 0.5), theta = kPi * uv.y;
    vec3 d = vec3(sin(theta) * sin(phi), cos(theta), -sin(theta) * cos(phi));

    vec3 o = vec3(0.0, a.planetRadius + a.viewHeight, 0.0);
    float tEnd = sphereHit(o, d, a.atmosphereRadius).y;
    vec2 ground = sphereHit(o, d, a.planetRadius);
    if (ground.x > 0.0) tEnd = ground.x;  // the view ray ends on the ground
    vec3 rayleigh = vec3(0.0), mie = vec3(0.0);
    vec2 depthView = vec2(0.0);  // optical depth (Rayleigh, Mie density integrals) from the eye
    // Midpoint rule in s = sqrt(t / tEnd): t = tEnd s^2 puts the samples densest near the eye, where the air is
    // densest for every ray that leaves the ground (half the error of uniform steps at the same count).
    float len = max(tEnd, 0.0);
    float n = float(a.viewSamples);
    for (uint i = 0u; i < a.viewSamples; ++i) {
        float s = (float(i) + 0.5) / n;
        vec3 p = o + d * (len * s * s);
        vec2 rho = density(p) * (len * 2.0 * s / n);
        depthView += rho * 0.5;  // up to the sample's midpoint
        if (sphereHit(p, a.toSun, a.planetRadius).x <= 0.0) {  // the sun is above this sample's horizon
            float ls = sphereHit(p, a.toSun, a.atmosphereRadius).y;  // the same spacing along the sun ray
            float m = float(a.lightSamples);
            vec2 depthSun = vec2(0.0);
            for (uint j = 0u; j < a.lightSamples; ++j) {
                float u = (float(j) + 0.5) / m;
                depthSun += density(p + a.toSun * (ls * u * u)) * (ls * 2.0 * u / m);
            }
            vec2 total = depthView + depthSun;
            vec3 tau = a.rayleighScattering * total.x + vec3(a.mieExtinction * total.y);
            vec3 transmittance = exp(-tau);
            rayleigh += transmittance * rho.x;
            mie += transmittance * rho.y;
        }
        depthView += rho * 0.5;
    }
    float mu = dot(d, a.toSun);
    float phaseR = 3.0 / (16.0 * kPi) * (1.0 + mu * mu);
    float g = a.mieG;
    float phaseM = (1.0 - g * g) / (4.0 * kPi * pow(1.0 + g * g - 2.0 * g * mu, 1.5));
    vec3 radiance = a.sunIntensity * (rayleigh * a.rayleighScattering * phaseR + mie * a.mieScattering * phaseM);
    OutRef(a.target).v[texel.y * a.width + texel.x] = vec4(radiance, 1.0);
}
