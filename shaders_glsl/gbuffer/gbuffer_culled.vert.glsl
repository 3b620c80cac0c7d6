#version 460
// gbuffer_culled.vert.glsl: the G-buffer's vertex pulling for the commands the culling pass compacted
// (culling/cull_instances.comp.glsl): each command's firstInstance (gl_InstanceIndex) names the instance it places,
// as gl_DrawID no longer does. Ports IDKEngine's GBuffer/VertexPath/vertex.glsl (there:
// visibleMeshInstanceIds[gl_BaseInstance + gl_InstanceID]).
#extension GL_GOOGLE_include_directive : require
#include "scene_vertex.glsl"

layout(push_constant, scalar) uniform Push { GBufferPush p; };

void main() { emitSceneVertex(uint(gl_InstanceIndex), p.instances, p.vertices, p.colors, p.uv1, p.frame); }
