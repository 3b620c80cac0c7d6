#version 460
// forward.vert.glsl: vertex pulling for the transparency pass's back-to-front indirect draw: each sorted command's
// firstInstance names the GpuInstance it draws (gl_DrawID is the sorted position). Otherwise as gbuffer.vert.
// Ports IDKEngine's RecordTransparent vertex stage (reference 2.14; gl_BaseInstance selects the mesh there too).
#extension GL_GOOGLE_include_directive : require
#include "scene_vertex.glsl"
#include "shadow_types.h"

layout(push_constant, scalar) uniform Push { TransparencyPush p; };

void main() { emitSceneVertex(uint(gl_InstanceIndex), p.instances, p.vertices, p.colors, p.uv1, p.frame); }
