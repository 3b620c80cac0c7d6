#version 460
// gbuffer.vert.glsl: vertex pulling for the multi-draw-indirect G-buffer pass: gl_DrawID selects the draw's
// GpuInstance (transform, mesh), gl_VertexIndex (index + the draw's baseVertex) the merged vertex.
// Ports IDKEngine's GBuffer/VertexPath/vertex.glsl (there: gl_BaseInstance + gl_InstanceID -> instance).
#extension GL_GOOGLE_include_directive : require
#include "scene_vertex.glsl"

layout(push_constant, scalar) uniform Push { GBufferPush p; };

void main() { emitSceneVertex(gl_DrawID, p.instances, p.vertices, p.colors, p.uv1, p.frame); }
