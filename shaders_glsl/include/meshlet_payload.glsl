// meshlet_payload.glsl: what a G-buffer task workgroup hands its mesh workgroups (gbuffer/gbuffer_mesh.*.glsl).
#ifndef IDK_MESHLET_PAYLOAD_GLSL
#define IDK_MESHLET_PAYLOAD_GLSL
#extension GL_EXT_buffer_reference : require
#include "meshlet_types.h"

struct MeshTaskPayload {
    uint instance;      // the GpuInstance all meshlets belong to
    int vertexOffset;   // the draw's vertexOffset (the mesh's baseVertex, or a deformed copy's)
    uint meshlets[kTaskGroupSize];  // surviving meshlets (GpuMeshlet indices), EmitMeshTasksEXT count of them
};

layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer Meshlets { GpuMeshlet data[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer MeshletWords { uint data[]; };

#endif
