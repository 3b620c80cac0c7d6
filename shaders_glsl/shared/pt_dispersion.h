// pt_dispersion.h: KHR_materials_dispersion in the path tracers (C++ and GLSL, see pt_sampling.h), written from the
// extension's specification. dispersion = 20 / V_d, the Abbe number V_d = (n_d - 1) / (n_F - n_C); the IOR at a
// wavelength lambda (nm) follows the specification's two-term Cauchy form through n_d = ior at 587.6 nm:
//   n(lambda) = max(ior + (ior - 1) / V_d * (523655 / lambda^2 - 1.5168), 1)
// The tracers render RGB, so a path that meets a dispersive surface (dispersion > 0 on a volume with transmission:
// the extension changes volumetric refraction only) picks one channel with a sampler dimension of its own
// (kPtDimDispersion, uniform over R, G, B) and from then on carries that channel alone, weighted 3 (the
// expectation over the three picks is the full RGB estimate); every dispersive surface the path meets later
// refracts at the same channel's IOR. Each channel stands for the Fraunhofer line the Abbe number is defined at:
// R = C (656.3 nm), G = d (587.6 nm), B = F (486.1 nm), so n_B - n_R = (ior - 1) / V_d (within 0.04%: the
// specification rounds its constants). The rasterizer's screen-space transmission (include/screen_transmission.glsl)
// refracts each channel at ptDispersionIor of its wavelength. The GPU tracer keeps the channel in GpuPtPath::flags
// (kPtPathChannel*).
#ifndef IDK_PT_DISPERSION_H
#define IDK_PT_DISPERSION_H
#include "pt_common.h"

IDK_GPU_BEGIN

IDK_CONST(uint, kPtNoChannel, 3u);  // the path still carries all three channels

// The wavelength (nm) a channel stands for.
IDK_INLINE float ptChannelWavelength(uint channel) {
    return channel == 0u ? 656.3f : (channel == 1u ? 587.6f : 486.1f);
}

// The IOR at a wavelength, from the IOR at 587.6 nm and the extension's dispersion (20 / V_d).
IDK_INLINE float ptDispersionIor(float ior, float dispersion, float lambda) {
    return max(ior + (ior - 1.0f) * (dispersion / 20.0f) * (523655.0f / (lambda * lambda) - 1.5168f), 1.0f);
}

// True when the surface refracts dispersively (the tracers then pick a channel).
IDK_INLINE bool ptIsDispersive(PtSurface s) {
    return s.dispersion > 0.0f && s.thickness > 0.0f && s.transmission > 0.0f && ptFinite(s.dispersion);
}

// The channel a uniform picks (R, G, B with probability 1/3 each).
IDK_INLINE uint ptPickChannel(float u) { return min(uint(u * 3.0f), 2u); }

// The throughput factor of carrying one channel: 3 in it, 0 in the others.
IDK_INLINE vec3 ptChannelWeight(uint channel) {
    return vec3(channel == 0u ? 3.0f : 0.0f, channel == 1u ? 3.0f : 0.0f, channel == 2u ? 3.0f : 0.0f);
}

// The surface as the path's channel sees it: the IOR at the channel's wavelength.
IDK_INLINE PtSurface ptDispersedSurface(PtSurface s, uint channel) {
    s.ior = ptDispersionIor(s.ior, s.dispersion, ptChannelWavelength(channel));
    return s;
}

IDK_GPU_END

#endif
