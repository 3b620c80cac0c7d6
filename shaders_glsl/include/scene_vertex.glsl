// scene_vertex.glsl: vertex pulling shared by the G-buffer and the forward transparency pass: the instance's
// transform applied to the merged vertex at gl_VertexIndex, optional colour and second UV streams, the varyings
// both fragment shaders read. The caller picks the instance (gl_DrawID or the sorted draw's firstInstance).
// Ports IDKEngine's GBuffer/VertexPath/vertex.glsl.
#ifndef IDK_SCENE_VERTEX_GLSL
#define IDK_SCENE_VERTEX_GLSL
#include "scene_buffers.glsl"

layout(location = 0) out vec3 outWorldPosition;
layout(location = 1) out vec3 outNormal;
layout(location = 2) out vec4 outTangent;
layout(location = 3) out vec2 outUv;
layout(location = 4) flat out uint outInstance;  // index into the instance buffer
layout(location = 5) out vec4 outColor;
layout(location = 6) out vec2 outUv1;

// colors / uv1: 0 when the scene has no such stream.
void emitSceneVertex(uint instanceIndex, uint64_t instances, uint64_t vertices, uint64_t colors, uint64_t uv1,
                     uint64_t frame) {
    GpuInstance instance = InstanceBuffer(instances).data[instanceIndex];
    GpuVertex v = VertexBuffer(vertices).data[gl_VertexIndex];
    vec4 world = instance.model * vec4(v.position, 1.0);
    outWorldPosition = world.xyz;
    outNormal = instance.normalMatrix * v.normal;
    outTangent = vec4(mat3(instance.model) * v.tangent.xyz, v.tangent.w);
    outUv = v.uv0;
    outInstance = instanceIndex;
    outColor = colors != 0 ? Vec4Buffer(colors).data[gl_VertexIndex] : vec4(1.0);
    outUv1 = uv1 != 0 ? Vec2Buffer(uv1).data[gl_VertexIndex] : vec2(0.0);
    gl_Position = FrameBuffer(frame).frame.viewProjection * world;
}

#endif
