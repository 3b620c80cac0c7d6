// pt_sampling.h: the path tracer's sampling maths, ONE source compiled as C++ (namespace idk::gpu, glm; used by
// the CPU reference tracer engine/pathtrace) and as GLSL (the wavefront shaders): the PCG hash RNG, camera rays,
// the glTF metallic-roughness BSDF (evaluate / sample / pdf), light and environment sampling with their pdfs,
// MIS weights, Russian roulette and Beer-Lambert absorption. tests/conformance/pt_math checks that both
// compilations agree.
//
// Where we differ from IDKEngine (PathTracing/include/Shading.glsl, reference 2.1 and section 5): the original
// has no light sampling and no MIS (lights count only when a path happens to hit them), picks a lobe by a
// heuristic "chance" and bends the mirror direction toward the diffuse one by roughness^2 with weight = albedo.
// Here the BSDF is the glTF model proper: GGX microfacet reflection sampled by visible normals (Heitz 2018,
// "Sampling the GGX Distribution of Visible Normals") with the height-correlated Smith masking-shadowing term
// (Heitz 2014), exact dielectric Fresnel from the IOR (the glTF spec's Schlick approximation is kept for the
// metal's coloured Fresnel), Lambert diffuse weighted by (1 - F), rough refraction through GGX (Walter et al.
// 2007) for volumes and a mirrored reflection lobe for thin-walled transmission; every light is sampled by
// next-event estimation (lights chosen by power through an alias table, the environment by texel luminance)
// and combined with BSDF sampling by the power heuristic. Refraction transports radiance (the 1/eta^2 factor is
// applied). Material extensions (KHR_materials_specular, _clearcoat, _sheen) layer on the core model
// (pt_bsdf_frame.h), and GGX's multiple scattering is compensated from precomputed albedo tables (pt_energy.h).
//
// Files: pt_types.h (GPU structs, conventions), pt_common.h (RNG, helpers, camera ray, roulette, absorption),
// pt_microfacet.h (GGX, Fresnel), pt_sheen.h (Charlie sheen), pt_energy.h + pt_albedo_tables.h (energy
// compensation), pt_bsdf_frame.h (setup, layers), pt_bsdf.h (the lobes: ptEvalBsdf, ptSampleBsdf), pt_lights.h (alias tables,
// ptSampleLight, ptLightPdf, environment mapping, ptSampleEnvironment, ptEnvironmentPdf).
//
// Common-subset rules: no swizzles longer than one component, IDK_OUT/IDK_INOUT for out parameters, no arrays
// as parameters, no overloading, no recursion, float literals with f. Local frame: z = shading normal.
#ifndef IDK_PT_SAMPLING_H
#define IDK_PT_SAMPLING_H
#include "pt_common.h"
#include "pt_bsdf.h"
#include "pt_lights.h"
#include "pt_dispersion.h"
#endif
