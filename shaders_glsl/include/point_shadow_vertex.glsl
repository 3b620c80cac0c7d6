// point_shadow_vertex.glsl: the vertex stage shared by both rungs of the point-shadow pass (point_shadows/
// layered.vert writes gl_Layer = face from gl_InstanceIndex, point_shadows/face.vert takes the face from the push
// block): vertex pulling as in gbuffer.vert, then the cube-face projection of include/shadows.glsl. Both rungs
// run this same arithmetic, so their depth maps agree bit for bit. Ports IDKEngine's PointShadow vertex shader.
#ifndef IDK_POINT_SHADOW_VERTEX_GLSL
#define IDK_POINT_SHADOW_VERTEX_GLSL
#include "scene_buffers.glsl"
#include "shadows.glsl"

layout(push_constant, scalar) uniform Push { PointShadowPush p; };

layout(location = 0) out vec2 outUv;
layout(location = 1) out vec2 outUv1;
layout(location = 2) out float outAlpha;  // COLOR_0 alpha
layout(location = 3) flat out uint outDraw;

vec4 pointShadowVertex(uint face) {
    GpuInstance instance = InstanceBuffer(p.instances).data[gl_DrawID];
    GpuVertex v = VertexBuffer(p.vertices).data[gl_VertexIndex];
    vec3 world = (instance.model * vec4(v.position, 1.0)).xyz;
    outUv = v.uv0;
    outUv1 = p.uv1 != 0 ? Vec2Buffer(p.uv1).data[gl_VertexIndex] : vec2(0.0);
    outAlpha = p.colors != 0 ? Vec4Buffer(p.colors).data[gl_VertexIndex].a : 1.0;
    outDraw = gl_DrawID;
    return cubeFaceClip(world - p.lightPosition, face, pointShadowDepthCoefficients(p.nearPlane, p.farPlane));
}

#endif
