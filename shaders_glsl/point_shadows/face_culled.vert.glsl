#version 460
// face_culled.vert.glsl: point-shadow faces drawn from GPU-culled commands (passes/cull_shadows.cpp): one
// vkCmdDrawIndexedIndirectCount per face into a single-face view, the face in the push block; the compacted
// commands' firstInstance names the instance (gl_DrawID is only the command's slot). Same arithmetic as
// face.vert and layered.vert, so culled and unculled cubes agree bit for bit.
#extension GL_GOOGLE_include_directive : require
#define IDK_SHADOW_CASTER_CULLED
#include "point_shadow_vertex.glsl"

void main() { gl_Position = pointShadowVertex(p.face); }
