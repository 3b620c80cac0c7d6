#version 460
// gbuffer_ids.frag.glsl: the G-buffer fragment shader that also writes each kept fragment's draw and triangle
// (an ID buffer: the ground truth of which draws and triangles are visible, for culling benchmarks and tests).
// Only on the vertex path (gl_PrimitiveID counts the draw's triangles there).
#extension GL_GOOGLE_include_directive : require
#define GBUFFER_IDS
#include "gbuffer_fragment.glsl"
