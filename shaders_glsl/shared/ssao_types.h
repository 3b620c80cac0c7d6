// ssao_types.h: push block of the screen-space ambient occlusion pass (shaders_glsl/ssao/ssao.comp). Ports the
// uniforms of IDKEngine's SSAO/compute.glsl.
#ifndef IDK_SSAO_TYPES_H
#define IDK_SSAO_TYPES_H
#include "interop.h"

IDK_GPU_BEGIN

struct SsaoPush {
    DeviceAddress frame;  // GpuFrame (matrices of this frame, jittered with TAA: the G-buffer's)
    uint depth;           // R32F storage: G-buffer depth
    uint normal;          // R32UI storage: G-buffer octahedral normal
    uint target;          // R32F storage: visibility (1 = unoccluded) of the ambient light
    uint samples;         // rays per pixel
    float radius;         // world-space length of the rays (occluders farther away do not count)
    uint frameIndex;      // varies the noise per frame so TAA averages it
};
IDK_GPU_SIZE(SsaoPush, 32);

IDK_CONST(uint, kSsaoGroupSize, 8);
IDK_CONST(uint, kSsaoSteps, 4);  // depth-buffer tests along each ray

IDK_GPU_END
#endif
