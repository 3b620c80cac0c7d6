// pt_diffuse_transmission.h: the KHR_materials_diffuse_transmission lobe (C++ and GLSL, see pt_sampling.h),
// written from the extension's specification. Its reference BSDF replaces the dielectric's diffuse base by
//   mix(diffuse_brdf(baseColor), diffuse_btdf(diffuseTransmissionColor), diffuseTransmission)
// beneath the same Fresnel layer (fresnel_mix with the specular BRDF), where diffuse_btdf is Lambert's 1/pi on the
// hemisphere opposite wo. So the diffuse reflection keeps 1 - diffuseTransmission of its weight and the transmitted
// lobe is diffuseTransmission * diffuseTransmissionColor / pi * |cos(wi)| times what passes the Fresnel layer:
// the Lambert lobes' albedo-scaled weight (1 - Es(mu_o)) (1 - Es(|mu_i|)) / (1 - Es_avg) of pt_bsdf_frame.h, so
// a white transmitting surface passes exactly the energy its Lambert reflection would: reflected + transmitted
// albedo is the factor-0 material's albedo (the white furnace of tests/unit/pathtrace/diffuse_transmission_test.cpp).
// The lobe is cosine-sampled on the far hemisphere; pt_bsdf.h calls these hooks and adds the lobe to its one-sample
// MIS. Thick (volume) materials: the transmitted direction enters the volume like the specular transmission, and
// both tracers start the medium for it.
#ifndef IDK_PT_DIFFUSE_TRANSMISSION_H
#define IDK_PT_DIFFUSE_TRANSMISSION_H
#include "pt_common.h"

IDK_GPU_BEGIN

// The sanitised factor (0 when absent or invalid) and colour (each channel in [0, 1]).
IDK_INLINE float ptDiffTransFactor(PtSurface s) { return ptSaturate(s.diffuseTransmission); }
IDK_INLINE vec3 ptDiffTransColor(PtSurface s) {
    return vec3(ptSaturate(s.diffuseTransmissionColor.x), ptSaturate(s.diffuseTransmissionColor.y),
                ptSaturate(s.diffuseTransmissionColor.z));
}

// The transmitted lobe's f * |cos| for a local wi below the surface (wi.z < 0). weight: (1 - metallic)
// (1 - transmission) diffuseTransmission times the layer weight of clearcoat and sheen; pass: what the dielectric
// layer lets through (the albedo-scaled weight at |cos wi|).
IDK_INLINE vec3 ptDiffTransValue(vec3 color, float weight, float pass, vec3 wi) {
    return color * (weight * pass * kPtInvPi * (-wi.z));
}

// The cosine density of the lobe on the far hemisphere.
IDK_INLINE float ptDiffTransPdf(vec3 wi) { return max(-wi.z, 0.0f) * kPtInvPi; }

// wi mirrored through the surface (the lobe is sampled as a cosine lobe above, then mirrored).
IDK_INLINE vec3 ptDiffTransMirror(vec3 wi) { return vec3(wi.x, wi.y, -wi.z); }

IDK_GPU_END

#endif
