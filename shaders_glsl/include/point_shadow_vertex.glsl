// point_shadow_vertex.glsl: the vertex stage shared by both rungs of the point-shadow pass (point_shadows/
// layered.vert writes gl_Layer = face from gl_InstanceIndex, point_shadows/face.vert takes the face from the push
// block): vertex pulling (include/shadow_caster.glsl), then the cube-face projection of include/shadows.glsl. Both
// rungs run this same arithmetic, so their depth maps agree bit for bit. Ports IDKEngine's PointShadow vertex shader.
#ifndef IDK_POINT_SHADOW_VERTEX_GLSL
#define IDK_POINT_SHADOW_VERTEX_GLSL
#define IDK_SHADOW_CASTER_VERTEX
#include "shadow_caster.glsl"
#include "shadows.glsl"

layout(push_constant, scalar) uniform Push { PointShadowPush p; };

vec4 pointShadowVertex(uint face) {
    vec3 world = shadowCasterVertex(p.vertices, p.instances, p.colors, p.uv1);
    return cubeFaceClip(world - p.lightPosition, face, pointShadowDepthCoefficients(p.nearPlane, p.farPlane));
}

#endif
