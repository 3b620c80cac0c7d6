// skinning_types.h: what the skinning compute pass reads (engine/render/gpu_animation.cpp packs it): one job per
// deformed (node, primitive) pair, per-vertex joint influences, morph-target deltas, and the push block with the
// per-frame pose (joint matrices, morph weights) by device address. Ports IDKEngine's Skinning/compute.glsl
// inputs (SSBOs 15 joint matrices, 16 unskinned vertices), plus the morph targets IDKEngine rejects.
#ifndef IDK_SKINNING_TYPES_H
#define IDK_SKINNING_TYPES_H
#include "interop.h"

IDK_GPU_BEGIN

IDK_CONST(uint, kSkinningGroupSize, 64);  // invocations per workgroup (IDKEngine: 64), one vertex each
IDK_CONST(uint, kDeformNone, 0xFFFFFFFFu);

IDK_CONST(uint, kMorphPositions, 1u);  // GpuDeformJob::morphAttributes: which delta arrays each target has
IDK_CONST(uint, kMorphNormals, 2u);
IDK_CONST(uint, kMorphTangents, 4u);

// One deformed (node, primitive): vertices [srcVertex, srcVertex + vertexCount) of the merged vertex buffer in
// their rest pose become [dstVertex, ...) = skin * (rest + sum_t weight_t * delta_t), in the node's space.
struct GpuDeformJob {
    uint srcVertex;        // rest-pose vertices (GpuVertex index)
    uint dstVertex;        // the deformed copy that the job's draws use as baseVertex
    uint vertexCount;
    uint firstThread;      // sum of vertexCount over earlier jobs: thread -> job by binary search
    uint influences;       // first GpuSkinInfluence of the primitive; kDeformNone: not skinned
    uint firstJoint;       // first joint matrix of the node in the pose's joint array
    uint jointCount;       // the skin's joints (influence indices are < jointCount)
    uint deltas;           // first vec3 of the primitive's morph deltas; kDeformNone: no morph targets
    uint targetCount;
    uint morphAttributes;  // kMorph* bits: delta arrays per target, laid out [target][attribute][vertex]
    uint firstWeight;      // first morph weight of the node in the pose's weight array
};
IDK_GPU_SIZE(GpuDeformJob, 44);

// JOINTS_0 / WEIGHTS_0 of one vertex: four joint indices (< kMaxJoints = 256) packed in bytes, x lowest.
struct GpuSkinInfluence {
    uint joints;
    vec4 weights;
};
IDK_GPU_SIZE(GpuSkinInfluence, 20);

// skinning.comp: every address is a scalar-layout array; `vertices` is read at srcVertex and written at dstVertex.
struct SkinningPush {
    DeviceAddress vertices;       // GpuVertex[] (the scene's merged vertex buffer)
    DeviceAddress jobs;           // GpuDeformJob[jobCount], sorted by firstThread
    DeviceAddress influences;     // GpuSkinInfluence[] (0 when nothing is skinned)
    DeviceAddress deltas;         // vec3[] (0 when nothing is morphed)
    DeviceAddress jointMatrices;  // mat4x3[] of this frame's pose (0 when nothing is skinned)
    DeviceAddress weights;        // float[] of this frame's pose (0 when nothing is morphed)
    uint jobCount;
    uint threadCount;             // sum of vertexCount over all jobs
};
IDK_GPU_SIZE(SkinningPush, 56);

IDK_GPU_END
#endif
