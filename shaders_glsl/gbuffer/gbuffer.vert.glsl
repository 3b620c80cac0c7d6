#version 460
// gbuffer.vert.glsl: vertex pulling for the multi-draw-indirect G-buffer pass: gl_DrawID selects the draw's
// GpuInstance (transform, mesh), gl_VertexIndex (index + the draw's baseVertex) the merged vertex.
// Ports IDKEngine's GBuffer/VertexPath/vertex.glsl (there: gl_BaseInstance + gl_InstanceID -> instance).
#extension GL_GOOGLE_include_directive : require
#include "scene_buffers.glsl"

layout(push_constant, scalar) uniform Push { GBufferPush p; };

layout(location = 0) out vec3 outWorldPosition;
layout(location = 1) out vec3 outNormal;
layout(location = 2) out vec4 outTangent;
layout(location = 3) out vec2 outUv;
layout(location = 4) flat out uint outDraw;
layout(location = 5) out vec4 outColor;
layout(location = 6) out vec2 outUv1;

void main() {
    GpuInstance instance = InstanceBuffer(p.instances).data[gl_DrawID];
    GpuVertex v = VertexBuffer(p.vertices).data[gl_VertexIndex];
    vec4 world = instance.model * vec4(v.position, 1.0);
    outWorldPosition = world.xyz;
    outNormal = instance.normalMatrix * v.normal;
    outTangent = vec4(mat3(instance.model) * v.tangent.xyz, v.tangent.w);
    outUv = v.uv0;
    outDraw = gl_DrawID;
    outColor = p.colors != 0 ? Vec4Buffer(p.colors).data[gl_VertexIndex] : vec4(1.0);
    outUv1 = p.uv1 != 0 ? Vec2Buffer(p.uv1).data[gl_VertexIndex] : vec2(0.0);
    gl_Position = FrameBuffer(p.frame).frame.viewProjection * world;
}
