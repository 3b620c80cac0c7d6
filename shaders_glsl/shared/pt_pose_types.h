// pt_pose_types.h: the push block of pathtrace/pose.comp.glsl (engine/render/pt_pose.cpp records it): one range of
// posed vertices, as the rasterizer's skinning pass wrote them into the merged GpuVertex buffer, copied into a
// GPU-posed path-tracing geometry (its GpuPtVertex shading array and its BLAS's packed positions).
#ifndef IDK_PT_POSE_TYPES_H
#define IDK_PT_POSE_TYPES_H
#include "interop.h"

IDK_GPU_BEGIN

IDK_CONST(uint, kPtPoseGroupSize, 64);

struct PtPosePush {
    DeviceAddress source;     // GpuVertex[]: the scene's merged vertex buffer (node space, after skinning)
    DeviceAddress vertices;   // GpuPtVertex[] of the geometry
    DeviceAddress positions;  // vec3[] of the geometry's BLAS (GpuBlas::positionBuffer)
    uint sourceFirst;         // first GpuVertex of the range (the deformed copy's baseVertex)
    uint destFirst;           // first vertex of the primitive in the geometry
    uint count;
    uint pad;
};
IDK_GPU_SIZE(PtPosePush, 40);

IDK_GPU_END
#endif
