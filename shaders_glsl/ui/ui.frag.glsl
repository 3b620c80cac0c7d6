#version 460
// ui.frag.glsl: vertex colour times the draw's texture (the font atlas), alpha-blended by the pipeline. Values
// stay display-encoded: ImGui's colours are sRGB and the UI is drawn into the UNORM swapchain image, which
// already holds the tonemapped, sRGB-encoded frame.
#extension GL_GOOGLE_include_directive : require
#include "interop.h"
#include "bindless.glsl"
#include "ui_types.h"

layout(push_constant, scalar) uniform Push { UiPush p; };

layout(location = 0) in vec2 inUv;
layout(location = 1) in vec4 inColor;
layout(location = 0) out vec4 outColor;

void main() {
    outColor = inColor * IDK_SAMPLE_2D(p.textureIndex, p.samplerIndex, inUv);
}
