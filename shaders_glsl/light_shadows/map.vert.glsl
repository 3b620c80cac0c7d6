#version 460
// map.vert.glsl: one layer of a directional light's cascades or a spot light's single map: vertex pulling
// (include/shadow_caster.glsl) and the layer's orthographic or perspective projection from the push block.
// Ports IDKEngine's shadow-caster vertex path for the light types its point-shadow pass does not cover.
#extension GL_GOOGLE_include_directive : require
#define IDK_SHADOW_CASTER_VERTEX
#include "shadow_caster.glsl"
#include "shadow_types.h"

layout(push_constant, scalar) uniform Push { ShadowMapPush p; };

void main() {
    vec3 world = shadowCasterVertex(p.vertices, p.instances, p.colors, p.uv1);
    gl_Position = p.viewProjection * vec4(world, 1.0);
}
