#version 460
// face.vert.glsl: the fallback rung of "point-shadow cube faces": one multi-draw-indirect per face into a
// single-layer view of that face, the face index in the push block (no gl_Layer, so no shaderOutputLayer).
// Ports IDKEngine's six-draw point-shadow path (reference readme "Point Shadows" 1.0).
#extension GL_GOOGLE_include_directive : require
#include "point_shadow_vertex.glsl"

void main() { gl_Position = pointShadowVertex(p.face); }
