#version 460
// forward.vert.glsl: vertex pulling for the transparency pass's back-to-front indirect draw: each sorted command's
// firstInstance names the GpuInstance it draws (gl_DrawID is the sorted position). Otherwise as gbuffer.vert.
// Ports IDKEngine's RecordTransparent vertex stage (reference 2.14; gl_BaseInstance selects the mesh there too).
#extension GL_GOOGLE_include_directive : require
#include "scene_buffers.glsl"
#include "shadow_types.h"

layout(push_constant, scalar) uniform Push { TransparencyPush p; };

layout(location = 0) out vec3 outWorldPosition;
layout(location = 1) out vec3 outNormal;
layout(location = 2) out vec4 outTangent;
layout(location = 3) out vec2 outUv;
layout(location = 4) flat out uint outInstance;
layout(location = 5) out vec4 outColor;
layout(location = 6) out vec2 outUv1;

void main() {
    uint index = uint(gl_InstanceIndex);
    GpuInstance instance = InstanceBuffer(p.instances).data[index];
    GpuVertex v = VertexBuffer(p.vertices).data[gl_VertexIndex];
    vec4 world = instance.model * vec4(v.position, 1.0);
    outWorldPosition = world.xyz;
    outNormal = instance.normalMatrix * v.normal;
    outTangent = vec4(mat3(instance.model) * v.tangent.xyz, v.tangent.w);
    outUv = v.uv0;
    outInstance = index;
    outColor = p.colors != 0 ? Vec4Buffer(p.colors).data[gl_VertexIndex] : vec4(1.0);
    outUv1 = p.uv1 != 0 ? Vec2Buffer(p.uv1).data[gl_VertexIndex] : vec2(0.0);
    gl_Position = FrameBuffer(p.frame).frame.viewProjection * world;
}
