#version 460
// motion_vectors.vert.glsl: the G-buffer's vertex pulling (gl_DrawID -> instance, gl_VertexIndex -> merged vertex)
// with this frame's and last frame's instance transforms and vertex positions (skinned and morphed copies are
// rewritten in place each animated frame, so last frame's copy is a history buffer). Ports the velocity part of
// IDKEngine's GBuffer/VertexPath/vertex.glsl (previous model matrix + previous skinned position).
#extension GL_GOOGLE_include_directive : require
#include "scene_buffers.glsl"
#include "temporal_types.h"

layout(buffer_reference, scalar, buffer_reference_align = 8) readonly buffer TemporalBuffer { GpuTemporalFrame t; };
layout(push_constant, scalar) uniform Push { MotionPush p; };

layout(location = 0) out vec4 outCurrent;   // unjittered clip position this frame
layout(location = 1) out vec4 outPrevious;  // clip position last frame

void main() {
    GpuTemporalFrame t = TemporalBuffer(p.temporal).t;
    GpuInstance instance = InstanceBuffer(p.instances).data[gl_DrawID];
    GpuInstance prevInstance = InstanceBuffer(p.prevInstances).data[gl_DrawID];
    vec3 position = VertexBuffer(p.vertices).data[gl_VertexIndex].position;
    vec3 prevPosition = VertexBuffer(p.prevVertices).data[gl_VertexIndex].position;
    vec4 world = instance.model * vec4(position, 1.0);
    outCurrent = t.unjittered * world;
    outPrevious = t.previous * (prevInstance.model * vec4(prevPosition, 1.0));
    gl_Position = t.viewProjection * world;  // the G-buffer's jittered position: the same rasterized depth
}
