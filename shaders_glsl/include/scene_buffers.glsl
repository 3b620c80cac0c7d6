// scene_buffers.glsl: buffer-reference views of the GPU scene and the frame constants (shared/scene_types.h,
// shared/deferred_types.h). Addresses arrive in push constants as uint64_t; construct a view with e.g.
// VertexBuffer(push.vertices).data[i]. Replaces IDKEngine's fixed SSBO bindings 2, 3, 4, 5, 7 and UBOs 1, 2.
#ifndef IDK_SCENE_BUFFERS_GLSL
#define IDK_SCENE_BUFFERS_GLSL
#extension GL_EXT_buffer_reference : require
#include "interop.h"
#include "scene_types.h"
#include "deferred_types.h"

layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer VertexBuffer { GpuVertex data[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer InstanceBuffer { GpuInstance data[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer MeshBuffer { GpuMesh data[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer MaterialBuffer { GpuMaterial data[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer LightBuffer { GpuLight data[]; };
layout(buffer_reference, scalar, buffer_reference_align = 8) readonly buffer FrameBuffer { GpuFrame frame; };
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer Vec4Buffer { vec4 data[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer Vec2Buffer { vec2 data[]; };

#endif
