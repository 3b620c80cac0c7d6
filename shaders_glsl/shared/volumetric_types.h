// volumetric_types.h: volumetric lighting (engine/frame/volumetrics_feature.cpp, passes/volumetrics.cpp): the push
// block of the reduced-resolution ray march and of the depth-aware upsample that composites it. Ports the inputs
// of IDKEngine's VolumetricLight/compute.glsl and VolumetricLight/Upscale/compute.glsl (reference 1.5 step 8).
#ifndef IDK_VOLUMETRIC_TYPES_H
#define IDK_VOLUMETRIC_TYPES_H
#include "interop.h"

IDK_GPU_BEGIN

IDK_CONST(uint, kVolumetricGroupSize, 8u);

struct VolumetricPush {
    DeviceAddress frame;    // GpuFrame
    DeviceAddress shadows;  // the shadow table (GpuPointShadow[lightCount] + records) or 0
    uint depth;             // R32F storage image: the full-resolution G-buffer depth
    uint lowRes;            // RGBA16F storage image: in-scattered radiance (rgb) and transmittance (a) per block
    uint target;            // upsample: the HDR image, composited in place as target * a + rgb
    uint scale;             // full-resolution pixels per low-resolution sample along each axis (2 or 4)
    uint steps;             // midpoint steps along each view ray
    float scattering;       // sigma_s, per metre
    float extinction;       // sigma_t = sigma_s + absorption, per metre
    float anisotropy;       // Henyey-Greenstein g
    float maxDistance;      // march length of background (sky) pixels
    uint pad;
};
IDK_GPU_SIZE(VolumetricPush, 56);

IDK_GPU_END
#endif
