#version 460
// layered.vert.glsl: the native rung of "point-shadow cube faces": each indirect draw has instanceCount 6 and
// instance i renders face i, selected by writing gl_Layer from the vertex shader (shaderOutputLayer), so one
// instanced multi-draw-indirect fills all six faces. Ports IDKEngine's PointShadow/VertexPath (gl_Layer path).
#extension GL_GOOGLE_include_directive : require
#extension GL_ARB_shader_viewport_layer_array : require
#include "point_shadow_vertex.glsl"

void main() {
    uint face = uint(gl_InstanceIndex);  // firstInstance is 0
    gl_Layer = int(face);
    gl_Position = pointShadowVertex(face);
}
