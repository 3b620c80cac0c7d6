#version 460
// ui.vert.glsl: Dear ImGui vertices pulled from this frame's vertex stream (index = gl_VertexIndex, which
// already includes the draw's vertexOffset) and mapped from pixels to clip space. Replaces IDKEngine's
// ImGui backend shader (ImGuiBackend.cs); drawn by the engine's own UI pass.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_buffer_reference : require
#include "interop.h"
#include "ui_types.h"

layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer UiVertexBuffer { UiVertex data[]; };
layout(push_constant, scalar) uniform Push { UiPush p; };

layout(location = 0) out vec2 outUv;
layout(location = 1) out vec4 outColor;

void main() {
    UiVertex v = UiVertexBuffer(p.vertices).data[gl_VertexIndex];
    outUv = v.uv;
    outColor = unpackUnorm4x8(v.color);
    gl_Position = vec4(v.position * p.scale + p.translate, 0.0, 1.0);
}
